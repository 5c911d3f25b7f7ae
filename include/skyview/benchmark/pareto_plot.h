#pragma once
// Speed against error as a picture: every benchmark's time-against-error plot on log axes, one
// colour per series, the Pareto front (no other point both faster and more accurate) joined.
#include <array>
#include <string>
#include <utility>
#include <vector>

namespace skyview {

struct ParetoPoint {
  std::string series;
  double seconds = 0, error = 0;
  bool pareto = false;
};

// Marks each point that no other point beats in both time and error (ties in one, better in the other).
void mark_pareto(std::vector<ParetoPoint>& points);

// A series and its colour (blue, green, red, 0-255); series not listed are drawn black.
using SeriesColour = std::pair<std::string, std::array<int, 3>>;

// Writes the plot as write_output_file writes (refused if `png_path` exists and !overwrite).
// `error_label` names the y axis; errors below 1e-5 are drawn at 1e-5.
void plot_pareto(const std::string& png_path, const std::string& title, const std::string& error_label,
                 const std::vector<ParetoPoint>& points, const std::vector<SeriesColour>& colours, bool overwrite);

}  // namespace skyview
