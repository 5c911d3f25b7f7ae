// Geometry and cosine-weighted integration of the directional exposure map.
#include "skyview/sky/exposure_map.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "skyview/core/error.h"

namespace skyview {

ExposureMap::ExposureMap(int width, int height) : width_(width), height_(height) {
  if (width < 1 || height < 1 || width > 65536 || height > 65536) {
    throw Error("exposure map size must be within 1 .. 65536 (got " + std::to_string(width) + "x" +
                std::to_string(height) + ")");
  }
  const std::size_t n = static_cast<std::size_t>(width) * height;
  direct_.assign(n, 0.0f);
  diffuse_.assign(n, 0.0f);
  solid_angle_.resize(height);
  const double dz = std::numbers::pi / 2 / height, dphi = 2 * std::numbers::pi / width;
  for (int y = 0; y < height; ++y) solid_angle_[y] = (std::cos(y * dz) - std::cos((y + 1) * dz)) * dphi;
}

std::vector<float>& ExposureMap::band(ExposureBand b) {
  if (b == ExposureBand::global) throw Error("the global band is a sum, not stored");
  return b == ExposureBand::direct ? direct_ : diffuse_;
}

const std::vector<float>& ExposureMap::band(ExposureBand b) const { return const_cast<ExposureMap*>(this)->band(b); }

double ExposureMap::value(ExposureBand b, int x, int y) const {
  const std::size_t i = static_cast<std::size_t>(y) * width_ + x;
  switch (b) {
    case ExposureBand::direct:
      return direct_[i];
    case ExposureBand::diffuse:
      return diffuse_[i];
    default:
      return static_cast<double>(direct_[i]) + diffuse_[i];
  }
}

double ExposureMap::azimuth_of_column(double x) const { return 2 * std::numbers::pi * x / width_; }
double ExposureMap::zenith_of_row(double y) const { return std::numbers::pi / 2 * y / height_; }
double ExposureMap::cell_solid_angle(int y) const { return solid_angle_[y]; }

Direction ExposureMap::direction(int x, int y) const {
  const double az = azimuth_of_column(x + 0.5), zen = zenith_of_row(y + 0.5);
  return {std::sin(zen) * std::sin(az), std::sin(zen) * std::cos(az), std::cos(zen)};
}

int horizon_sector(double azimuth, int sectors) {
  const double turn = 2 * std::numbers::pi;
  double a = std::fmod(azimuth, turn);
  if (a < 0) a += turn;
  return static_cast<int>(std::floor(a / turn * sectors + 0.5)) % sectors;
}

double ExposureMap::irradiation(ExposureBand b, const Direction& n, std::span<const float> horizon) const {
  double sum = 0.0;
  const int sectors = static_cast<int>(horizon.size());
  for (int y = 0; y < height_; ++y) {
    const double zen = zenith_of_row(y + 0.5);
    const double elevation = std::numbers::pi / 2 - zen;
    double row = 0.0;
    for (int x = 0; x < width_; ++x) {
      const double az = azimuth_of_column(x + 0.5);
      if (sectors > 0 && elevation < horizon[horizon_sector(az, sectors)]) continue;
      const double cosine =
          n[0] * std::sin(zen) * std::sin(az) + n[1] * std::sin(zen) * std::cos(az) + n[2] * std::cos(zen);
      if (cosine > 0.0) row += value(b, x, y) * cosine;
    }
    sum += row * solid_angle_[y];
  }
  return sum;
}

}  // namespace skyview
