// Building and sampling the exposure map's mip-map pyramid.
#include "skyview/sky/exposure_pyramid.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "skyview/core/error.h"

namespace skyview {

ExposurePyramid::ExposurePyramid(const ExposureMap& map) {
  Level base;
  base.width = map.width();
  base.height = map.height();
  const std::size_t n = static_cast<std::size_t>(base.width) * base.height;
  base.direct.resize(n);
  base.diffuse.resize(n);
  base.solid_angle.resize(n);
  base.centre.resize(n);
  base.direct_moment.resize(n);
  base.diffuse_moment.resize(n);
  for (int y = 0; y < base.height; ++y) {
    for (int x = 0; x < base.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * base.width + x;
      const double omega = map.cell_solid_angle(y);
      base.direct[i] = map.value(ExposureBand::direct, x, y) * omega;
      base.diffuse[i] = map.value(ExposureBand::diffuse, x, y) * omega;
      base.solid_angle[i] = omega;
      base.centre[i] = map.direction(x, y);
      for (int c = 0; c < 3; ++c) {
        base.direct_moment[i][c] = base.direct[i] * base.centre[i][c];
        base.diffuse_moment[i][c] = base.diffuse[i] * base.centre[i][c];
      }
    }
  }
  levels_.push_back(std::move(base));
  while (levels_.back().width > 1 || levels_.back().height > 1) {
    const Level& fine = levels_.back();
    Level coarse;
    coarse.width = (fine.width + 1) / 2;
    coarse.height = (fine.height + 1) / 2;
    const std::size_t m = static_cast<std::size_t>(coarse.width) * coarse.height;
    coarse.direct.assign(m, 0.0);
    coarse.diffuse.assign(m, 0.0);
    coarse.solid_angle.assign(m, 0.0);
    coarse.centre.assign(m, Direction{0, 0, 0});
    coarse.direct_moment.assign(m, Direction{0, 0, 0});
    coarse.diffuse_moment.assign(m, Direction{0, 0, 0});
    for (int y = 0; y < fine.height; ++y) {
      for (int x = 0; x < fine.width; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * fine.width + x;
        const std::size_t j = static_cast<std::size_t>(y / 2) * coarse.width + x / 2;
        coarse.direct[j] += fine.direct[i];
        coarse.diffuse[j] += fine.diffuse[i];
        coarse.solid_angle[j] += fine.solid_angle[i];
        for (int c = 0; c < 3; ++c) {
          coarse.centre[j][c] += fine.centre[i][c] * fine.solid_angle[i];
          coarse.direct_moment[j][c] += fine.direct_moment[i][c];
          coarse.diffuse_moment[j][c] += fine.diffuse_moment[i][c];
        }
      }
    }
    for (Direction& d : coarse.centre) {
      const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      if (len > 0) d = {d[0] / len, d[1] / len, d[2] / len};
    }
    levels_.push_back(std::move(coarse));
  }
}

double ExposurePyramid::irradiation(ExposureBand b, const Direction& n, std::span<const float> horizon,
                                    int level_index) const {
  if (level_index < 0 || level_index >= levels())
    throw Error("exposure pyramid: no level " + std::to_string(level_index));
  const Level& l = levels_[level_index];
  const int sectors = static_cast<int>(horizon.size());
  double sum = 0.0;
  for (std::size_t i = 0; i < l.centre.size(); ++i) {
    const Direction& d = l.centre[i];
    if (sectors > 0) {
      const double elevation = std::asin(std::clamp(d[2], -1.0, 1.0));
      if (elevation < horizon[horizon_sector(std::atan2(d[0], d[1]), sectors)]) continue;
    }
    const double cosine = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
    if (cosine <= 0.0) continue;
    const double energy = b == ExposureBand::direct    ? l.direct[i]
                          : b == ExposureBand::diffuse ? l.diffuse[i]
                                                       : l.direct[i] + l.diffuse[i];
    sum += energy * cosine;
  }
  return sum;
}

}  // namespace skyview
