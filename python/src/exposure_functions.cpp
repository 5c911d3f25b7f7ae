// skyview.exposure: `skyview exposure` on a NumPy array. The sky, the site checks, the albedo and
// the metadata come from the library's exposure job (exposure_job.h), as on the command line; the
// package (skyview/__init__.py) names the keywords and passes them here as a dict.
#include "arrays.h"
#include "bindings.h"
#include "horizon_keywords.h"
#include "progress_callback.h"
#include "skyview/core/error.h"
#include "skyview/core/number_text.h"
#include "skyview/exposure/exposure_job.h"
#include "skyview/sky_view/horizon_request.h"

namespace skyview::python {

namespace {

// The keyword `name` of `options`, None or absent: nullopt.
template <class T>
std::optional<T> get(const py::dict& options, const char* name) {
  if (!options.contains(name)) return std::nullopt;
  const py::object value = options[name];
  if (value.is_none()) return std::nullopt;
  try {
    return value.cast<T>();
  } catch (const py::cast_error&) {
    throw UsageError(std::string(name) +
                     " has the wrong type: " + std::string(py::str(py::type::of(value).attr("__name__"))));
  }
}

// The exposure options as the command line states them, with those given marked by its names.
ExposureJobRequest exposure_request(const py::dict& o) {
  ExposureJobRequest r;
  auto given = [&](const char* option, bool is_given) {
    if (is_given) r.given.insert(option);
  };
  if (auto v = get<std::string>(o, "method")) r.method = *v;
  if (auto v = get<std::string>(o, "reads")) r.reads = *v, given("--reads", true);
  given("--max-error", get<double>(o, "max_error").has_value());
  if (auto v = get<int>(o, "map_size")) r.map_size = *v, given("--map-size", true);
  if (get<bool>(o, "allow_site_mismatch").value_or(false)) r.allow_site_mismatch = true;
  given("--allow-site-mismatch", r.allow_site_mismatch);
  SkyRequest& s = r.sky;
  if (auto v = get<std::string>(o, "sky")) s.sky = *v, given("--sky", true);
  if (auto v = get<std::string>(o, "epw")) s.epw = *v, given("--epw", true);
  if (auto v = get<double>(o, "lat")) s.latitude = *v, given("--lat", true);
  if (auto v = get<double>(o, "lon")) s.longitude = *v, given("--lon", true);
  if (auto v = get<double>(o, "elevation")) s.elevation = *v, given("--elevation", true);
  if (auto v = get<std::string>(o, "from_")) s.from = *v, given("--from", true);
  if (auto v = get<std::string>(o, "to")) s.to = *v, given("--to", true);
  if (auto v = get<std::string>(o, "step")) s.step = *v, given("--step", true);
  if (auto v = get<std::string>(o, "tz")) s.tz = *v, given("--tz", true);
  if (auto v = get<double>(o, "turbidity")) s.turbidity = *v, given("--turbidity", true);
  if (auto v = get<double>(o, "luminous_efficacy")) s.luminous_efficacy = *v, given("--luminous-efficacy", true);
  // The sky map: a file, or a SkyMap's bands and metadata (skymap names it in messages).
  if (auto v = get<std::string>(o, "skymap")) r.skymap = *v;
  if (auto direct = get<py::array>(o, "skymap_direct")) {
    const auto d = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(*direct);
    const auto f = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(o["skymap_diffuse"]);
    if (!d || !f || d.ndim() != 2 || f.ndim() != 2 || d.shape(0) != f.shape(0) || d.shape(1) != f.shape(1) ||
        d.size() == 0)
      throw UsageError("skymap's direct and diffuse must be 2-D arrays of one shape (a SkyMap)");
    ExposureMap map(static_cast<int>(d.shape(1)), static_cast<int>(d.shape(0)));
    map.band(ExposureBand::direct).assign(d.data(), d.data() + d.size());
    map.band(ExposureBand::diffuse).assign(f.data(), f.data() + f.size());
    std::map<std::string, std::string> metadata;
    for (const auto& [key, value] : o["skymap_metadata"].cast<py::dict>())
      metadata[py::str(key).cast<std::string>()] = py::str(value).cast<std::string>();
    r.skymap_data = skymap_from_bands(std::move(map), std::move(metadata), r.skymap);
  }
  // The albedo: a number, a raster's path, or an array of the heights' shape.
  if (auto v = get<double>(o, "albedo")) {
    if (!(*v >= 0.0 && *v <= 1.0)) throw UsageError("--albedo must be within 0 .. 1 (got " + number_text(*v) + ")");
    r.albedo.value = *v;
  }
  if (auto v = get<std::string>(o, "albedo_raster")) r.albedo = parse_exposure_albedo(*v);
  if (auto v = get<py::array>(o, "albedo_cells")) {
    const auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(*v);
    if (!a || a.ndim() != 2) throw UsageError("albedo must be a number, a raster's path or a 2-D array");
    Grid<float> cells(static_cast<int>(a.shape(1)), static_cast<int>(a.shape(0)));
    std::copy(a.data(), a.data() + a.size(), cells.values().begin());
    r.albedo.cells = std::move(cells);
  }
  return r;
}

HorizonKeywords horizon_keywords(const py::dict& o) {
  HorizonKeywords k;
  k.method = get<std::string>(o, "horizon_method");
  k.directions = get<int>(o, "directions");
  k.samples = get<int>(o, "samples");
  k.far_lines = get<int>(o, "far_lines");
  k.rays = get<int>(o, "rays");
  k.radius = get<double>(o, "radius");
  k.refraction = get<double>(o, "refraction");
  k.seed = get<std::uint64_t>(o, "seed");
  k.edge = get<std::string>(o, "edge");
  k.curvature = get<std::string>(o, "curvature");
  k.azimuth_origin = get<std::string>(o, "azimuth_origin");
  k.azimuths = get<std::string>(o, "azimuths");
  k.early_exit = get<bool>(o, "early_exit").value_or(true);
  return k;
}

py::tuple exposure(const py::object& z, const py::dict& o) {
  const ArrayGeoreference where{get<double>(o, "cell_size"),
                                get<std::vector<double>>(o, "transform"),
                                get<std::string>(o, "crs"),
                                get<double>(o, "nodata"),
                                get<double>(o, "z_scale"),
                                get<std::array<int, 4>>(o, "_tile"),
                                get<std::array<double, 2>>(o, "_height_range")};
  const int threads = get<int>(o, "threads").value_or(0);
  const py::object callback = o.contains("progress") ? py::object(o["progress"]) : py::none();
  // The options first, in the command line's order, then the heights.
  ExposureJobRequest request = exposure_request(o);
  check_exposure_job(request);
  HorizonRequest horizon;
  horizon.method_option = "--horizon-method";
  horizon.azimuth_origin = "grid";  // exposure sums over azimuth
  apply(horizon, horizon_keywords(o));
  HorizonSetup setup = plan_horizon(horizon);
  std::vector<std::string> warnings;
  const Terrain terrain = terrain_from_array(z, where, warnings);
  fit_horizon(setup, horizon, terrain);
  // A tile (skyview.dask) is placed in its raster: the site is checked against the raster's centre.
  const GeoReference whole = terrain.georef.window(-terrain.origin_col, -terrain.origin_row);
  ExposureJob job;
  {
    py::gil_scoped_release preparing;
    const ThreadLimit limit(threads);
    job = prepare_exposure_job(
        request, {terrain, terrain.raster_width(), terrain.raster_height(), whole, "z", false},
        [&](const std::vector<std::string>& lines) { warnings.insert(warnings.end(), lines.begin(), lines.end()); });
  }
  job.request.edge = setup.edge;
  ExposureBands bands;
  run_with_progress(callback, [&](ProgressCounter& progress) {
    const ThreadLimit limit(threads);
    progress.set_total(static_cast<std::uint64_t>(terrain.width()) * terrain.height());
    bands = compute_exposure(*setup.engine, terrain, Window::whole(terrain), job.sky, job.request, progress);
  });
  record_edge_cells(setup, bands.edge_cells);
  if (bands.albedo_nodata_cells > 0) {
    warnings.push_back(std::to_string(bands.albedo_nodata_cells) +
                       " cells have no albedo: their reflected and total bands are nodata");
  }
  warnings.insert(warnings.end(), setup.warnings.begin(), setup.warnings.end());
  warn_all(warnings);
  py::dict out;
  for (const ExposureBandInfo& b : exposure_band_info()) {
    out[py::str(b.name)] = to_numpy(std::move((bands.*b.grid).values()), {terrain.height(), terrain.width()});
  }
  py::dict metadata;
  for (const auto& [key, value] : setup.metadata) metadata[py::str(key)] = value;
  for (const auto& [key, value] : job.metadata) metadata[py::str(key)] = value;
  return py::make_tuple(out, metadata);
}

}  // namespace

void bind_exposure_functions(py::module_& m) {
  using namespace pybind11::literals;
  m.def("_exposure", exposure, "z"_a, "options"_a);
  m.def("_exposure_band_names", [] {
    std::vector<std::string> names;
    for (const ExposureBandInfo& b : exposure_band_info()) names.push_back(b.name);
    return names;
  });
}

}  // namespace skyview::python
