#include "skyview/render/exposure_reference.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "hemisphere_rays.h"
#include "skyview/core/error.h"

namespace skyview {
namespace {

// The map's global radiance as a distribution over its cells: L·Ω cumulated row-major.
struct MapDistribution {
  const ExposureMap& map;
  std::vector<double> cdf;  // cdf[c] = ∑ L·Ω of cells before c+1
  double total = 0;         // T = ∑ L·Ω, Wh m-2 (the exposure of a sphere's view of the map)

  explicit MapDistribution(const ExposureMap& m) : map(m), cdf(std::size_t(m.width()) * m.height()) {
    for (int y = 0; y < m.height(); ++y) {
      for (int x = 0; x < m.width(); ++x) {
        total += m.value(ExposureBand::global, x, y) * m.cell_solid_angle(y);
        cdf[std::size_t(y) * m.width() + x] = total;
      }
    }
  }

  // The cell holding a direction of the upper hemisphere (east, north, up).
  double radiance(const Vec3f& d) const {
    const double az = std::atan2(double(d[0]), double(d[1]));
    const double zen = std::acos(std::clamp(double(d[2]), -1.0, 1.0));
    const int x =
        std::clamp(int(std::floor((az < 0 ? az + 2 * std::numbers::pi : az) / (2 * std::numbers::pi) * map.width())), 0,
                   map.width() - 1);
    const int y = std::clamp(int(std::floor(zen / (std::numbers::pi / 2) * map.height())), 0, map.height() - 1);
    return map.value(ExposureBand::global, x, y);
  }

  // A direction with density L/T: a cell by its share of T, then uniform in solid angle within it.
  Vec3f sample(double u0, double u1, double u2) const {
    const std::size_t c =
        std::min<std::size_t>(std::upper_bound(cdf.begin(), cdf.end(), u0 * total) - cdf.begin(), cdf.size() - 1);
    const int x = int(c % map.width()), y = int(c / map.width());
    const double az = map.azimuth_of_column(x + u1);
    const double c0 = std::cos(map.zenith_of_row(y)), c1 = std::cos(map.zenith_of_row(y + 1));
    const double cz = c1 + (c0 - c1) * u2, sz = std::sqrt(std::max(0.0, 1 - cz * cz));
    return {float(sz * std::sin(az)), float(sz * std::cos(az)), float(cz)};
  }
};

}  // namespace

ExposureReference exposure_reference(const RayScene& scene, const ViewBuffers& v, const ExposureMap& map, int rays,
                                     std::uint64_t seed) {
  if (rays < 1) throw UsageError("--reference-rays must be at least 1");
  const float nan = std::numeric_limits<float>::quiet_NaN();
  ExposureReference out{Grid<float>(v.width, v.height, nan), Grid<float>(v.width, v.height, nan)};
  const MapDistribution sky(map);
  // Multi-sample MIS: half the rays by each strategy (all by the cosine for a dark map), each
  // sample weighted f / (n_c p_c + n_m p_m). Each strategy's first number is stratified (one
  // stratum per ray: the map's cumulative runs through the sun's track, so its strata spread the
  // rays along it); the standard error from the samples' spread ignores the strata and so errs
  // high.
  const int by_map = sky.total > 0 ? rays / 2 : 0, by_cosine = rays - by_map;
  tbb::parallel_for(0, v.height, [&](int row) {
    for (int col = 0; col < v.width; ++col) {
      const std::size_t i = v.depth.index(col, row);
      if (!v.hit(i)) continue;
      detail::PixelHemisphere hemisphere(v.position[i], v.normal[i], seed, col, row);
      const Vec3f& n = hemisphere.normal();
      double sum = 0, sum2 = 0;
      for (int k = 0; k < rays; ++k) {
        const bool cosine_ray = k < by_cosine;
        const int stratum = cosine_ray ? k : k - by_cosine, strata = cosine_ray ? by_cosine : by_map;
        const double u0 = (stratum + hemisphere.uniform()) / strata, u1 = hemisphere.uniform();
        const Vec3f d = cosine_ray ? hemisphere.cosine_direction(u0, u1) : sky.sample(u0, u1, hemisphere.uniform());
        const double cosine = double(n[0]) * d[0] + double(n[1]) * d[1] + double(n[2]) * d[2];
        if (d[2] <= 0 || cosine <= 0) continue;  // below the horizon or behind the surface: f = 0
        const double radiance = sky.radiance(d);
        if (radiance <= 0 || scene.occluded(hemisphere.origin(), d)) continue;
        const double density = by_cosine * cosine / std::numbers::pi + (by_map ? by_map * radiance / sky.total : 0.0);
        const double value = rays * radiance * cosine / density;
        sum += value;
        sum2 += value * value;
      }
      const double mean = sum / rays, variance = std::max(0.0, sum2 / rays - mean * mean);
      out.exposure.values()[i] = float(mean / 1000);  // Wh to kWh
      out.stderr_.values()[i] = float(std::sqrt(variance / rays) / 1000);
    }
  });
  return out;
}

}  // namespace skyview
