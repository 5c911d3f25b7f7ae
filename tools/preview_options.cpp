#include "preview_options.h"

#include <cmath>
#include <filesystem>

#include "skyview/core/error.h"

namespace skyview::cli {

namespace {

// Why `text` is no range MIN,MAX ("" if it is one), with the limits read into lo and hi.
std::string range_problem(const std::string& text, double& lo, double& hi) {
  const std::size_t comma = text.find(',');
  const auto number = [](const std::string& part, double& x) {
    std::size_t used = 0;
    try {
      x = std::stod(part, &used);
    } catch (const std::exception&) {
      return false;
    }
    // Blanks around a number are fine ("0, 1"): stod skips those before it, this those after.
    while (used < part.size() && part[used] == ' ') ++used;
    return used == part.size() && std::isfinite(x);
  };
  if (comma == std::string::npos || text.find(',', comma + 1) != std::string::npos ||
      !number(text.substr(0, comma), lo) || !number(text.substr(comma + 1), hi)) {
    return "'" + text + "' is not two numbers MIN,MAX (e.g. 0,1)";
  }
  if (!(lo < hi)) return "'" + text + "': MIN must be below MAX";
  return "";
}

}  // namespace

void add_preview_options(CLI::App& app, PreviewOptions& o, const std::string& help) {
  app.add_option("--preview", o.path, help);
  app.add_option("--preview-range", o.range,
                 "The preview's colour ramp from MIN to MAX (e.g. 0,1), so that previews compare; default: the 2nd "
                 "to 98th percentile of the band drawn")
      ->check(CLI::Validator(
          [](std::string& text) {
            double lo = 0, hi = 0;
            return range_problem(text, lo, hi);
          },
          "MIN,MAX"));
  app.add_option("--preview-band", o.band, "The band the preview draws, by name (default: the first written)");
}

std::pair<double, double> parse_preview_range(const std::string& text) {
  double lo = 0, hi = 0;
  const std::string problem = range_problem(text, lo, hi);
  if (!problem.empty()) throw UsageError("--preview-range: " + problem);
  return {lo, hi};
}

std::size_t check_preview_options(const CLI::App& app, const PreviewOptions& o, const std::vector<std::string>& bands,
                                  std::size_t default_band) {
  refuse_unused(app, "--preview-range", !o.path.empty(), "runs with --preview");
  refuse_unused(app, "--preview-band", !o.path.empty(), "runs with --preview");
  if (o.path.empty()) return default_band;
  require_extension(o.path, {".png"}, "--preview");
  if (o.band.empty()) return default_band;
  for (std::size_t i = 0; i < bands.size(); ++i)
    if (bands[i] == o.band) return i;
  std::string list;
  for (const std::string& b : bands) list += (list.empty() ? "" : ", ") + b;
  throw UsageError("--preview-band '" + o.band + "' is not a band of the output; it holds " + list);
}

void write_preview(const PreviewOptions& o, const Grid<float>& values, const PreviewBand& band, bool overwrite) {
  if (o.path.empty()) return;
  PreviewSpec spec;
  spec.band = band.name;
  spec.unit = band.unit;
  spec.title = band.name + " - " + std::filesystem::path(band.output).filename().string();
  spec.ramp = band.ramp ? *band.ramp : ramp_for_band(band.name, band.unit);
  spec.range = o.range.empty() ? band.fixed_range : std::optional(parse_preview_range(o.range));
  spec.georef = band.georef;
  write_raster_preview(o.path, values, spec, overwrite);
}

}  // namespace skyview::cli
