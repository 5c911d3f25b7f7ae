#pragma once
// The sun of many time steps against horizons that arrive a direction at a time: each step's sun
// lies in the gap between two neighbouring directions of a uniform set, where the horizon towards
// it is interpolated between theirs (sun_horizon.h). Steps are sorted into their gaps once, and a
// gap is tested as soon as both its directions' horizons are there.
#include <cstddef>
#include <functional>
#include <numbers>
#include <span>
#include <vector>

#include "skyview/exposure/sun_horizon.h"

namespace skyview::detail {

struct SunGap {
  struct Sun {
    double direction[3];
    double beam, share, elevation;  // share: SunBracket::f towards the gap's second direction
    std::size_t step;               // index in the steps sorted
  };
  std::vector<Sun> sun;
  double lowest = std::numbers::pi / 2;  // the lowest sun elevation among them
  double beam[3] = {0, 0, 0};            // Σ beam × direction
};

// The gaps of `directions` uniform directions from `rotation` (gap k between direction k and the
// next), each holding the steps whose sun's azimuth lies in it.
std::vector<SunGap> sort_into_gaps(std::span<const SunStep> sun, int directions, double rotation);

// Pairs planes of horizons (one per direction, `cells` each) as directions arrive in order, and
// hands over each gap once both of its planes are there; the last gap's second plane is direction
// 0's, kept until then.
class GapPlanes {
 public:
  using Visit = std::function<void(int gap, const float* first, const float* second)>;
  GapPlanes(int directions, std::size_t cells) : directions_(directions), cells_(cells) {}
  // Directions [first, first + count), planes one after another.
  void add(int first, int count, const float* upper, const Visit& visit);

 private:
  int directions_;
  std::size_t cells_;
  std::vector<float> first_plane_, last_plane_;
};

}  // namespace skyview::detail
