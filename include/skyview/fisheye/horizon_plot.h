#pragma once
// Polar plots of observers' horizons (`skyview points --profile-png`): one panel per observer, the
// sky as an upward-looking equidistant fish-eye sees it (north up, east left, rings at 30° and 60°
// zenith angle), the terrain below its horizon filled grey, the horizon line, and the observer's
// label and svf.
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

namespace skyview {

constexpr std::size_t kMaxHorizonPlots = 64;

struct HorizonPlot {
  std::string label;
  std::vector<float> horizons;  // radians, n uniform sectors; empty: "no values"
  double rotation = 0;          // azimuth of sector 0
  double svf = std::numeric_limits<double>::quiet_NaN();
};

// Panels in rows of up to four, written as one PNG under a temporary name renamed into place.
// Throws skyview::Error for more than kMaxHorizonPlots plots, or if `path` exists and !overwrite.
void write_horizon_plots(const std::string& path, const std::vector<HorizonPlot>& plots, bool overwrite);

}  // namespace skyview
