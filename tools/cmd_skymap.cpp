// skyview skymap: the directional exposure map of the sky over a period (direct and diffuse
// bands, Wh m-2 sr-1, Blinn–Newell longitude/latitude layout) plus a PNG preview.
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "command.h"
#include "sky_job.h"
#include "skyview/core/error.h"
#include "skyview/core/version.h"
#include "skyview/sky/exposure_preview.h"
#include "skyview/sky/skymap_file.h"

namespace skyview::cli {
namespace {

struct SkymapOptions {
  SkyRequest sky;
  std::string output, preview;
  int size = ExposureOptions{}.width;
  bool no_preview = false;
  OutputOptions out;
  const CLI::App* app = nullptr;
};

int run(const SkymapOptions& o) {
  const auto started = std::chrono::steady_clock::now();
  check_sky_options(*o.app, o.sky);
  if (o.size < 8 || o.size > 8192) throw UsageError("--size must be within 8 .. 8192");
  refuse_unused(*o.app, "--albedo", o.sky.sky == "hosek", "--sky hosek");
  refuse_unused(*o.app, "--preview", !o.no_preview, "runs without --no-preview");
  if (!o.preview.empty()) require_extension(o.preview, {".png"}, "--preview");
  const std::string preview =
      o.no_preview
          ? ""
          : (o.preview.empty() ? std::filesystem::path(o.output).replace_extension(".png").string() : o.preview);
  if (!preview.empty() && preview == o.output) throw Error("the preview would overwrite OUT; give --preview");
  make_sky_model(o.sky);  // its options' errors before the outputs'
  check_outputs_apart({o.output, preview}, {o.sky.epw});
  check_output_writable(o.output, o.out.overwrite);
  check_output_format(o.output, o.out.format, 2, o.out.creation_options);
  if (!preview.empty()) check_output_writable(preview, o.out.overwrite);

  PreparedSky sky = prepare_sky(o.sky);
  print_warnings(sky.warnings);
  sky.warnings.clear();
  ThreadLimit limit(o.out.threads);
  const ExposureMap map = make_exposure_map(sky, o.size);
  print_warnings(sky.warnings);

  WriteOptions wo;
  wo.format = o.out.format;
  wo.creation_options = o.out.creation_options;
  wo.overwrite = o.out.overwrite;
  wo.metadata = sky.metadata;
  wo.metadata["SKYVIEW_VERSION"] = version();
  wo.metadata["SKYVIEW_COMMAND"] = command_line();
  write_skymap(o.output, map, wo);
  if (!preview.empty()) write_exposure_preview(preview, map, o.out.overwrite);
  if (!o.out.quiet) {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    const Direction up{0, 0, 1};
    const double direct_h = map.irradiation(ExposureBand::direct, up);
    const double diffuse_h = map.irradiation(ExposureBand::diffuse, up);
    std::fprintf(stderr,
                 "skyview skymap: %zu steps, horizontal exposure %.1f kWh/m2 (direct %.1f, diffuse %.1f%s), %.2f s\n",
                 sky.steps.size(), (direct_h + diffuse_h) / 1000, direct_h / 1000, diffuse_h / 1000,
                 o.sky.sky == "hosek" ? "; 320-720 nm only" : "", seconds);
  }
  return 0;
}

Runner setup(CLI::App& app) {
  auto o = std::make_shared<SkymapOptions>();
  o->app = &app;
  app.add_option("OUT", o->output, "Output raster (bands direct, diffuse)")->required();
  add_sky_options(app, o->sky, "default with --epw: the file's");
  app.add_option("--albedo", o->sky.albedo, "Ground albedo for hosek, 0-1")->capture_default_str();
  app.add_option("--size", o->size, "Map width and height in cells")->capture_default_str();
  app.add_option("--preview", o->preview, "PNG preview path (default: OUT with .png)");
  app.add_flag("--no-preview", o->no_preview, "Do not write the PNG preview");
  add_output_options(app, o->out);
  app.footer(
      "Bands: 1 direct, 2 diffuse, radiant exposure per unit solid angle (Wh m-2 sr-1). Layout: columns = azimuth "
      "clockwise from north (N at the left edge, S in the middle), rows = zenith angle (zenith at the top, horizon "
      "at the bottom). See docs/sky.md.");
  return [o] { return run(*o); };
}

const Registration reg("skymap", "Directional exposure map of the sky over a period (sun and sky models, EPW data)",
                       setup);

}  // namespace
}  // namespace skyview::cli
