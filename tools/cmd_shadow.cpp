// skyview shadow: where the sun is seen from every DSM cell at one instant (docs/commands/shadow.md).
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>

#include "horizon_job.h"
#include "preview_options.h"
#include "sky_job.h"
#include "skyview/core/error.h"
#include "skyview/core/number_text.h"
#include "skyview/exposure/shadow.h"
#include "skyview/solar/solar_position.h"
#include "skyview/solar/time_parse.h"

namespace skyview::cli {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

struct Options {
  HorizonJobOptions job;
  std::string time, tz;
  PreviewOptions preview;
  std::optional<double> lat, lon, elevation;
  bool soft = false;
  const CLI::App* app = nullptr;
};

int run(const Options& o) {
  const RunSummary summary("shadow");
  const CLI::App& app = *o.app;
  // The one direction is the sun's: nothing of the direction set applies.
  for (const char* name : {"--directions", "--azimuth-origin", "--azimuths", "--max-error"})
    refuse_unused(app, name, false, "commands with many directions (a shadow is found along the sun's azimuth)");
  if (!o.tz.empty()) check_time_zone(o.tz);
  const ParsedTime when = parse_time_option(o.time, o.tz);
  const char* first = o.soft ? "sun_fraction" : "sunlit";
  const std::size_t drawn = check_preview_options(app, o.preview, {first, "incidence_cos"});
  check_outputs_apart({o.job.output, o.preview.path}, {o.job.input});
  HorizonJob job = prepare_horizon_job(o.job, "shadow", {o.preview.path});
  check_output_format(o.job.output, o.job.out.format, 2, o.job.out.creation_options);
  const Terrain& t = job.terrain;
  std::string site_source;
  const Site site = raster_sun_site(t, o.job.input, o.lat, o.lon, o.elevation, site_source);
  const SunPosition sun = solar_position(when.unix_utc, site);
  require_sun_up(sun, when.unix_utc, site);
  // The engine again, turned to the sun.
  job.engine =
      make_horizon_engine(job.engine->name(), shadow_horizon_params(job.engine->params(), sun.azimuth_deg * kDegree));
  ShadowRequest request;
  request.sun_azimuth = sun.azimuth_deg * kDegree;
  request.sun_elevation = sun.elevation_deg * kDegree;
  request.soft = o.soft;
  request.edge = job.edge;
  ShadowBands bands;
  {
    ThreadLimit limit(o.job.out.threads);
    with_progress(job, [&](ProgressCounter& progress) {
      bands = compute_shadow(*job.engine, t, Window::whole(t), request, progress);
    });
  }
  record_edge_cells(job, bands.edge_cells);
  auto& meta = job.metadata;
  for (const char* key : {"DIRECTIONS", "AZIMUTH_ORIGIN", "AZIMUTHS", "SECTOR_ROTATION_DEG"}) meta.erase(key);
  add_sun_instant_metadata(meta, o.time, o.tz, when.unix_utc, site, site_source, sun);
  meta["SHADOW_TEST"] = o.soft ? "visible share of the solar disc (radius 0.2665 deg) above the horizon along the "
                                 "sun's azimuth, taken level across the disc"
                               : "the sun's centre above the horizon along the sun's azimuth";

  WriteOptions wo;
  wo.format = o.job.out.format;
  wo.creation_options = o.job.out.creation_options;
  wo.overwrite = o.job.out.overwrite;
  wo.metadata = meta;
  write_bands(
      o.job.output, t.width(), t.height(), t.georef,
      {{first,
        "1",
        bands.sunlit.data(),
        {{"DEFINITION", o.soft ? "share of the solar disc seen, 0..1" : "1 where the sun's centre is seen, else 0"}}},
       {"incidence_cos",
        "1",
        bands.incidence_cos.data(),
        {{"DEFINITION",
          "cosine of the sun's direction on the cell's surface (Horn normal); below 0 the "
          "surface faces away from the sun"}}}},
      wo);
  if (drawn == 0) {
    // Sunlit and shaded are the ends of a fixed 0..1 ramp: a stretch of a mask means nothing.
    write_preview(o.preview, bands.sunlit, {first, "1", o.job.output, t.georef, ColourRamp::grey, std::pair{0.0, 1.0}},
                  o.job.out.overwrite);
  } else {
    write_preview(o.preview, bands.incidence_cos,
                  {"incidence_cos", "1", o.job.output, t.georef, ColourRamp::diverging, std::pair{-1.0, 1.0}},
                  o.job.out.overwrite);
  }
  {
    double lit = 0;
    std::int64_t valid = 0;
    for (float v : bands.sunlit.values()) {
      if (!std::isnan(v)) lit += v, ++valid;
    }
    char what[200];
    std::snprintf(what, sizeof what, "sun at azimuth %.2f, elevation %.2f deg; %.1f%% of %lld cells sunlit",
                  sun.azimuth_deg, sun.elevation_deg, valid ? 100.0 * lit / valid : 0.0, static_cast<long long>(valid));
    summary.print(what, o.job.out.quiet);
  }
  return 0;
}

Runner setup(CLI::App& app) {
  auto o = std::make_shared<Options>();
  o->app = &app;
  add_horizon_job_options(app, o->job);
  app.add_option("--time", o->time, "The instant, ISO 8601 with offset or zone (as skyview sun)")->required();
  app.add_option("--tz", o->tz, "IANA zone for --time without an offset");
  app.add_option("--lat", o->lat, "Latitude, degrees north (default: the raster's centre)");
  app.add_option("--lon", o->lon, "Longitude, degrees east (default: the raster's centre)");
  app.add_option("--elevation", o->elevation, "Elevation above sea level, metres (default: the raster's centre)");
  app.add_flag("--soft", o->soft, "Band sun_fraction: the visible share of the solar disc instead of its centre");
  add_preview_options(app, o->preview, "Also write a PNG of the first band, or --preview-band's");
  app.footer(
      "Bands: sunlit (1 where the sun's centre is seen, else 0) or, with --soft, sun_fraction (0..1); incidence_cos. "
      "See docs/commands/shadow.md.");
  return [o] { return run(*o); };
}

const Registration reg("shadow", "Where the sun is seen from every DSM cell at one instant (shadows)", setup);

}  // namespace
}  // namespace skyview::cli
