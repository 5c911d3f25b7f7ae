#include "skyview/fisheye/projection.h"

#include <cmath>
#include <limits>

#include "skyview/core/error.h"

namespace skyview {

const char* projection_name(Projection p) {
  switch (p) {
    case Projection::equidistant:
      return "equidistant";
    case Projection::equisolid:
      return "equisolid";
    case Projection::orthographic:
      return "orthographic";
    case Projection::stereographic:
      return "stereographic";
  }
  return "equidistant";
}

Projection projection_named(std::string_view name) {
  for (Projection p :
       {Projection::equidistant, Projection::equisolid, Projection::orthographic, Projection::stereographic}) {
    if (name == projection_name(p)) return p;
  }
  throw Error("unknown projection '" + std::string(name) +
              "' (known: equidistant, equisolid, orthographic, stereographic)");
}

double projection_radius(Projection p, double t) {
  switch (p) {
    case Projection::equidistant:
      return t / (M_PI / 2);
    case Projection::equisolid:
      return std::sqrt(2.0) * std::sin(t / 2);
    case Projection::orthographic:
      return std::sin(t);
    case Projection::stereographic:
      return std::tan(t / 2);
  }
  return t / (M_PI / 2);
}

double projection_zenith(Projection p, double r) {
  switch (p) {
    case Projection::equidistant:
      return r * (M_PI / 2);
    case Projection::equisolid:
      return r <= std::sqrt(2.0) ? 2.0 * std::asin(r / std::sqrt(2.0)) : std::numeric_limits<double>::quiet_NaN();
    case Projection::orthographic:
      return r <= 1.0 ? std::asin(r) : std::numeric_limits<double>::quiet_NaN();
    case Projection::stereographic:
      return 2.0 * std::atan(r);
  }
  return r * (M_PI / 2);
}

bool FisheyeFrame::direction(double x, double y, double& zenith, double& azimuth) const {
  const double dx = x - cx, dy = y - cy;
  const double r = std::hypot(dx, dy) / radius;
  zenith = projection_zenith(projection, r);
  if (!(zenith <= M_PI / 2)) return false;
  // Up is north; east is left unless mirrored.
  azimuth = std::atan2(mirror ? dx : -dx, -dy);
  if (azimuth < 0) azimuth += 2 * M_PI;
  return true;
}

void FisheyeFrame::pixel(double zenith, double azimuth, double& x, double& y) const {
  const double r = projection_radius(projection, zenith) * radius;
  x = cx + (mirror ? 1.0 : -1.0) * r * std::sin(azimuth);
  y = cy - r * std::cos(azimuth);
}

}  // namespace skyview
