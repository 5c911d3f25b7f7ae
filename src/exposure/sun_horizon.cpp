// The sun against a cell's horizon.
#include "skyview/exposure/sun_horizon.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace skyview {

SunStep sun_step(double azimuth, double elevation) {
  SunStep s;
  s.azimuth = azimuth;
  s.elevation = elevation;
  const double ce = std::cos(elevation);
  s.direction = {ce * std::sin(azimuth), ce * std::cos(azimuth), std::sin(elevation)};
  return s;
}

std::vector<SunStep> sun_steps(const SkyModel& model, std::span<const ExposureStep> steps) {
  std::vector<SunStep> out;
  for (const ExposureStep& step : steps) {
    const double elevation = std::numbers::pi / 2 - step.conditions.sun_zenith;
    if (!(elevation > 0.0) || !(step.hours > 0.0)) continue;
    const double dni = model.at(step.conditions)->direct_normal();
    if (!(dni > 0.0)) continue;
    SunStep s = sun_step(step.conditions.sun_azimuth, elevation);
    s.beam = dni * step.hours;
    s.hours = step.hours;
    out.push_back(s);
  }
  return out;
}

SunBracket bracket_azimuth(double azimuth, int n, double rotation) {
  const double turn = 2 * std::numbers::pi;
  double p = std::fmod((azimuth - rotation) / turn * n, static_cast<double>(n));
  if (p < 0) p += n;
  SunBracket b;
  b.k0 = std::min(static_cast<int>(p), n - 1);
  b.k1 = b.k0 + 1 == n ? 0 : b.k0 + 1;
  b.f = std::clamp(p - b.k0, 0.0, 1.0);
  return b;
}

double visible_disc_fraction(double d, double r) {
  if (d >= r) return 1.0;
  if (d <= -r) return 0.0;
  // The segment of the unit disc above the chord at height −x, x = d / r: (acos(−x) + x√(1 − x²)) / π.
  const double x = d / r;
  return (std::acos(-x) + x * std::sqrt(1.0 - x * x)) / std::numbers::pi;
}

}  // namespace skyview
