// Sorting sun steps into the gaps between horizon directions, and pairing the planes of each gap.
#include "exposure/sun_gaps.h"

namespace skyview::detail {

std::vector<SunGap> sort_into_gaps(std::span<const SunStep> sun, int directions, double rotation) {
  std::vector<SunGap> gaps(static_cast<std::size_t>(directions));
  for (std::size_t i = 0; i < sun.size(); ++i) {
    const SunStep& s = sun[i];
    const SunBracket b = bracket_azimuth(s.azimuth, directions, rotation);
    SunGap& gap = gaps[static_cast<std::size_t>(b.k0)];
    gap.sun.push_back({{s.direction[0], s.direction[1], s.direction[2]}, s.beam, b.f, s.elevation, i});
    gap.lowest = std::min(gap.lowest, s.elevation);
    for (int c = 0; c < 3; ++c) gap.beam[c] += s.beam * s.direction[c];
  }
  return gaps;
}

void GapPlanes::add(int first, int count, const float* upper, const Visit& visit) {
  const int n = directions_;
  for (int i = 0; i < count; ++i) {
    const int k = first + i;
    const float* plane = upper + cells_ * i;
    if (n == 1) {
      visit(0, plane, plane);
      continue;
    }
    if (k > 0) visit(k - 1, i > 0 ? plane - cells_ : last_plane_.data(), plane);
    if (k == n - 1) visit(k, plane, first == 0 ? upper : first_plane_.data());
  }
  if (first == 0) first_plane_.assign(upper, upper + cells_);
  last_plane_.assign(upper + cells_ * (count - 1), upper + cells_ * count);
}

}  // namespace skyview::detail
