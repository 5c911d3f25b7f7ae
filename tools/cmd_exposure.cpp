// skyview exposure: solar exposure of every cell of a DSM over a period (docs/commands/exposure.md).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>

#include "horizon_job.h"
#include "preview_options.h"
#include "sky_job.h"
#include "skyview/core/error.h"
#include "skyview/core/number_text.h"
#include "skyview/exposure/exposure.h"
#include "skyview/raster/raster_site.h"
#include "skyview/sky/skymap_file.h"
#include "skyview/tiling/memory_budget.h"

namespace skyview::cli {
namespace {

// A map made for a site farther than this from the raster describes another sky.
constexpr double kMaxSiteDistanceDeg = 1.0;

struct Options {
  HorizonJobOptions job;
  SkyRequest sky;
  std::string method = "fast", skymap, albedo, reads = "area";
  PreviewOptions preview;
  int map_size = 512;
  bool allow_site_mismatch = false;
  TileRequest tiling;
  const CLI::App* app = nullptr;
};

// --albedo: a number, or a raster of one per cell.
struct Albedo {
  std::optional<double> value;
  std::string raster;
};
Albedo parse_albedo(const std::string& text) {
  Albedo a;
  if (text.empty()) return a;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end && *end == '\0' && end != text.c_str()) {
    if (!(v >= 0.0 && v <= 1.0)) throw UsageError("--albedo must be within 0 .. 1 (got " + text + ")");
    a.value = v;
  } else {
    a.raster = text;
  }
  return a;
}

// The albedo raster lies on the DSM's grid: the same size, its first cell within half a cell of
// the DSM's, the same cell size.
void check_albedo_grid(const std::string& path, int width, int height, const GeoReference& albedo, int dsm_width,
                       int dsm_height, const GeoReference& dsm) {
  const auto& g = albedo.geotransform;
  const auto& d = dsm.geotransform;
  const bool same_grid =
      albedo.has_geotransform == dsm.has_geotransform &&
      (!dsm.has_geotransform ||
       (std::abs(g[0] - d[0]) < 0.5 * std::abs(d[1]) && std::abs(g[3] - d[3]) < 0.5 * std::abs(d[5]) &&
        std::abs(g[1] - d[1]) < 1e-6 * std::abs(d[1]) && std::abs(g[5] - d[5]) < 1e-6 * std::abs(d[5])));
  if (width != dsm_width || height != dsm_height || !same_grid) {
    throw UsageError("--albedo '" + path + "' is " + std::to_string(width) + "x" + std::to_string(height) +
                     " cells where the DSM is " + std::to_string(dsm_width) + "x" + std::to_string(dsm_height) +
                     (same_grid ? "" : ", or lies elsewhere") + "; resample it onto the DSM's grid");
  }
}

// The albedo raster's cells (all of them, or a tile's), each within 0 .. 1 or nodata.
Grid<float> checked_albedo(RasterBand&& band, const std::string& path) {
  for (float v : band.values.values()) {
    if (!std::isnan(v) && !(v >= 0.0f && v <= 1.0f))
      throw UsageError("--albedo '" + path + "' holds " + number_text(v) + ", outside 0 .. 1");
  }
  return std::move(band.values);
}

struct BandInfo {
  const char* name;
  Grid<float> ExposureBands::*grid;
  const char* unit;
  const char* definition;
};
constexpr BandInfo kBands[] = {
    {"total", &ExposureBands::total, "kWh m-2", "direct + diffuse + reflected on the cell's tilted surface"},
    {"direct", &ExposureBands::direct, "kWh m-2", "the sun's beam on the cell's tilted surface (Horn normal)"},
    {"diffuse", &ExposureBands::diffuse, "kWh m-2", "the sky without the sun, through the parts the cell sees"},
    {"reflected", &ExposureBands::reflected, "kWh m-2",
     "isotropic reflection: albedo x unobstructed global horizontal x (1 - svf of the tilted surface)"},
    {"horizontal_total", &ExposureBands::horizontal_total, "kWh m-2",
     "direct + diffuse + reflected on a horizontal surface at the cell (a pyranometer)"},
    {"svf", &ExposureBands::svf, "1", "sky-view factor, 1 - mean sin^2(max(h,0)); cosine-weighted, horizontal"},
};
constexpr int kBandCount = static_cast<int>(std::size(kBands));

// The run tile by tile (docs/tiling.md): each tile's window plus halo through compute_exposure with
// the tile's own cells as its window, those cells written at the tile's place. The sky is the whole
// run's, made once; an albedo raster is read a tile's window at a time. Returns the sums over the
// tiles (the total band's); adds the cells without albedo to `albedo_nodata_cells`.
TileSummary run_tiled_exposure(HorizonJob& job, const Options& o, const ExposureSky& sky,
                               const ExposureRequest& request, const std::string& albedo_raster,
                               std::int64_t& albedo_nodata_cells) {
  TiledOutput output;
  output.path = o.job.output;
  output.tiles_dir = o.tiling.options.tiles_dir;
  output.bands = kBandCount;
  output.identity = "exposure";
  output.options.format = o.job.out.format;
  output.options.creation_options = o.job.out.creation_options;
  output.options.overwrite = o.job.out.overwrite;
  output.options.metadata = job.metadata;
  TileSummary total;
  ThreadLimit limit(o.job.out.threads);
  with_progress(job, [&](ProgressCounter& progress) {
    total = run_tiles(
        job, output, progress, [&](const Terrain& part, const Window& inner, BandWriter& out, int col0, int row0) {
          ExposureRequest tile_request = request;
          if (!albedo_raster.empty()) {
            const Window cells{part.origin_col + inner.col0, part.origin_row + inner.row0, inner.cols, inner.rows};
            tile_request.albedo_grid = checked_albedo(read_band(albedo_raster, 1, cells), albedo_raster);
          }
          const ExposureBands bands = compute_exposure(*job.engine, part, inner, sky, tile_request, progress);
          for (int b = 0; b < kBandCount; ++b) {
            const BandInfo& info = kBands[b];
            out.write_window(b, col0, row0, inner.cols, inner.rows, (bands.*info.grid).data());
            out.describe(b, {info.name, info.unit, nullptr, {{"DEFINITION", info.definition}}});
          }
          albedo_nodata_cells += bands.albedo_nodata_cells;
          TileSummary tile;
          tile.first_band_name = kBands[0].name;
          tile.first_band.add(bands.total.values());
          tile.edge_cells = bands.edge_cells;
          return tile;
        });
  });
  return total;
}

int run(Options& o) {
  const RunSummary summary("exposure");
  const CLI::App& app = *o.app;
  if (o.method != "fast" && o.method != "exact")
    throw UsageError("--method must be fast or exact (got '" + o.method + "')");
  const bool exact = o.method == "exact";
  refuse_unused(app, "--max-error", false, "skyview svf (skyview bench --exposure measures exposure's error)");
  refuse_unused(app, "--reads", !exact, "--method fast");
  if (o.reads != "area" && o.reads != "mipmap")
    throw UsageError("--reads must be area or mipmap (got '" + o.reads + "')");
  const bool from_file = !o.skymap.empty();
  if (from_file) {
    for (const std::string& name : sky_option_names())
      refuse_unused(app, name, false, "runs without --skymap (the map file holds its sky, site and period)");
    refuse_unused(app, "--map-size", false, "runs without --skymap (the map file has its size)");
  } else {
    check_sky_options(app, o.sky);
    if (o.map_size < 16 || o.map_size > 8192) throw UsageError("--map-size must be within 16 .. 8192");
  }
  const Albedo albedo = parse_albedo(o.albedo);
  std::vector<std::string> band_names;
  for (const BandInfo& b : kBands) band_names.push_back(b.name);
  const std::size_t drawn = check_preview_options(*o.app, o.preview, band_names);
  check_outputs_apart({o.job.output, o.preview.path}, {o.job.input, o.skymap, o.sky.epw, albedo.raster});

  // The map's cells for the memory model: a map file's are not known before it is read (1024^2
  // stands for them, twice the default's side).
  const std::int64_t map_cells = from_file ? std::int64_t{1024} * 1024 : std::int64_t{o.map_size} * o.map_size;
  o.tiling.memory = [map_cells](const HorizonEngine& engine) { return exposure_memory(engine, map_cells); };
  HorizonJob job = prepare_horizon_job(o.job, "exposure", {o.preview.path}, &o.tiling);
  if (o.tiling.options.tiles_dir.empty())
    check_output_format(o.job.output, o.job.out.format, kBandCount, o.job.out.creation_options);
  if (job.tiles.tiled && !o.preview.path.empty())
    throw UsageError("--preview needs the whole raster, and the run goes by tiles (" + job.tiles.why + ")");
  // A tiled run holds only a window about the raster's centre (HorizonJob::terrain).
  const Terrain& t = job.terrain;
  const int width = job.width(), height = job.height();
  auto& meta = job.metadata;
  const std::optional<GeoPoint> centre = raster_centre_geographic(job.georef(), width, height);

  // The sky: from the map file, or made here for the raster's site.
  ExposureSky sky;
  std::optional<PreparedSky> prepared;
  std::map<std::string, std::string> sky_meta;
  std::string site_source;
  std::optional<EpwFile> weather;
  if (from_file) {
    SkymapFile file = read_skymap(o.skymap);
    sky.map = std::move(file.map);
    sky_meta = file.metadata;
    site_source = "the sky map '" + o.skymap + "'";
    if (exact) {
      // The beam of every step: the map's own period and sky again.
      try {
        prepared = prepare_sky(file.request);
      } catch (const Error& e) {
        throw UsageError("--method exact rebuilds the time steps of '" + o.skymap +
                         "' from its metadata, which failed: " + e.what());
      }
      weather = prepared->weather;
    } else if (!file.request.epw.empty() && !albedo.value && albedo.raster.empty()) {
      try {
        weather = read_epw(file.request.epw);
      } catch (const Error&) {
        // Only the albedo was wanted from it: the default stands.
      }
    }
  } else {
    if (!centre && !o.sky.latitude && o.sky.epw.empty()) {
      throw Error("'" + o.job.input + "' has no CRS to place the sun: give --lat and --lon");
    }
    std::optional<Site> default_site;
    if (centre) {
      Site s;
      s.latitude_deg = centre->latitude_deg;
      s.longitude_deg = centre->longitude_deg;
      const double mid = t.heights(width / 2 - t.origin_col, height / 2 - t.origin_row);
      s.elevation_m = t.base_height + (std::isnan(mid) ? 0.0 : mid);
      default_site = s;
    }
    // Hošek–Wilkie's sky depends on the ground albedo: the one given, where it is a number.
    if (albedo.value) o.sky.albedo = *albedo.value;
    prepared = prepare_sky(o.sky, default_site);
    weather = prepared->weather;
    site_source = o.sky.latitude ? "--lat/--lon" : centre ? "the raster's centre" : "the EPW file";
  }
  if (prepared) {
    print_warnings(prepared->warnings);
    prepared->warnings.clear();
  }
  if (!from_file) {
    ThreadLimit limit(o.job.out.threads);
    sky.map = make_exposure_map(*prepared, o.map_size);
    print_warnings(prepared->warnings);
    sky_meta = prepared->metadata;
  }
  const double global_horizontal = sky.map.irradiation(ExposureBand::global, Direction{0, 0, 1});
  if (!(global_horizontal > 0.0)) {
    const std::string period =
        sky_meta.count("FROM_UTC") ? " from " + sky_meta["FROM_UTC"] + " to " + sky_meta["TO_UTC"] : "";
    throw Error("no daylight at " + sky_meta["LATITUDE"] + ", " + sky_meta["LONGITUDE"] + period +
                ": the sun stays below the horizon and the sky is dark");
  }
  if (exact) sky.sun = sun_steps(*prepared->model, prepared->steps);
  // The site of the sky against the raster's.
  const GeoPoint sky_site{std::strtod(sky_meta["LATITUDE"].c_str(), nullptr),
                          std::strtod(sky_meta["LONGITUDE"].c_str(), nullptr)};
  if (centre) {
    const double apart = angular_distance_deg(sky_site, *centre);
    if (apart > kMaxSiteDistanceDeg && !o.allow_site_mismatch) {
      throw Error("the sky is made for " + number_text(sky_site.latitude_deg) + ", " +
                  number_text(sky_site.longitude_deg) + " (" + site_source + "), " + number_text(std::round(apart)) +
                  " degrees from the raster's centre " + number_text(centre->latitude_deg) + ", " +
                  number_text(centre->longitude_deg) + "; give --allow-site-mismatch if that is meant");
    }
    // The weather measured at the EPW's site is the sky's too.
    if (weather) {
      const GeoPoint station{weather->location.latitude_deg, weather->location.longitude_deg};
      const double off = angular_distance_deg(station, *centre);
      if (off > kMaxSiteDistanceDeg && !o.allow_site_mismatch) {
        throw Error("the weather file was measured at " + number_text(station.latitude_deg) + ", " +
                    number_text(station.longitude_deg) + ", " + number_text(std::round(off)) +
                    " degrees from the raster's centre " + number_text(centre->latitude_deg) + ", " +
                    number_text(centre->longitude_deg) + "; give --allow-site-mismatch if that is meant");
      }
    }
    meta["RASTER_CENTRE_LAT_LON"] = number_text(centre->latitude_deg) + ", " + number_text(centre->longitude_deg);
  } else if (from_file) {
    std::fprintf(stderr, "Warning: '%s' has no CRS: the sky map's site (%s, %s) cannot be checked against it\n",
                 o.job.input.c_str(), number_text(sky_site.latitude_deg).c_str(),
                 number_text(sky_site.longitude_deg).c_str());
  }
  refuse_unused(app, "--allow-site-mismatch", true, "");

  ExposureRequest request;
  request.method = exact ? ExposureMethod::exact : ExposureMethod::fast;
  request.sampler.reads = o.reads == "mipmap" ? SamplerReads::mipmap : SamplerReads::area;
  request.edge = job.edge;
  std::string albedo_source;
  if (albedo.value) {
    request.albedo = *albedo.value;
    albedo_source = "--albedo";
  } else if (!albedo.raster.empty()) {
    if (job.tiles.tiled) {  // each tile reads its window of it
      const RasterSize size = raster_size(albedo.raster, 1);
      check_albedo_grid(albedo.raster, size.width, size.height, read_band(albedo.raster, 1, {0, 0, 1, 1}).georef, width,
                        height, job.georef());
    } else {
      RasterBand band = read_band(albedo.raster, 1);
      check_albedo_grid(albedo.raster, band.values.width(), band.values.height(), band.georef, width, height, t.georef);
      request.albedo_grid = checked_albedo(std::move(band), albedo.raster);
    }
    albedo_source = "the raster '" + albedo.raster + "'";
  } else if (std::optional<double> a = weather ? mean_albedo(*weather) : std::nullopt) {
    request.albedo = *a;
    albedo_source = "the EPW's albedo field, weighted by global horizontal irradiance";
  } else {
    albedo_source = "default";
  }

  for (const auto& [key, value] : sky_meta) {
    if (key.rfind("SKYVIEW_", 0) == 0) continue;  // the map file's own command and version
    meta["SKY_" + key] = value;
  }
  if (from_file) meta["SKYMAP"] = o.skymap;
  meta["SITE_SOURCE"] = site_source;
  meta["EXPOSURE_METHOD"] = o.method;
  meta["EXPOSURE_CITATION"] =
      exact ? "beam of every time step against the horizon interpolated at the sun's azimuth; sky radiance summed over "
              "the period integrated over the visible sky at the map's resolution with the exact cosine"
            : "Section 6 of Munoz-Pandiella et al., Solar exposure of complex cities (exposure map sampled per "
              "horizon direction, Eqs. 7-10)";
  if (!exact) meta["EXPOSURE_SAMPLER_READS"] = o.reads;
  meta["EXPOSURE_MAP_SIZE"] = std::to_string(sky.map.width()) + "x" + std::to_string(sky.map.height());
  meta["ALBEDO"] = albedo.raster.empty() ? number_text(request.albedo) : "per cell";
  meta["ALBEDO_SOURCE"] = albedo_source;
  meta["GLOBAL_HORIZONTAL_UNOBSTRUCTED_KWH_M2"] = number_text(global_horizontal / 1000);
  meta["UNITS"] = "kWh m-2 over the period (svf: 1)";
  meta["PERIOD"] = sky_meta.count("FROM_UTC") ? sky_meta["FROM_UTC"] + " to " + sky_meta["TO_UTC"] + " (excluded)"
                                              : "the EPW file's hours (" + sky_meta["EPW"] + ")";

  // The summary line, whole or tiled: the mean of the total band's valid cells.
  auto print_summary = [&](double sum, std::int64_t valid, const std::string& tiles) {
    char what[256];
    std::snprintf(what, sizeof what,
                  "%dx%d cells by %s with %d directions%s; unobstructed global horizontal %.1f kWh/m2, mean total "
                  "%.1f kWh/m2",
                  width, height, o.method.c_str(), job.engine->params().directions, tiles.c_str(),
                  global_horizontal / 1000, valid ? sum / valid : 0.0);
    summary.print(what, o.job.out.quiet);
  };
  auto warn_albedo_nodata = [&](std::int64_t cells) {
    if (cells > 0) {
      std::fprintf(stderr, "Warning: %lld cells have no albedo in '%s': their reflected and total bands are nodata\n",
                   static_cast<long long>(cells), albedo.raster.c_str());
    }
  };

  if (job.tiles.tiled) {
    std::int64_t albedo_nodata_cells = 0;
    const TileSummary total = run_tiled_exposure(job, o, sky, request, albedo.raster, albedo_nodata_cells);
    warn_albedo_nodata(albedo_nodata_cells);
    print_summary(total.first_band.sum, total.first_band.n,
                  " in " + std::to_string(job.tiles.tiles) + " tiles of " + std::to_string(job.tiles.tile_size) +
                      " cells (halo " + std::to_string(job.tiles.halo) +
                      (job.tiles.skipped > 0 ? ", " + std::to_string(job.tiles.skipped) + " already finished" : "") +
                      ")");
    return 0;
  }

  ExposureBands bands;
  {
    ThreadLimit limit(o.job.out.threads);
    with_progress(job, [&](ProgressCounter& progress) {
      bands = compute_exposure(*job.engine, t, Window::whole(t), sky, request, progress);
    });
  }
  record_edge_cells(job, bands.edge_cells);
  warn_albedo_nodata(bands.albedo_nodata_cells);

  WriteOptions wo;
  wo.format = o.job.out.format;
  wo.creation_options = o.job.out.creation_options;
  wo.overwrite = o.job.out.overwrite;
  wo.metadata = meta;
  for (const auto& [k, v] : tiling_metadata(job.tiles)) wo.metadata[k] = v;
  std::vector<OutputBand> out;
  for (const BandInfo& b : kBands)
    out.push_back({b.name, b.unit, (bands.*b.grid).data(), {{"DEFINITION", b.definition}}});
  write_bands(o.job.output, width, height, t.georef, out, wo);
  {
    const BandInfo& b = kBands[drawn];
    write_preview(o.preview, bands.*b.grid, {b.name, b.unit, o.job.output, t.georef, {}, {}}, o.job.out.overwrite);
  }
  double sum = 0.0;
  std::int64_t valid = 0;
  for (float v : bands.total.values()) {
    if (!std::isnan(v)) sum += v, ++valid;
  }
  print_summary(sum, valid, "");
  return 0;
}

Runner setup(CLI::App& app) {
  auto o = std::make_shared<Options>();
  o->app = &app;
  o->job.method_option = "--horizon-method";
  o->job.azimuth_origin = "grid";  // exposure sums over azimuth
  add_horizon_job_options(app, o->job);
  add_tiling_options(app, o->tiling.options);
  app.add_option("--method", o->method,
                 "fast: the exposure map sampled per horizon direction (Section 6 of the paper); exact: the beam of "
                 "every time step against the horizon at the sun's azimuth and the sky at the map's full resolution")
      ->capture_default_str();
  app.add_option("--skymap", o->skymap,
                 "A map written by skyview skymap (its sky, site and period), instead of the "
                 "sky options");
  add_sky_options(app, o->sky, "default: the raster's centre; with --epw and no CRS: the file's");
  app.add_option("--map-size", o->map_size, "Width and height of the exposure map made in memory, cells")
      ->capture_default_str();
  app.add_option("--albedo", o->albedo,
                 "Ground albedo for the reflected light (and Hosek-Wilkie's sky): a number 0-1 or a raster on the "
                 "DSM's grid; default: the EPW's albedo field where it has one, else 0.2");
  app.add_flag("--allow-site-mismatch", o->allow_site_mismatch,
               "Accept a sky made for a site more than 1 degree from the raster's centre");
  app.add_option("--reads", o->reads,
                 "fast: how samples read the map: area (exact rectangles, summed-area table) or mipmap (the paper's "
                 "trilinear reads)")
      ->capture_default_str();
  add_preview_options(app, o->preview, "Also write a PNG of the total band, or --preview-band's");
  app.footer(
      "Bands: total, direct, diffuse, reflected (kWh/m2 over the period on each cell's tilted surface), "
      "horizontal_total (kWh/m2 on a horizontal surface at the cell), svf. See docs/commands/exposure.md.");
  return [o] { return run(*o); };
}

const Registration reg("exposure", "Solar exposure (direct, diffuse, reflected) of every DSM cell over a period",
                       setup);

}  // namespace
}  // namespace skyview::cli
