#include "skyview/height_unit.h"

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cctype>
#include <cmath>

#include "skyview/error.h"
#include "skyview/number_text.h"

namespace skyview {
namespace {

std::string lower_trimmed(std::string_view name) {
  std::string s;
  for (const char c : name) s += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t") - first + 1);
}

bool is_metre(double metres) { return std::abs(metres - 1.0) < 1e-12; }

}  // namespace

double metres_per_height_unit(std::string_view name) {
  // The US survey foot is 1200/3937 m exactly; the international foot 0.3048 m.
  struct Known {
    const char* name;
    double metres;
  };
  static constexpr Known kKnown[] = {
      {"m", 1.0},
      {"metre", 1.0},
      {"metres", 1.0},
      {"meter", 1.0},
      {"meters", 1.0},
      {"cm", 0.01},
      {"centimetre", 0.01},
      {"centimeter", 0.01},
      {"mm", 0.001},
      {"millimetre", 0.001},
      {"millimeter", 0.001},
      {"ft", 0.3048},
      {"foot", 0.3048},
      {"feet", 0.3048},
      {"international foot", 0.3048},
      {"foot (international)", 0.3048},
      {"us survey foot", 1200.0 / 3937.0},
      {"us survey feet", 1200.0 / 3937.0},
      {"foot_us", 1200.0 / 3937.0},
      {"ftus", 1200.0 / 3937.0},
      {"us-ft", 1200.0 / 3937.0},
      {"us_survey_foot", 1200.0 / 3937.0},
  };
  const std::string key = lower_trimmed(name);
  for (const Known& k : kKnown) {
    if (key == k.name) return k.metres;
  }
  return 0.0;
}

HeightUnit height_unit(GDALRasterBand& band, const OGRSpatialReference* crs, double given, const std::string& path) {
  if (!(given >= 0.0) || !std::isfinite(given)) throw Error("--z-scale must be a positive number");
  if (given > 0.0) return {given, "--z-scale"};
  const std::string unit = band.GetUnitType() ? band.GetUnitType() : "";
  if (!lower_trimmed(unit).empty()) {
    const double metres = metres_per_height_unit(unit);
    if (metres == 0.0) {
      throw Error("'" + path + "' gives its heights in '" + unit +
                  "', a unit skyview does not know; give --z-scale (metres per unit)");
    }
    return {metres, "band unit '" + unit + "'"};
  }
  if (!crs) return {1.0, "metres (assumed: no CRS)"};
  const char* name = nullptr;
  if (crs->IsVertical()) {
    const double metres = crs->GetTargetLinearUnits("VERT_CS", &name);
    if (metres > 0.0 && std::isfinite(metres)) {
      return {metres, "vertical CRS unit '" + std::string(name ? name : "?") + "'"};
    }
  }
  if (crs->IsGeographic()) return {1.0, "metres (assumed: geographic CRS, no height unit stated)"};
  const double metres = crs->GetLinearUnits(&name);
  if (is_metre(metres)) return {1.0, "metres (assumed: the CRS is in metres, no height unit stated)"};
  throw Error("'" + path + "' does not say in which unit its heights are, and its CRS is in " +
              (name ? name : "a unit other than the metre") + " (" + number_text(metres) +
              " m): give --z-scale, metres per height unit (" + number_text(metres) + " if the heights are in " +
              (name ? name : "that unit") + ", 1 if in metres)");
}

}  // namespace skyview
