// skyview sunhours: hours of direct sun on every DSM cell over a period (docs/commands/sunhours.md).
#include <cmath>
#include <cstdio>
#include <optional>

#include "horizon_job.h"
#include "preview_options.h"
#include "sky_job.h"
#include "skyview/core/error.h"
#include "skyview/core/number_text.h"
#include "skyview/exposure/sun_hours.h"
#include "skyview/solar/time_parse.h"

namespace skyview::cli {
namespace {

struct Options {
  HorizonJobOptions job;
  std::string from, to, step = "10m", tz;
  PreviewOptions preview;
  std::optional<double> lat, lon, elevation;
  const CLI::App* app = nullptr;
};

int run(const Options& o) {
  const RunSummary summary("sunhours");
  refuse_unused(*o.app, "--max-error", false, "skyview svf");
  if (!o.tz.empty()) check_time_zone(o.tz);
  const double from = parse_time_option(o.from, o.tz).unix_utc, to = parse_time_option(o.to, o.tz).unix_utc;
  if (!(to > from)) throw Error("the period is empty: --to must be later than --from");
  const double step_s = parse_duration_option(o.step);
  if (!(step_s < to - from))
    throw UsageError("--step " + o.step + " is not shorter than the period from --from to --to");
  const std::size_t drawn = check_preview_options(*o.app, o.preview, {"sun_hours", "first_sun", "last_sun"});
  check_outputs_apart({o.job.output, o.preview.path}, {o.job.input});
  HorizonJob job = prepare_horizon_job(o.job, "sunhours", {o.preview.path});
  check_output_format(o.job.output, o.job.out.format, 3, o.job.out.creation_options);
  const Terrain& t = job.terrain;
  std::string site_source;
  const Site site = raster_sun_site(t, o.job.input, o.lat, o.lon, o.elevation, site_source);
  const std::vector<SunStep> steps = daylight_steps(site, from, to, step_s);
  if (steps.empty()) {
    throw Error("no daylight at " + number_text(site.latitude_deg) + ", " + number_text(site.longitude_deg) + " from " +
                format_iso_utc(from) + " to " + format_iso_utc(to) +
                ": the sun's centre stays below the "
                "horizon");
  }
  SunHoursBands bands;
  {
    ThreadLimit limit(o.job.out.threads);
    with_progress(job, [&](ProgressCounter& progress) {
      bands = compute_sun_hours(*job.engine, t, Window::whole(t), steps, from, progress);
    });
  }
  auto& meta = job.metadata;
  meta["FROM"] = o.from;
  meta["TO"] = o.to;
  meta["FROM_UTC"] = format_iso_utc(from);
  meta["TO_UTC"] = format_iso_utc(to);
  if (!o.tz.empty()) meta["TIME_ZONE"] = o.tz;
  meta["STEP"] = o.step;
  meta["DAYLIGHT_STEPS"] = std::to_string(steps.size());
  meta["LATITUDE"] = number_text(site.latitude_deg);
  meta["LONGITUDE"] = number_text(site.longitude_deg);
  meta["SITE_SOURCE"] = site_source;
  meta["SUN_POSITION"] = "NREL SPA at each step's middle, topocentric, refracted (15 C, 1013.25 mbar)";
  meta["SUN_TEST"] =
      "the sun's centre above the horizon interpolated between the two directions either side of "
      "its azimuth";
  meta["UNITS"] = "hours; first_sun and last_sun from FROM (" + format_iso_utc(from) + ")";

  WriteOptions wo;
  wo.format = o.job.out.format;
  wo.creation_options = o.job.out.creation_options;
  wo.overwrite = o.job.out.overwrite;
  wo.metadata = meta;
  write_bands(o.job.output, t.width(), t.height(), t.georef,
              {{"sun_hours", "hours", bands.sun_hours.data(), {{"DEFINITION", "hours with the sun's centre seen"}}},
               {"first_sun",
                "hours",
                bands.first_sun.data(),
                {{"DEFINITION", "hours from the period's start to the start of the first sunlit step (nodata: none)"}}},
               {"last_sun",
                "hours",
                bands.last_sun.data(),
                {{"DEFINITION", "hours from the period's start to the end of the last sunlit step (nodata: none)"}}}},
              wo);
  {
    const Grid<float>* drawn_band[] = {&bands.sun_hours, &bands.first_sun, &bands.last_sun};
    const char* names[] = {"sun_hours", "first_sun", "last_sun"};
    write_preview(o.preview, *drawn_band[drawn], {names[drawn], "hours", o.job.output, t.georef, {}, {}},
                  o.job.out.overwrite);
  }
  {
    double sum = 0, most = 0;
    std::int64_t valid = 0;
    for (float v : bands.sun_hours.values()) {
      if (!std::isnan(v)) sum += v, ++valid, most = std::max<double>(most, v);
    }
    char what[200];
    std::snprintf(what, sizeof what, "%dx%d cells, %zu daylight steps, %d directions; mean %.2f h of sun (most %.2f h)",
                  t.width(), t.height(), steps.size(), job.engine->params().directions, valid ? sum / valid : 0.0,
                  most);
    summary.print(what, o.job.out.quiet);
  }
  return 0;
}

Runner setup(CLI::App& app) {
  auto o = std::make_shared<Options>();
  o->app = &app;
  // The horizon is interpolated between directions towards each step's sun: more of them than the
  // sky-view factor needs.
  o->job.params.directions = 64;
  o->job.azimuth_origin = "grid";
  add_horizon_job_options(app, o->job);
  app.add_option("--from", o->from, "Start, ISO 8601 with offset or zone (as skyview sun)")->required();
  app.add_option("--to", o->to, "End (excluded)")->required();
  app.add_option("--step", o->step, "Time step: 10m, 1h, ...; each step's sun at its middle")->capture_default_str();
  app.add_option("--tz", o->tz, "IANA zone for --from/--to without an offset");
  app.add_option("--lat", o->lat, "Latitude, degrees north (default: the raster's centre)");
  app.add_option("--lon", o->lon, "Longitude, degrees east (default: the raster's centre)");
  app.add_option("--elevation", o->elevation, "Elevation above sea level, metres (default: the raster's centre)");
  add_preview_options(app, o->preview, "Also write a PNG of the sun_hours band, or --preview-band's");
  app.footer(
      "Bands: sun_hours, first_sun, last_sun (hours; the last two from the period's start). See "
      "docs/commands/sunhours.md.");
  return [o] { return run(*o); };
}

const Registration reg("sunhours", "Hours of direct sun on every DSM cell over a period, first and last sun", setup);

}  // namespace
}  // namespace skyview::cli
