#include "scene/scene_crs.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "skyview/core/error.h"
#include "skyview/raster/raster_io.h"

namespace skyview {
namespace {

// The AdV's (German surveying authorities') CRS names, which PROJ does not know, as EPSG codes.
std::string adv_as_epsg(const std::string& text) {
  const std::string prefix = "urn:adv:crs:";
  if (text.rfind(prefix, 0) != 0) return "";
  static const std::map<std::string, std::string> horizontal = {{"ETRS89_UTM32", "25832"}, {"ETRS89_UTM33", "25833"},
                                                                {"DE_DHDN_3GK2", "31466"}, {"DE_DHDN_3GK3", "31467"},
                                                                {"DE_DHDN_3GK4", "31468"}, {"DE_DHDN_3GK5", "31469"}};
  static const std::map<std::string, std::string> vertical = {{"DE_DHHN92_NH", "5783"}, {"DE_DHHN2016_NH", "7837"}};
  const std::string rest = text.substr(prefix.size());
  const std::size_t star = rest.find('*');
  const auto h = horizontal.find(rest.substr(0, star));
  if (h == horizontal.end()) return "";
  if (star == std::string::npos) return "EPSG:" + h->second;
  const auto v = vertical.find(rest.substr(star + 1));
  return "EPSG:" + h->second + (v == vertical.end() ? "" : "+" + v->second);
}

}  // namespace

OGRSpatialReference scene_crs(const std::string& text, const std::string& what) {
  init_gdal();
  OGRSpatialReference s;
  const std::string adv = adv_as_epsg(text);
  if (text.empty() || s.SetFromUserInput((adv.empty() ? text : adv).c_str()) != OGRERR_NONE) {
    throw Error("cannot understand the CRS of " + what + " ('" + text.substr(0, 80) + "')");
  }
  s.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  return s;
}

std::string crs_display_name(const std::string& text) {
  if (text.empty()) return "none (local metres)";
  OGRSpatialReference s;
  const std::string adv = adv_as_epsg(text);
  if (s.SetFromUserInput((adv.empty() ? text : adv).c_str()) != OGRERR_NONE || !s.GetName()) return text;
  std::string name = s.GetName();
  const char* code = s.GetAuthorityCode(nullptr);
  const char* authority = s.GetAuthorityName(nullptr);
  if (code && authority) name += " (" + std::string(authority) + ":" + code + ")";
  return name;
}

void require_projected_metres(const OGRSpatialReference& crs, const std::string& what, double lon, double lat) {
  if (crs.IsGeographic() || crs.IsGeocentric() || !crs.IsProjected()) {
    std::string hint = "give --t_srs with a projected CRS in metres";
    if (crs.IsGeographic() && std::isfinite(lon) && std::isfinite(lat) && std::abs(lat) < 84) {
      const int zone = std::clamp(static_cast<int>(std::floor((lon + 180.0) / 6.0)) + 1, 1, 60);
      hint += " (the UTM zone there is EPSG:" + std::to_string((lat >= 0 ? 32600 : 32700) + zone) + ")";
    }
    throw Error(what + " is not in a projected CRS, and a scene's coordinates are metres on the ground: " + hint);
  }
  const double metres = crs.GetLinearUnits(nullptr);
  if (std::abs(metres - 1.0) > 1e-9) {
    throw Error(what + " is in a CRS whose unit is " + std::to_string(metres) +
                " m, and a scene's coordinates are metres: give --t_srs with a projected CRS in metres");
  }
}

TransformPtr scene_transform(const OGRSpatialReference& from, const OGRSpatialReference& to, const std::string& what) {
  if (from.IsSame(&to)) return nullptr;
  TransformPtr t(OGRCreateCoordinateTransformation(&from, &to));
  if (!t) throw Error("cannot transform " + what + " to the scene's CRS");
  return t;
}

}  // namespace skyview
