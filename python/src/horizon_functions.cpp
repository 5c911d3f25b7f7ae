// skyview.svf and skyview.horizon: `skyview svf` and `skyview horizon` on a NumPy array, with the
// same options under the same names (without their dashes) and the same defaults.
#include <cmath>
#include <limits>

#include "arrays.h"
#include "bindings.h"
#include "horizon_keywords.h"
#include "progress_callback.h"
#include "skyview/core/error.h"

#include "skyview/sky_view/horizon_bands.h"
#include "skyview/sky_view/svf_run.h"

namespace skyview::python {

namespace {

// "svf,sky_visibility" or ["svf", "sky_visibility"].
std::string product_list(const py::object& products) {
  if (py::isinstance<py::str>(products)) return products.cast<std::string>();
  std::string list;
  for (const py::handle& p : products) list += (list.empty() ? "" : ",") + py::str(p).cast<std::string>();
  return list;
}

py::dict svf(const py::object& z, const ArrayGeoreference& where, const HorizonKeywords& k, const py::object& products,
             std::optional<int> check_cells, int threads, const py::object& progress) {
  std::vector<std::string> warnings;
  SvfRequest request;
  apply(request.horizon, k);
  if (!products.is_none()) request.products = product_list(products);
  if (check_cells) request.check_cells = *check_cells;
  // The options first, as the command line checks them before it reads the input.
  parse_svf_products(request.products);
  check_svf_request(request);
  HorizonSetup setup = plan_horizon(request.horizon);
  const Terrain terrain = terrain_from_array(z, where, warnings);
  fit_horizon(setup, request.horizon, terrain);
  SvfResult result;
  run_with_progress(progress, [&](ProgressCounter& counter) {
    const ThreadLimit limit(threads);
    counter.set_total(static_cast<std::uint64_t>(terrain.width()) * terrain.height());
    result =
        run_svf(terrain, request, setup, [&](const std::function<void(ProgressCounter&)>& work) { work(counter); });
  });
  warnings.insert(warnings.end(), setup.warnings.begin(), setup.warnings.end());
  warnings.insert(warnings.end(), result.warnings.begin(), result.warnings.end());
  warn_all(warnings);
  py::dict bands;
  for (SvfBand& b : result.bands) {
    bands[py::str(b.name)] = to_numpy(std::move(b.values.values()), {terrain.height(), terrain.width()});
  }
  return bands;
}

py::tuple horizon(const py::object& z, const ArrayGeoreference& where, const HorizonKeywords& k, int threads,
                  const py::object& callback) {
  std::vector<std::string> warnings;
  HorizonRequest request;
  apply(request, k);
  request.params.rays = 0;  // the ray cast's Monte-Carlo svf is not a horizon band
  HorizonSetup setup = plan_horizon(request);
  const Terrain terrain = terrain_from_array(z, where, warnings);
  fit_horizon(setup, request, terrain);
  const int w = terrain.width(), h = terrain.height(), n = setup.engine->params().directions;
  const Window whole = Window::whole(terrain);
  const std::size_t cells = static_cast<std::size_t>(whole.cells());
  std::vector<float> angles(cells * static_cast<std::size_t>(n));
  run_with_progress(callback, [&](ProgressCounter& progress) {
    const ThreadLimit limit(threads);
    std::int64_t edge_cells = 0;
    const std::vector<unsigned char> blank = horizon_blank_cells(setup, terrain, Window::whole(terrain), edge_cells);
    // Rows [row0, row0 + rows) of direction k in degrees, nodata where the command line writes it.
    auto take_rows = [&](int k, int row0, int rows, const float* radians) {
      const std::size_t first = static_cast<std::size_t>(row0) * w, count = static_cast<std::size_t>(rows) * w;
      float* out = angles.data() + cells * static_cast<std::size_t>(k) + first;
      for (std::size_t i = 0; i < count; ++i) {
        out[i] =
            blank[first + i] ? std::numeric_limits<float>::quiet_NaN() : static_cast<float>(radians[i] * 180.0 / M_PI);
      }
    };
    progress.set_total(cells);
    if (setup.engine->streams_directions()) {
      HorizonField rest;
      setup.engine->compute_directions(terrain, whole, rest, progress,
                                       [&](int first, int count, const float* upper, const float*) {
                                         for (int j = 0; j < count; ++j)
                                           take_rows(first + j, 0, h, upper + cells * static_cast<std::size_t>(j));
                                       });
    } else {
      compute_by_row_blocks(*setup.engine, terrain, whole, progress, kHorizonBlockBytes, 1,
                            [&](const Window& block, HorizonField& field) {
                              for (int k = 0; k < n; ++k) take_rows(k, block.row0, block.rows, field.upper_plane(k));
                            });
    }
  });
  warnings.insert(warnings.end(), setup.warnings.begin(), setup.warnings.end());
  warn_all(warnings);
  std::vector<double> azimuths;
  for (const DirectionBand& d : direction_bands(setup)) azimuths.push_back(std::stod(d.azimuth_deg));
  return py::make_tuple(to_numpy(std::move(angles), {n, h, w}), py::array_t<double>(azimuths.size(), azimuths.data()));
}

ArrayGeoreference georeference(std::optional<double> cell_size, std::optional<std::vector<double>> transform,
                               std::optional<std::string> crs, std::optional<double> nodata,
                               std::optional<double> z_scale, std::optional<std::array<int, 4>> tile,
                               std::optional<std::array<double, 2>> height_range = std::nullopt) {
  return {cell_size, std::move(transform), std::move(crs), nodata, z_scale, tile, height_range};
}

// The bands svf() returns for these options, in order.
std::vector<std::string> svf_band_names(const py::object& products, std::optional<std::string> method,
                                        std::optional<int> rays) {
  SvfRequest request;
  std::vector<std::string> names;
  for (const SvfProductInfo* p : parse_svf_products(products.is_none() ? request.products : product_list(products)))
    names.push_back(p->name);
  // The ray cast's Monte-Carlo svf and its standard error follow (SvfResult::bands).
  if (method.value_or(request.horizon.method) == "raycast" && rays.value_or(request.horizon.params.rays) > 0) {
    names.push_back("svf_montecarlo");
    names.push_back("svf_montecarlo_stderr");
  }
  return names;
}

// halo_cells for a raster of rows x cols, from its ground frame at the nine cells halo_cells
// samples (corners, edge middles, centre), without its heights.
int raster_halo_cells(int rows, int cols, double radius, std::optional<double> cell_size,
                      std::optional<std::vector<double>> transform, std::optional<std::string> crs) {
  if (rows < 1 || cols < 1) throw UsageError("the raster is empty");
  if (!(std::isfinite(radius) && radius > 0)) throw UsageError("radius must be a positive number");
  std::vector<std::string> ignored;
  py::array_t<float> flat({2, 2});
  std::fill(flat.mutable_data(), flat.mutable_data() + flat.size(), 0.0f);
  const std::array<int, 4> tile{0, 0, std::max(cols, 2), std::max(rows, 2)};
  const Terrain probe = terrain_from_array(
      flat, georeference(cell_size, std::move(transform), std::move(crs), std::nullopt, std::nullopt, tile), ignored);
  int halo = 0;
  for (int r : {0, rows / 2, rows - 1}) {
    for (int c : {0, cols / 2, cols - 1}) {
      Terrain at = probe;
      at.heights = Grid<float>(1, 1);
      at.origin_col = c;
      at.origin_row = r;
      halo = std::max(halo, halo_cells(at, radius));
    }
  }
  return halo;
}

}  // namespace

constexpr const char* kSvfDoc = R"(
Sky-view factor and friends of a height array, as ``skyview svf`` computes them.

z: 2-D array of heights (rows, cols; any real dtype; NaN or ``nodata`` marks nodata).
cell_size: square cells of this many metres, north up; or transform: the GDAL/rasterio affine
(6 numbers, GDAL order; rasterio's ``Affine.to_gdal()``) with crs (any string GDAL/PROJ reads),
so that geographic rasters get true ground distances. Every other keyword is the command line's
option of the same name; None keeps its default (sweep, 16 directions, unlimited radius, sectors
from grid north, bands svf, svf_surface, sky_visibility, openness_positive, openness_negative).
Returns {band name: float32 array}, NaN on nodata, equal to the GeoTIFF's bands.)";

constexpr const char* kHorizonDoc = R"(
Horizon angles of a height array, as ``skyview horizon`` computes them: angles is a float32 array
(directions, rows, cols) in degrees above the horizontal (NaN where the command line writes
nodata), azimuths the centre azimuth of each direction in degrees clockwise from north.
Keywords as for :func:`svf` (sectors from true north by default, as on the command line).)";

void bind_horizon_functions(py::module_& m) {
  using namespace pybind11::literals;
  m.def(
      "svf",
      [](const py::object& z, std::optional<double> cell_size, std::optional<std::vector<double>> transform,
         std::optional<std::string> crs, std::optional<int> directions, std::optional<std::string> method,
         std::optional<double> radius, std::optional<int> samples, const py::object& products,
         std::optional<double> nodata, std::optional<double> max_error, std::optional<int> far_lines,
         std::optional<int> rays, std::optional<std::uint64_t> seed, std::optional<std::string> edge,
         std::optional<std::string> curvature, std::optional<double> refraction,
         std::optional<std::string> azimuth_origin, std::optional<std::string> azimuths, bool early_exit,
         std::optional<int> check_cells, std::optional<double> z_scale, int threads,
         std::optional<std::array<int, 4>> tile, std::optional<std::array<double, 2>> height_range,
         const py::object& progress) {
        const HorizonKeywords k{method,    directions, samples, far_lines, rays,           radius,   refraction,
                                max_error, seed,       edge,    curvature, azimuth_origin, azimuths, early_exit};
        return svf(z,
                   georeference(cell_size, std::move(transform), std::move(crs), nodata, z_scale, tile, height_range),
                   k, products, check_cells, threads, progress);
      },
      kSvfDoc, "z"_a, py::kw_only(), "cell_size"_a = py::none(), "transform"_a = py::none(), "crs"_a = py::none(),
      "directions"_a = py::none(), "method"_a = py::none(), "radius"_a = py::none(), "samples"_a = py::none(),
      "products"_a = py::none(), "nodata"_a = py::none(), "max_error"_a = py::none(), "far_lines"_a = py::none(),
      "rays"_a = py::none(), "seed"_a = py::none(), "edge"_a = py::none(), "curvature"_a = py::none(),
      "refraction"_a = py::none(), "azimuth_origin"_a = py::none(), "azimuths"_a = py::none(), "early_exit"_a = true,
      "check_cells"_a = py::none(), "z_scale"_a = py::none(), "threads"_a = 0, "_tile"_a = py::none(),
      "_height_range"_a = py::none(), "progress"_a = py::none());
  m.def(
      "horizon",
      [](const py::object& z, std::optional<double> cell_size, std::optional<std::vector<double>> transform,
         std::optional<std::string> crs, std::optional<int> directions, std::optional<std::string> method,
         std::optional<double> radius, std::optional<int> samples, std::optional<double> nodata,
         std::optional<double> max_error, std::optional<int> far_lines, std::optional<std::uint64_t> seed,
         std::optional<std::string> edge, std::optional<std::string> curvature, std::optional<double> refraction,
         std::optional<std::string> azimuth_origin, std::optional<std::string> azimuths, bool early_exit,
         std::optional<double> z_scale, int threads, std::optional<std::array<int, 4>> tile,
         std::optional<std::array<double, 2>> height_range, const py::object& progress) {
        const HorizonKeywords k{method,    directions, samples, far_lines, std::nullopt,   radius,   refraction,
                                max_error, seed,       edge,    curvature, azimuth_origin, azimuths, early_exit};
        return horizon(
            z, georeference(cell_size, std::move(transform), std::move(crs), nodata, z_scale, tile, height_range), k,
            threads, progress);
      },
      kHorizonDoc, "z"_a, py::kw_only(), "cell_size"_a = py::none(), "transform"_a = py::none(), "crs"_a = py::none(),
      "directions"_a = py::none(), "method"_a = py::none(), "radius"_a = py::none(), "samples"_a = py::none(),
      "nodata"_a = py::none(), "max_error"_a = py::none(), "far_lines"_a = py::none(), "seed"_a = py::none(),
      "edge"_a = py::none(), "curvature"_a = py::none(), "refraction"_a = py::none(), "azimuth_origin"_a = py::none(),
      "azimuths"_a = py::none(), "early_exit"_a = true, "z_scale"_a = py::none(), "threads"_a = 0,
      "_tile"_a = py::none(), "_height_range"_a = py::none(), "progress"_a = py::none());
  m.def("_svf_band_names", svf_band_names, "products"_a, "method"_a, "rays"_a);
  m.def("_halo_cells", raster_halo_cells, "rows"_a, "cols"_a, "radius"_a, "cell_size"_a, "transform"_a, "crs"_a);
}

}  // namespace skyview::python
