#include "skyview/raster/height_unit.h"

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <cmath>

#include "skyview/core/error.h"
#include "skyview/core/lowercase.h"
#include "skyview/core/number_text.h"

namespace skyview {
namespace {

std::string lower_trimmed(std::string_view name) {
  const std::string s = lowercase(name);
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
      {"us feet", 1200.0 / 3937.0},
      {"usft", 1200.0 / 3937.0},
      {"ft (us)", 1200.0 / 3937.0},
      {"km", 1000.0},
      {"kilometre", 1000.0},
      {"kilometer", 1000.0},
      {"dm", 0.1},
  };
  const std::string key = lower_trimmed(name);
  // The whole name, else its first word ("m asl", "metres above sea level").
  for (const std::string& k : {key, key.substr(0, key.find(' '))}) {
    for (const Known& known : kKnown) {
      if (k == known.name) return known.metres;
    }
  }
  return 0.0;
}

namespace {

// The vertical part's unit of a compound CRS, into `unit`; false when the CRS has no vertical part.
bool vertical_unit(const OGRSpatialReference& crs, HeightUnit& unit) {
  if (!crs.IsVertical()) return false;
  const char* name = nullptr;
  const double metres = crs.GetTargetLinearUnits("VERT_CS", &name);
  if (!(metres > 0.0) || !std::isfinite(metres)) return false;
  unit = {metres, "vertical CRS unit '" + std::string(name ? name : "?") + "'"};
  return true;
}

void check_given(double given) {
  if (!(given >= 0.0) || !std::isfinite(given)) throw UsageError("--z-scale must be a positive number");
}

}  // namespace

HeightUnit height_unit(GDALRasterBand& band, const OGRSpatialReference* crs, double given, const std::string& path) {
  check_given(given);
  if (given > 0.0) return {given, "--z-scale"};
  const std::string unit = band.GetUnitType() ? band.GetUnitType() : "";
  const std::string key = lower_trimmed(unit);
  const bool stated = !key.empty() && key != "unknown" && key != "none" && key != "undefined";
  if (const double metres = stated ? metres_per_height_unit(unit) : 0.0; metres > 0.0)
    return {metres, "band unit '" + unit + "'"};
  HeightUnit vertical;
  if (crs && vertical_unit(*crs, vertical)) return vertical;
  if (stated) {
    throw Error("'" + path + "' gives its heights in '" + unit +
                "', a unit skyview does not know; give --z-scale (metres per unit)");
  }
  return unstated_height_unit(crs, path, "--z-scale");
}

HeightUnit unstated_height_unit(const OGRSpatialReference* crs, const std::string& path, const std::string& option) {
  if (!crs) return {1.0, "metres (assumed: no CRS)"};
  if (crs->IsGeographic()) return {1.0, "metres (assumed: geographic CRS, no height unit stated)"};
  const char* name = nullptr;
  const double metres = crs->GetLinearUnits(&name);
  if (is_metre(metres)) return {1.0, "metres (assumed: the CRS is in metres, no height unit stated)"};
  throw Error("'" + path + "' does not say in which unit its heights are, and its CRS is in " +
              (name ? name : "a unit other than the metre") + " (" + number_text(metres) + " m): give " + option +
              ", metres per height unit (" + number_text(metres) + " if the heights are in " +
              (name ? name : "that unit") + ", 1 if in metres)");
}

HeightUnit cloud_height_unit(const OGRSpatialReference* crs, const OGRSpatialReference* output, double stated,
                             double given) {
  check_given(given);
  if (given > 0.0) return {given, "--points-z-scale"};
  const OGRSpatialReference* frame = crs ? crs : output;
  const std::string whose = crs ? "its CRS's" : "the output CRS's (the cloud has none)";
  HeightUnit vertical;
  if (frame && vertical_unit(*frame, vertical)) return vertical;
  if (stated > 0.0) return {stated, "the file's vertical unit (" + number_text(stated) + " m)"};
  if (!frame) return {1.0, "metres (assumed: no CRS)"};
  if (frame->IsGeographic()) return {1.0, "metres (assumed: geographic CRS)"};
  const char* name = nullptr;
  const double metres = frame->GetLinearUnits(&name);
  if (!(metres > 0.0) || !std::isfinite(metres)) return {1.0, "metres (assumed: " + whose + " unit is unusable)"};
  return {metres, whose + " unit '" + std::string(name ? name : "?") + "'"};
}

}  // namespace skyview
