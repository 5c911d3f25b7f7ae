// skyview skymap: the directional exposure map of the sky over a period (direct and diffuse
// bands, Wh m-2 sr-1, Blinn–Newell longitude/latitude layout) plus a PNG preview.
#include <cstdio>
#include <filesystem>

#include "command.h"
#include "preview_options.h"
#include "sky_job.h"
#include "skyview/core/error.h"
#include "skyview/core/version.h"
#include "skyview/sky/exposure_preview.h"
#include "skyview/sky/skymap_file.h"

namespace skyview::cli {
namespace {

struct SkymapOptions {
  SkyRequest sky;
  std::string output;
  PreviewOptions preview;
  int size = ExposureOptions{}.width;
  bool no_preview = false;
  OutputOptions out;
  const CLI::App* app = nullptr;
};

int run(const SkymapOptions& o) {
  const RunSummary summary("skymap");
  check_sky_options(*o.app, o.sky);
  if (o.size < 8 || o.size > 8192) throw UsageError("--size must be within 8 .. 8192");
  refuse_unused(*o.app, "--albedo", o.sky.sky == "hosek", "--sky hosek");
  refuse_unused(*o.app, "--preview", !o.no_preview, "runs without --no-preview");
  // The preview is on by default here (OUT with .png): the map is hard to read as numbers.
  PreviewOptions shown = o.preview;
  if (!o.no_preview && shown.path.empty())
    shown.path = std::filesystem::path(o.output).replace_extension(".png").string();
  if (o.no_preview) shown.path.clear();
  const std::string& preview = shown.path;
  const std::vector<std::string> band_names{"direct", "diffuse"};
  const std::size_t drawn = check_preview_options(*o.app, shown, band_names);
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
  if (!preview.empty() && shown.band.empty()) {
    // Both bands, one above the other, unless --preview-band asks for one.
    write_exposure_preview(preview, map, o.out.overwrite,
                           shown.range.empty() ? std::nullopt : std::optional(parse_preview_range(shown.range)));
  } else if (!preview.empty()) {
    const ExposureBand band = drawn == 0 ? ExposureBand::direct : ExposureBand::diffuse;
    std::vector<float> values = map.band(band);
    write_preview(shown, Grid<float>(map.width(), map.height(), std::move(values)),
                  {band_names[drawn], "Wh m-2 sr-1", o.output, GeoReference{}, ColourRamp::magma, {}}, o.out.overwrite);
  }
  {
    const Direction up{0, 0, 1};
    const double direct_h = map.irradiation(ExposureBand::direct, up);
    const double diffuse_h = map.irradiation(ExposureBand::diffuse, up);
    char what[200];
    std::snprintf(what, sizeof what, "%zu steps, horizontal exposure %.1f kWh/m2 (direct %.1f, diffuse %.1f%s)",
                  sky.steps.size(), (direct_h + diffuse_h) / 1000, direct_h / 1000, diffuse_h / 1000,
                  o.sky.sky == "hosek" ? "; 320-720 nm only" : "");
    summary.print(what, o.out.quiet);
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
  add_preview_options(app, o->preview,
                      "PNG preview path (default: OUT with .png): both bands, or --preview-band's alone");
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
