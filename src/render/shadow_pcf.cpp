// Percentage-closer filtering (Reeves et al. 1987): the share of the texels under the receiver's
// footprint whose depth is not in front of the receiver's own plane there.
#include "render/shadow_light_space.h"

namespace skyview::detail {

double pcf_lookup(const DepthMap& map, const LightReceiver& r, const ShadowOptions& o) {
  if (!r.faces_sun) return 0.0;
  const double bias = lookup_bias(r, o, map.texel);
  double lit = 0.0;
  filter_footprint(map, r.x, r.y, o.pcf_kernel, [&](int i, int j, double w, double, double) {
    // The receiver's plane at the texel's centre, where the texel's depth was taken.
    const double dx = map.x0 + (i + 0.5) * map.texel - r.x, dy = map.y0 + (j + 0.5) * map.texel - r.y;
    const double z = r.z + r.dzdx * dx + r.dzdy * dy - bias;
    if (map.at(i, j) >= z) lit += w;
  });
  return lit;
}

}  // namespace skyview::detail
