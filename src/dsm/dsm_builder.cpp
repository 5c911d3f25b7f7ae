#include "skyview/dsm/dsm_builder.h"

#include <gdal_alg.h>
#include <gdal_priv.h>
#include <gdal_utils.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>

#include "dsm/footprint_layer.h"
#include "dsm/point_filters.h"
#include "skyview/core/error.h"
#include "skyview/core/number_text.h"
#include "skyview/dsm/point_cloud.h"
#include "skyview/dsm/point_gridder.h"
#include "skyview/raster/height_unit.h"
#include "skyview/raster/raster_io.h"

namespace skyview {

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

struct CtDeleter {
  void operator()(OGRCoordinateTransformation* t) const { OGRCoordinateTransformation::DestroyCT(t); }
};
using TransformPtr = std::unique_ptr<OGRCoordinateTransformation, CtDeleter>;

OGRSpatialReference srs_from(const std::string& wkt_or_user, const std::string& what) {
  OGRSpatialReference s;
  if (s.SetFromUserInput(wkt_or_user.c_str()) != OGRERR_NONE) throw Error("cannot understand the CRS of " + what);
  s.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  return s;
}

// Transform from `from` to `to`, or null when they are the same CRS.
TransformPtr transform(const OGRSpatialReference& from, const OGRSpatialReference& to, const std::string& what) {
  if (from.IsSame(&to)) return nullptr;
  TransformPtr t(OGRCreateCoordinateTransformation(&from, &to));
  if (!t) throw Error("cannot transform " + what + " to the output CRS");
  return t;
}

struct Extent {
  double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
  void add(double x, double y) {
    x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
  }
  bool empty() const { return !(x1 > x0 && y1 > y0); }
  // No point at all; a single point or a line of them has a place but no area.
  bool none() const { return !(x1 >= x0 && y1 >= y0); }
};

// Adds a box's corners and edge midpoints (they survive curved reprojections better); a box none
// of whose points transforms is in a CRS its coordinates do not fit.
void add_box(Extent& e, double x0, double y0, double x1, double y1, OGRCoordinateTransformation* t,
             const std::string& what) {
  int added = 0;
  for (int i = 0; i <= 8; ++i) {
    double xs[3] = {x0, 0.5 * (x0 + x1), x1}, ys[3] = {y0, 0.5 * (y0 + y1), y1};
    double x = xs[i % 3], y = ys[i / 3];
    if (t && (!t->Transform(1, &x, &y) || !std::isfinite(x) || !std::isfinite(y))) continue;
    e.add(x, y);
    ++added;
  }
  if (added == 0) {
    throw Error("the extent of " + what +
                " cannot be transformed to the output CRS: are its coordinates in the CRS it declares (or --s_srs)?");
  }
}

// Closes nodata holes up to `max_distance` cells with GDAL's inverse-distance fill; returns how many
// cells it filled.
std::int64_t fill_nodata(Grid<float>& g, double max_distance) {
  GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
  GDALDatasetUniquePtr ds(mem->Create("", g.width(), g.height(), 1, GDT_Float32, nullptr));
  std::vector<float> v = g.values();
  for (float& x : v) x = std::isnan(x) ? -3.4e38f : x;
  GDALRasterBand* band = ds->GetRasterBand(1);
  band->SetNoDataValue(-3.4e38);
  if (band->RasterIO(GF_Write, 0, 0, g.width(), g.height(), v.data(), g.width(), g.height(), GDT_Float32, 0, 0) !=
          CE_None ||
      GDALFillNodata(band, nullptr, max_distance, 0, 0, nullptr, nullptr, nullptr) != CE_None ||
      band->RasterIO(GF_Read, 0, 0, g.width(), g.height(), v.data(), g.width(), g.height(), GDT_Float32, 0, 0) !=
          CE_None) {
    throw Error("filling nodata failed");
  }
  std::int64_t filled = 0;
  for (std::size_t k = 0; k < v.size(); ++k) {
    if (std::isnan(g.values()[k]) && v[k] > -1e38f) {
      g.values()[k] = v[k];
      ++filled;
    }
  }
  return filled;
}

GDALDatasetUniquePtr open_raster(const std::string& path) {
  init_gdal();
  GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!ds) throw Error("cannot open '" + path + "' as a raster");
  return ds;
}

}  // namespace

