// ZenithDepthMap::update_region: a changed object's footprint made again, the rest copied.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "skyview/render/zenith_depth_map.h"
#include "zenith_column.h"

namespace skyview {

std::int64_t ZenithDepthMap::update_region(const Scene& scene, const RayScene& rays, const ZenithOptions& o,
                                           std::array<double, 2> lo, std::array<double, 2> hi) {
  const ZenithDepthMap frame = frame_of(rays, o);
  // The same grid and the same start of every ray, or a full build would differ outside the box.
  if (std::isnan(ray_top_) || cut_.size() != counts_.size() || frame.width_ != width_ || frame.height_ != height_ ||
      frame.x0_ != x0_ || frame.y0_ != y0_ || frame.resolution_ != resolution_ || frame.ray_top_ != ray_top_ ||
      o.max_layers != max_layers_ || o.merge_gap != merge_gap_) {
    return -1;
  }
  if (!(lo[0] <= hi[0] && lo[1] <= hi[1])) return 0;
  // Texels whose centre may lie in the box, a texel more each way (recomputing one too many
  // changes nothing).
  const int c0 = std::max(0, col_of(lo[0]) - 1), c1 = std::min(width_ - 1, col_of(hi[0]) + 1);
  const int r0 = std::max(0, row_of(hi[1]) - 1), r1 = std::min(height_ - 1, row_of(lo[1]) + 1);
  if (c0 > c1 || r0 > r1) return 0;
  const int w = c1 - c0 + 1, h = r1 - r0 + 1;
  std::vector<std::vector<float>> fresh(std::size_t(w) * h);
  std::vector<std::uint8_t> fresh_cut(fresh.size(), 0);
  tbb::parallel_for(0, h, [&](int r) {
    const float y = float(y0_ - (r0 + r + 0.5) * resolution_);
    for (int c = 0; c < w; ++c) {
      bool cut = false;
      fresh[std::size_t(r) * w + c] =
          zenith_column(scene, rays, float(x0_ + (c0 + c + 0.5) * resolution_), y, ray_top_, o, cut);
      fresh_cut[std::size_t(r) * w + c] = cut;
    }
  });
  // Repack the heights row-major as build() does: texels before the box keep their offsets.
  std::vector<float> values;
  values.reserve(values_.size());
  values.assign(values_.begin(), values_.begin() + std::ptrdiff_t(offsets_[index(c0, r0)]));
  for (std::size_t i = index(c0, r0); i < counts_.size(); ++i) {
    const int col = int(i % width_), row = int(i / width_);
    const std::uint64_t offset = values.size();
    if (col >= c0 && col <= c1 && row >= r0 && row <= r1) {
      const std::size_t k = std::size_t(row - r0) * w + (col - c0);
      values.insert(values.end(), fresh[k].begin(), fresh[k].end());
      truncated_ += int(fresh_cut[k]) - int(cut_[i]);
      cut_[i] = fresh_cut[k];
      counts_[i] = static_cast<std::uint8_t>(fresh[k].size());
    } else {
      values.insert(values.end(), values_.begin() + std::ptrdiff_t(offsets_[i]),
                    values_.begin() + std::ptrdiff_t(offsets_[i] + counts_[i]));
    }
    offsets_[i] = offset;
  }
  values.push_back(0.0f);  // as build(): heights() of an empty last texel stays in bounds
  values_.swap(values);
  pack();
  return std::int64_t(w) * h;
}

bool ZenithDepthMap::same_as(const ZenithDepthMap& other) const {
  return width_ == other.width_ && height_ == other.height_ && x0_ == other.x0_ && y0_ == other.y0_ &&
         resolution_ == other.resolution_ && max_layers_ == other.max_layers_ && truncated_ == other.truncated_ &&
         counts_ == other.counts_ && offsets_ == other.offsets_ && values_.size() == other.values_.size() &&
         std::memcmp(values_.data(), other.values_.data(), values_.size() * sizeof(float)) == 0;
}

}  // namespace skyview
