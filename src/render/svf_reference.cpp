#include "skyview/render/svf_reference.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>

#include "hemisphere_rays.h"

#include "skyview/core/error.h"

namespace skyview {

SvfReference svf_reference(const RayScene& scene, const ViewBuffers& v, int rays, std::uint64_t seed) {
  if (rays < 1) throw UsageError("--reference-rays must be at least 1");
  const float nan = std::numeric_limits<float>::quiet_NaN();
  SvfReference out{Grid<float>(v.width, v.height, nan), Grid<float>(v.width, v.height, nan)};
  tbb::parallel_for(0, v.height, [&](int row) {
    for (int col = 0; col < v.width; ++col) {
      const std::size_t i = v.depth.index(col, row);
      if (!v.hit(i)) continue;
      detail::PixelHemisphere hemisphere(v.position[i], v.normal[i], seed, col, row);
      int open = 0;
      for (int k = 0; k < rays; ++k) {
        const double u1 = hemisphere.uniform(), u2 = hemisphere.uniform();
        const Vec3f d = hemisphere.cosine_direction(u1, u2);
        if (d[2] <= 0) continue;  // below the horizon: no sky there
        open += !scene.occluded(hemisphere.origin(), d);
      }
      const double f = double(open) / rays;
      out.svf.values()[i] = float(f);
      out.stderr_.values()[i] = float(std::sqrt(f * (1 - f) / rays));
    }
  });
  return out;
}

}  // namespace skyview