DsmResult build_dsm(const DsmOptions& o) {
  init_gdal();
  if (o.dems.empty() && o.points.empty() && o.footprints.empty()) {
    throw Error("nothing to build from: give --dem, --points or --footprints");
  }
  if (o.want_dtm && o.dems.empty() && o.points.empty()) {
    throw UsageError("--dtm needs a terrain: give --dem, or --points with ground returns");
  }
  const GridStatistic stat = parse_grid_statistic(o.stat);
  // Inputs and their CRSs.
  DsmResult out;
  std::vector<std::unique_ptr<PointCloud>> clouds;
  for (const auto& p : o.points) {
    clouds.push_back(open_point_cloud(p));
    if (clouds.back()->point_count() == 0) throw Error("'" + p + "' holds no points");
    const auto& doubts = clouds.back()->warnings();
    out.report.warnings.insert(out.report.warnings.end(), doubts.begin(), doubts.end());
  }
  auto cloud_crs = [&](const PointCloud& c) { return o.s_srs.empty() ? c.crs_wkt() : o.s_srs; };
  std::string first_crs;
  for (const auto& d : o.dems) {
    if (first_crs.empty()) first_crs = open_raster(d)->GetProjectionRef();
  }
  for (const auto& c : clouds) {
    if (first_crs.empty()) first_crs = cloud_crs(*c);
  }
  std::optional<FootprintLayer> footprints;
  OGRLayer* layer = nullptr;
  if (!o.footprints.empty()) {
    footprints.emplace(o.footprints,
                       FootprintFields{o.height_field, o.base_field, o.absolute_heights, o.footprint_z_scale});
    layer = &footprints->layer();
    if (first_crs.empty() && layer->GetSpatialRef()) {
      char* w = nullptr;
      layer->GetSpatialRef()->exportToWkt(&w);
      first_crs = w ? w : "";
      CPLFree(w);
    }
  }
  const std::string out_crs = !o.t_srs.empty() ? o.t_srs : first_crs;
  if (out_crs.empty()) throw Error("no input carries a CRS; give --t_srs");
  const OGRSpatialReference target = srs_from(out_crs, "--t_srs");

  // The grid: extent from --te or the inputs, snapped to the resolution: to the first DEM's own
  // lattice where its cells are the output's (same CRS, north-up, square cells of the resolution),
  // so that its heights are copied, not resampled half a cell off; else to multiples of it.
  double res = o.res;
  Extent ext;
  std::optional<std::array<double, 2>> lattice;
  for (const auto& d : o.dems) {
    auto ds = open_raster(d);
    double gt[6];
    ds->GetGeoTransform(gt);
    const OGRSpatialReference s = srs_from(ds->GetProjectionRef(), "'" + d + "'");
    // The DEM's cell size holds only in its own CRS (a 1 m DEM made 1° cells in EPSG:4326).
    if (res <= 0 && !s.IsSame(&target)) {
      throw Error("give --res: '" + d + "' is in another CRS than the output, so its cell size does not carry over");
    }
    if (res <= 0) res = std::abs(gt[1]);
    const bool square_north_up = gt[2] == 0.0 && gt[4] == 0.0 && gt[1] > 0.0 && gt[5] == -gt[1];
    if (&d == &o.dems.front() && square_north_up && std::abs(gt[1] - res) <= 1e-9 * res && s.IsSame(&target))
      lattice = std::array<double, 2>{gt[0], gt[3]};
    auto t = transform(s, target, "'" + d + "'");
    add_box(ext, gt[0], gt[3] + gt[5] * ds->GetRasterYSize(), gt[0] + gt[1] * ds->GetRasterXSize(), gt[3], t.get(),
            "'" + d + "'");
  }
  Extent cloud_ext;  // returns lie in a closed box, rasters and polygons cover half-open cells
  for (const auto& c : clouds) {
    TransformPtr t;
    if (!cloud_crs(*c).empty()) t = transform(srs_from(cloud_crs(*c), c->path()), target, "'" + c->path() + "'");
    const double* b = c->bounds();
    add_box(ext, b[0], b[1], b[2], b[3], t.get(), "'" + c->path() + "'");
    add_box(cloud_ext, b[0], b[1], b[2], b[3], t.get(), "'" + c->path() + "'");
  }
  if (layer) {
    // The box of the footprints themselves, transformed: the layer's box transformed whole grows
    // with the rotation between the CRSs (a district in EPSG:2263 came out 228² for 128²).
    TransformPtr t;
    if (layer->GetSpatialRef()) t = transform(*layer->GetSpatialRef(), target, "'" + o.footprints + "'");
    layer->ResetReading();
    int placed = 0, failed = 0;
    for (auto& feature : *layer) {
      const OGRGeometry* g = feature->GetGeometryRef();
      if (!g || g->IsEmpty()) continue;
      std::unique_ptr<OGRGeometry> there(g->clone());
      if (t && there->transform(t.get()) != OGRERR_NONE) {  // counted as skipped when burned
        ++failed;
        continue;
      }
      OGREnvelope env;
      there->getEnvelope(&env);
      ext.add(env.MinX, env.MinY);
      ext.add(env.MaxX, env.MaxY);
      ++placed;
    }
    if (placed == 0 && failed > 0) {
      throw Error("no footprint of '" + o.footprints +
                  "' transforms into the output CRS: its coordinates do not fit its CRS");
    }
  }
  if (res <= 0 && target.IsGeographic()) {
    throw Error("give --res for a geographic output CRS, in degrees (1 m is about 0.00001 degrees of latitude)");
  }
  if (res <= 0) res = 1.0;
  if (o.te) {
    ext = {(*o.te)[0], (*o.te)[1], (*o.te)[2], (*o.te)[3]};
    if (!(ext.x1 > ext.x0 && ext.y1 > ext.y0))
      throw UsageError("--te is xmin ymin xmax ymax, with xmin < xmax and ymin < ymax");
    lattice = std::array<double, 2>{ext.x0, ext.y1};  // its corner is the grid's, as gdalwarp -te keeps it
  }
  // Clouds' returns lie in a closed box: a single return, or a row of them, still makes a grid
  // (the extra column and row below).
  const bool cloud_only_extent = !o.te && std::isfinite(cloud_ext.x0) && ext.x0 == cloud_ext.x0 &&
                                 ext.x1 == cloud_ext.x1 && ext.y0 == cloud_ext.y0 && ext.y1 == cloud_ext.y1;
  if (ext.none() || (ext.empty() && !cloud_only_extent))
    throw Error("the inputs cover no area (empty point cloud or extent)");
  // (Within a billionth of a cell an extent already on the lattice stays there.)
  const double lx = lattice ? (*lattice)[0] : 0.0, ly = lattice ? (*lattice)[1] : 0.0;
  const double x0 = lx + std::floor((ext.x0 - lx) / res + 1e-9) * res;
  const double y1 = ly + std::ceil((ext.y1 - ly) / res - 1e-9) * res;
  double cols = std::ceil((ext.x1 - x0) / res - 1e-9), rows = std::ceil((y1 - ext.y0) / res - 1e-9);
  // A cloud's largest x and smallest y lie on the grid's far edges, just outside its half-open cells.
  if (!o.te && std::isfinite(cloud_ext.x0)) {
    cols += cloud_ext.x1 >= x0 + cols * res ? 1 : 0;
    rows += cloud_ext.y0 <= y1 - rows * res ? 1 : 0;
  }
  if (target.IsGeographic() &&
      (y1 > 90.0 + 1e-9 || y1 - rows * res < -90.0 - 1e-9 || x0 < -540.0 || x0 + cols * res > 540.0)) {
    throw Error(
        "the output grid would reach beyond 90 degrees of latitude or 540 of longitude in a geographic CRS: "
        "the inputs' coordinates are not degrees (check --s_srs and --t_srs)");
  }
  if (!(cols >= 1 && rows >= 1) || cols * rows > 4e9) {
    throw Error("the output grid would be " + number_text(cols) + " x " + number_text(rows) +
                " cells; check --res and the extent");
  }
  const int width = static_cast<int>(cols), height = static_cast<int>(rows);
  out.georef.has_geotransform = true;
  out.georef.geotransform = {x0, res, 0, y1, 0, -res};
  // Heights are written in metres, so a vertical CRS in another unit would mislabel them.
  OGRSpatialReference written(target);
  if (written.IsCompound()) written.StripVertical();
  char* wkt = nullptr;
  written.exportToWkt(&wkt);
  out.georef.crs_wkt = wkt ? wkt : "";
  CPLFree(wkt);
  Grid<float> terrain(width, height, kNaN);

  // Terrain: every DEM warped bilinearly onto the grid (later DEMs fill where earlier are nodata).
  for (const auto& d : o.dems) {
    auto src = open_raster(d);
    const HeightUnit z_unit = height_unit(*src->GetRasterBand(1), src->GetSpatialRef(), o.z_scale, d);
    const double z_scale = z_unit.metres;
    out.report.height_units.push_back("'" + d + "': " + z_unit.source);
    // Packed DEMs warp as stored and are unpacked after.
    const BandPacking packing = band_packing(*src->GetRasterBand(1), d, 1);
    GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
    GDALDatasetUniquePtr dst(mem->Create("", width, height, 1, GDT_Float32, nullptr));
    double gt[6] = {x0, res, 0, y1, 0, -res};
    dst->SetGeoTransform(gt);
    dst->SetProjection(out.georef.crs_wkt.c_str());
    dst->GetRasterBand(1)->SetNoDataValue(-3.4e38);
    dst->GetRasterBand(1)->Fill(-3.4e38);
    const char* args[] = {"-r", "bilinear", "-dstnodata", "-3.4e38", nullptr};
    GDALWarpAppOptions* wo = GDALWarpAppOptionsNew(const_cast<char**>(args), nullptr);
    GDALDatasetH srcs[] = {src.get()};
    int usage = 0;
    GDALDatasetH r = GDALWarp(nullptr, dst.get(), 1, srcs, wo, &usage);
    GDALWarpAppOptionsFree(wo);
    if (!r || usage) throw Error("cannot warp '" + d + "' onto the output grid");
    std::vector<float> v(static_cast<std::size_t>(width) * height);
    if (dst->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, width, height, v.data(), width, height, GDT_Float32, 0, 0) !=
        CE_None) {
      throw Error("cannot read the warped '" + d + "'");
    }
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (std::isnan(terrain.values()[i]) && v[i] > -1e38 && std::isfinite(v[i])) {
        terrain.values()[i] = static_cast<float>((v[i] * packing.scale + packing.offset) * z_scale);
      }
    }
  }

  // Footprint ids per cell (cell centre inside the polygon), burned before the points so that
  // returns inside a footprint can give it a height.
  Grid<float> footprint_id(width, height, 0.0f);
  std::vector<double> fp_height, fp_base;
  std::vector<std::vector<float>> fp_returns;
  if (layer) {
    TransformPtr t;
    if (layer->GetSpatialRef()) t = transform(*layer->GetSpatialRef(), target, "'" + o.footprints + "'");
    if (!footprints->height_unit().empty()) {
      out.report.height_units.push_back("'" + o.footprints + "': " + footprints->height_unit());
    }
    GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
    GDALDatasetUniquePtr ids(mem->Create("", width, height, 1, GDT_Float32, nullptr));
    double gt[6] = {x0, res, 0, y1, 0, -res};
    ids->SetGeoTransform(gt);
    ids->SetProjection(out.georef.crs_wkt.c_str());
    std::vector<OGRGeometryH> geoms;
    std::vector<double> burn;
    FootprintCounts counts;
    footprints->read(
        t.get(),
        [&](Footprint& f) {
          fp_height.push_back(f.height);
          fp_base.push_back(f.base);
          geoms.push_back(OGRGeometry::ToHandle(f.polygons.release()));
          burn.push_back(static_cast<double>(geoms.size()));
        },
        counts);
    out.report.footprints_not_polygons += counts.not_polygons;
    out.report.footprints_repaired += counts.repaired;
    out.report.footprints_skipped += counts.skipped;
    if (const std::string w = geos_notices_warning(counts, o.footprints); !w.empty()) out.report.warnings.push_back(w);
    if (counts.polygons == 0) throw Error("'" + o.footprints + "' holds no polygons");
    int bands[] = {1};
    if (!geoms.empty() &&
        GDALRasterizeGeometries(ids.get(), 1, bands, static_cast<int>(geoms.size()), geoms.data(), nullptr, nullptr,
                                burn.data(), nullptr, nullptr, nullptr) != CE_None) {
      throw Error("cannot rasterise '" + o.footprints + "'");
    }
    for (OGRGeometryH g : geoms) OGR_G_DestroyGeometry(g);
    if (ids->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, width, height, footprint_id.data(), width, height, GDT_Float32,
                                        0, 0) != CE_None) {
      throw Error("cannot read the rasterised footprints");
    }
    fp_returns.resize(fp_height.size());
  }

  // Without a DEM, the terrain that relative footprint heights stand on and that --dtm writes is
  // the clouds' bare earth: the mean of their ground returns, holes (under buildings) filled.
  const bool cloud_terrain =
      o.dems.empty() && !clouds.empty() && (o.want_dtm || (layer && o.base_field.empty() && !o.absolute_heights));
  std::optional<PointGridder> ground_gridder;
  if (cloud_terrain) ground_gridder.emplace(GridLattice{width, height, x0, y1, res}, GridStatistic::mean);

  // Points: streamed (or held in memory for the PCL filters), reprojected, filtered, gridded.
  PointGridder gridder({width, height, x0, y1, res}, stat, o.idw_radius, o.idw_power);
  auto keep_class = [&](int cls, bool ground) {
    if (o.ground_only && !ground) return false;
    return o.classes.empty() || std::find(o.classes.begin(), o.classes.end(), cls) != o.classes.end();
  };
  // Every return, after denoising and before the class filters, may give its footprint a height.
  auto accept = [&](double x, double y, double z, int cls, bool ground) {
    const double fc = (x - x0) / res, fr = (y1 - y) / res;
    if (!(fc >= 0 && fr >= 0 && fc < width && fr < height) || !std::isfinite(z)) return;
    if (!fp_height.empty()) {  // only footprints need this lookup (a cache miss per return)
      const float id = footprint_id(static_cast<int>(fc), static_cast<int>(fr));
      if (id > 0 && std::isnan(fp_height[static_cast<std::size_t>(id) - 1])) {
        fp_returns[static_cast<std::size_t>(id) - 1].push_back(static_cast<float>(z));
      }
    }
    if (ground_gridder && ground) ground_gridder->add(x, y, static_cast<float>(z));
    if (!keep_class(cls, ground)) return;
    ++out.report.points_used;
    gridder.add(x, y, static_cast<float>(z));
  };
  for (const auto& cloud : clouds) {
    const std::string name = "'" + cloud->path() + "'";
    TransformPtr t;
    std::optional<OGRSpatialReference> crs;
    if (!cloud_crs(*cloud).empty()) {
      crs = srs_from(cloud_crs(*cloud), cloud->path());
      t = transform(*crs, target, name);
    }
    // Heights in metres from the start: the denoiser and the ground filter's thresholds work in them.
    const HeightUnit z_unit =
        cloud_height_unit(crs ? &*crs : nullptr, &target, cloud->z_unit_metres(), o.points_z_scale);
    const double cloud_z = z_unit.metres;
    out.report.height_units.push_back(name + ": " + z_unit.source);
    auto each_point = [&](auto&& f) {  // f(x, y, point) in the output CRS
      std::vector<double> xs, ys;
      cloud->read_points([&](const std::vector<LasPoint>& chunk) {
        xs.resize(chunk.size());
        ys.resize(chunk.size());
        for (std::size_t i = 0; i < chunk.size(); ++i) xs[i] = chunk[i].x, ys[i] = chunk[i].y;
        if (t) t->Transform(static_cast<int>(xs.size()), xs.data(), ys.data());
        for (std::size_t i = 0; i < chunk.size(); ++i) f(xs[i], ys[i], chunk[i]);
      });
    };
    // Bare earth comes from class 2 when the cloud has it, else from the morphological filter.
    const bool need_ground = o.ground_only || cloud_terrain;
    bool has_ground_class = false;
    if (need_ground) {  // classes only: no reprojection needed
      cloud->read_points([&](const std::vector<LasPoint>& chunk) {
        for (const LasPoint& p : chunk) has_ground_class |= p.classification == 2;
      });
    }
    const bool filter_ground = need_ground && !has_ground_class;
    if (need_ground) {
      const std::string source = filter_ground ? "morphological filter" : "class 2";
      std::string& r = out.report.ground_source;
      r = r.empty() || r == source ? source : "class 2 and morphological filter";
    }
    if (!o.denoise && !filter_ground) {
      each_point([&](double x, double y, const LasPoint& p) {
        ++out.report.points_read;
        accept(x, y, p.z * cloud_z, p.classification, p.classification == 2);
      });
      continue;
    }
    // The PCL filters need the whole cloud: 25 bytes per return here and about as much in PCL.
    std::vector<XyzPoint> pts;
    std::vector<std::uint8_t> cls;
    pts.reserve(static_cast<std::size_t>(cloud->point_count()));
    each_point([&](double x, double y, const LasPoint& p) {
      ++out.report.points_read;
      if (!std::isfinite(p.z)) return;
      pts.push_back({x, y, p.z * cloud_z});
      cls.push_back(p.classification);
    });
    if (o.denoise) {
      const std::vector<char> keep = statistical_inliers(pts, o.denoise_k, o.denoise_sigma);
      std::size_t n = 0;
      for (std::size_t i = 0; i < pts.size(); ++i) {
        if (keep[i]) pts[n] = pts[i], cls[n] = cls[i], ++n;
      }
      out.report.points_removed_as_noise += pts.size() - n;
      pts.resize(n);
      cls.resize(n);
    }
    std::vector<char> ground(pts.size(), 0);
    if (filter_ground) {
      GroundFilterParams gp;
      gp.cell = res;
      gp.max_window = o.ground_window;
      gp.slope = o.ground_slope;
      ground = morphological_ground(pts, gp);
    } else {
      for (std::size_t i = 0; i < pts.size(); ++i) ground[i] = cls[i] == 2;
    }
    for (std::size_t i = 0; i < pts.size(); ++i) accept(pts[i].x, pts[i].y, pts[i].z, cls[i], ground[i]);
  }
  Grid<float> pts = gridder.finish(&out.report.cells_from_points);
  if (cloud_terrain) {
    terrain = ground_gridder->finish();
    if (std::all_of(terrain.values().begin(), terrain.values().end(), [](float v) { return std::isnan(v); })) {
      throw Error("the clouds hold no ground returns to make the terrain from; give --dem");
    }
    fill_nodata(terrain, std::max(width, height));
  }
  if (!clouds.empty() && out.report.points_used == 0) {
    throw Error("none of the " + std::to_string(out.report.points_read) +
                " returns falls on the output grid after the class filters (check the clouds' CRS or --s_srs, "
                "--te, --classes)");
  }

  // Buildings on the terrain, then DSM = max(terrain, buildings, points). Terrain made from the
  // clouds only carries buildings and goes to --dtm: the DSM already has those returns, and asking
  // for --dtm must not change it.
  out.dsm = Grid<float>(width, height, kNaN);
  std::vector<char> burned(fp_height.size(), 0);  // a footprint with a height that reached a cell
  // A height above the terrain is measured from the lowest ground under the building (as
  // OpenStreetMap's height=* is, from the lowest point of its perimeter): one flat top per
  // footprint, not a roof that copies the slope beneath it.
  std::vector<double> fp_ground(fp_height.size(), std::numeric_limits<double>::infinity());
  for (std::size_t k = 0; k < out.dsm.size(); ++k) {
    const float id = footprint_id.values()[k], ground = terrain.values()[k];
    if (id > 0 && !std::isnan(ground)) {
      double& low = fp_ground[static_cast<std::size_t>(id) - 1];
      low = std::min(low, static_cast<double>(ground));
    }
  }
  for (std::size_t k = 0; k < out.dsm.size(); ++k) {
    const float ground = terrain.values()[k];
    float v = cloud_terrain ? kNaN : ground;
    const float id = footprint_id.values()[k];
    if (id > 0) {
      const std::size_t f = static_cast<std::size_t>(id) - 1;
      const double top = footprint_top(fp_height[f], fp_base[f], o.absolute_heights, fp_ground[f]);
      if (!std::isnan(top)) {
        v = std::isnan(v) ? static_cast<float>(top) : std::max(v, static_cast<float>(top));
        burned[f] = 1;
      }
    }
    const float p = pts.values()[k];
    if (!std::isnan(p)) v = std::isnan(v) ? p : std::max(v, p);
    out.dsm.values()[k] = v;
  }
  // Footprints without a height take the 90th percentile of the returns inside them.
  for (std::size_t f = 0; f < fp_height.size(); ++f) {
    // A height above the terrain where there is no terrain (off the DEM) burns nothing: skipped.
    if (!std::isnan(fp_height[f])) {
      ++(burned[f] ? out.report.footprints_burned : out.report.footprints_skipped);
      continue;
    }
    auto& z = fp_returns[f];
    if (z.empty()) {
      ++out.report.footprints_skipped;
      continue;
    }
    std::nth_element(z.begin(), z.begin() + static_cast<std::ptrdiff_t>(0.9 * (z.size() - 1)), z.end());
    const float top = z[static_cast<std::size_t>(0.9 * (z.size() - 1))];
    for (std::size_t k = 0; k < out.dsm.size(); ++k) {
      if (footprint_id.values()[k] == static_cast<float>(f + 1)) {
        float& v = out.dsm.values()[k];
        v = std::isnan(v) ? top : std::max(v, top);
      }
    }
    ++out.report.footprints_from_cloud;
  }
  if (o.fill) out.report.cells_filled = fill_nodata(out.dsm, o.fill_distance);
  if (std::all_of(out.dsm.values().begin(), out.dsm.values().end(), [](float v) { return std::isnan(v); })) {
    if (std::any_of(fp_height.begin(), fp_height.end(), [](double h) { return !std::isnan(h); })) {
      throw Error(
          "nothing gave the DSM a height: footprint heights above the terrain need terrain under them "
          "(--dem or --points), or --base-field or --absolute-heights");
    }
    throw Error("nothing gave the DSM a height: footprints without heights need --height-field, --points or --dem");
  }
  if (!o.dems.empty() || cloud_terrain) out.dtm = std::move(terrain);
  return out;
}

}  // namespace skyview
