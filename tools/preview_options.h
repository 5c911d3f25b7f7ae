#pragma once
// The preview options every raster-writing command shares (--preview, --preview-range,
// --preview-band) and the one way they become a PNG (docs/previews.md).
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "command.h"
#include "skyview/core/grid.h"
#include "skyview/preview/raster_preview.h"

namespace skyview::cli {

struct PreviewOptions {
  std::string path;   // --preview; empty: none
  std::string range;  // --preview-range MIN,MAX as typed
  std::string band;   // --preview-band; empty: the command's default band
};

// Adds --preview (described by `help`), --preview-range and --preview-band; a range that cannot be
// read fails while parsing (exit 2).
void add_preview_options(CLI::App& app, PreviewOptions& o, const std::string& help);

// "MIN,MAX" as numbers with MIN < MAX, both finite. Throws UsageError naming --preview-range.
std::pair<double, double> parse_preview_range(const std::string& text);

// Checks the options before the run's work: --preview-range and --preview-band only with
// --preview, a .png name, and a band among `bands` (the names the output will hold, in order).
// Returns the index of the band to draw: --preview-band's, else `default_band`. Throws UsageError.
std::size_t check_preview_options(const CLI::App& app, const PreviewOptions& o, const std::vector<std::string>& bands,
                                  std::size_t default_band = 0);

// What the preview draws, beyond the values: the band's name and unit, the raster written (for
// the title) and where it lies.
struct PreviewBand {
  std::string name, unit;
  std::string output;  // the raster written; its file name goes in the title
  GeoReference georef;
  // The ramp where the band's name and unit do not choose the right one (ramp_for_band).
  std::optional<ColourRamp> ramp;
  // Limits the quantity cannot leave (0 and 1 for a sunlit mask), used without --preview-range.
  std::optional<std::pair<double, double>> fixed_range;
};

// Writes o.path (nothing without --preview): `values` under the ramp of `band`, its range from
// --preview-range, else band.fixed_range, else the stretch.
void write_preview(const PreviewOptions& o, const Grid<float>& values, const PreviewBand& band, bool overwrite);

}  // namespace skyview::cli
