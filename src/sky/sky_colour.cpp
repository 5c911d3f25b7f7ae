// Preetham sky colour for pictures: Yxy -> XYZ -> linear sRGB (preetham.h) -> Reinhard tone map ->
// sRGB transfer.
#include "skyview/sky/sky_colour.h"

#include <algorithm>
#include <cmath>

#include "skyview/core/error.h"
#include "skyview/core/number_text.h"

namespace skyview {

double srgb_encode(double linear) {
  const double v = std::clamp(linear, 0.0, 1.0);
  return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

Srgb8 to_srgb8(const preetham::LinearRgb& c, double scale) {
  double r = std::max(0.0, c.r * scale), g = std::max(0.0, c.g * scale), b = std::max(0.0, c.b * scale);
  const double peak = std::max({r, g, b});
  if (peak > 1.0) r /= peak, g /= peak, b /= peak;  // keep the hue where a channel would clip
  auto byte = [](double v) { return static_cast<std::uint8_t>(std::lround(255.0 * srgb_encode(v))); };
  return {byte(r), byte(g), byte(b)};
}

preetham::Yxy linear_srgb_to_yxy(const preetham::LinearRgb& c) {
  // Inverse of the Rec. 709 / D65 matrix in preetham::to_linear_srgb.
  const double X = 0.4124564 * c.r + 0.3575761 * c.g + 0.1804375 * c.b;
  const double Y = 0.2126729 * c.r + 0.7151522 * c.g + 0.0721750 * c.b;
  const double Z = 0.0193339 * c.r + 0.1191920 * c.g + 0.9503041 * c.b;
  const double sum = X + Y + Z;
  if (!(sum > 0.0)) return {};
  return {Y, X / sum, Y / sum};
}

SkyColour::SkyColour(double turbidity, double sun_zenith, double sun_azimuth, double key)
    : turbidity_(turbidity), sun_zenith_(sun_zenith), sun_azimuth_(sun_azimuth) {
  if (!(turbidity >= 2.0 && turbidity <= 10.0))
    throw Error("turbidity " + number_text(turbidity) + " is outside the Preetham sky's range 2..10");
  if (!(sun_zenith < M_PI / 2)) throw Error("the sun is below the horizon: the Preetham sky models no twilight");
  if (!(key > 0.0 && key < 1.0)) throw Error("the sky's tone-mapping key must be between 0 and 1");
  // Reinhard: L_d = L / (1 + L); the zenith's L is key / (1 - key).
  exposure_ = key / (1.0 - key) / preetham::zenith(turbidity, sun_zenith).Y;
}

SkyColour::SkyColour(double turbidity, double sun_zenith, double sun_azimuth, FixedTone tone)
    : SkyColour(turbidity, sun_zenith, sun_azimuth, tone.key) {
  if (!(tone.luminance > 0.0) || !std::isfinite(tone.luminance))
    throw Error("the sky's fixed tone-mapping luminance must be positive");
  exposure_ = tone.key / (1.0 - tone.key) / tone.luminance;
}

FixedTone reference_tone() { return {preetham::zenith(3.0, M_PI / 4).Y, 0.5}; }

preetham::Yxy SkyColour::yxy(double zenith, double azimuth) const {
  // Angle between the view direction and the sun (spherical law of cosines).
  const double cos_gamma = std::cos(zenith) * std::cos(sun_zenith_) +
                           std::sin(zenith) * std::sin(sun_zenith_) * std::cos(azimuth - sun_azimuth_);
  const double gamma = std::acos(std::clamp(cos_gamma, -1.0, 1.0));
  return preetham::sky(turbidity_, sun_zenith_, zenith, gamma);
}

preetham::LinearRgb SkyColour::linear(double zenith, double azimuth) const {
  return preetham::to_linear_srgb(preetham::to_xyz(yxy(zenith, azimuth)));
}

Srgb8 SkyColour::display(const preetham::LinearRgb& c) const {
  const double y = 0.2126729 * c.r + 0.7151522 * c.g + 0.0721750 * c.b;
  if (!(y > 0.0)) return {};
  const double l = y * exposure_;
  return to_srgb8(c, exposure_ / (1.0 + l));  // L_d / Y = exposure / (1 + L)
}

Srgb8 SkyColour::display(double zenith, double azimuth) const { return display(linear(zenith, azimuth)); }

}  // namespace skyview
