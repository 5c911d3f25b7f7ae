#pragma once
// The zenithal depth map of "Solar exposure of complex cities" (Section 5.1, the paper's global
// depth map): the scene seen orthographically from above on a regular grid, made once per scene
// with Embree and read by the large-scale visibility of every view. Where a vertical ray meets the
// scene once (a height field) a texel holds one height; where it meets it more than once
// (overhangs, porches, bridges) it holds the list of surfaces from the top down, up to a maximum.
//
// The list bounds solid parts: heights top0 >= bottom0 > top1 >= bottom1 > ..., so a texel of a
// height field holds [top0] (solid below it), a texel under a closed porch slab [slab top, slab
// bottom, ground]. A downward ray enters a solid at the first surface it meets and leaves it only
// through a surface whose triangle faces down (outward winding, as CityGML requires); a solid
// without a bottom (an open-bottomed building) is thus solid down to what is under it, and an
// inward-wound mesh reads as solid: both err towards occlusion. Gaps thinner than `merge_gap`
// (a building's floor on the terrain) are closed. The count is odd: the last solid reaches down
// without end (a bottom with nothing under it is dropped); where a texel has more surfaces than `max_layers`, the
// deepest are dropped and the last kept top reaches down (counted in `truncated`).
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "skyview/raster/band_writer.h"
#include "skyview/scene/ray_scene.h"

namespace skyview {

struct ZenithOptions {
  double resolution = 1.0;  // metres per texel
  int max_layers = 8;
  double margin = 0.0;      // metres added around the scene's bounds
  double merge_gap = 0.05;  // metres
  std::int64_t max_texels = 200'000'000;
};

class ZenithDepthMap {
 public:
  ZenithDepthMap() = default;

  // Renders `scene` from above over its bounds (plus margin). Parallel (oneTBB). Throws
  // skyview::UsageError for a resolution <= 0, max_layers < 1 or a map above max_texels.
  static ZenithDepthMap build(const Scene& scene, const RayScene& rays, const ZenithOptions& options);

  int width() const { return width_; }
  int height() const { return height_; }
  double resolution() const { return resolution_; }
  double x0() const { return x0_; }  // scene-local x of the left edge
  double y0() const { return y0_; }  // scene-local y of the top (north) edge
  int max_layers() const { return max_layers_; }
  std::int64_t truncated() const { return truncated_; }
  std::int64_t layered_texels() const;  // texels with more than one height
  int deepest() const;                  // the largest count of heights in a texel

  // Texel of a scene-local point (may be outside: check in_map).
  int col_of(double x) const { return static_cast<int>(std::floor((x - x0_) / resolution_)); }
  int row_of(double y) const { return static_cast<int>(std::floor((y0_ - y) / resolution_)); }
  bool in_map(int col, int row) const { return col >= 0 && row >= 0 && col < width_ && row < height_; }
  // Heights of a texel from the top down (scene-local z); empty where the scene has nothing.
  int count(int col, int row) const { return packed_[index(col, row)].count; }
  const float* heights(int col, int row) const {
    const Packed& t = packed_[index(col, row)];
    return t.count <= 1 ? &t.first : &values_[offsets_[index(col, row)]];
  }

  // Dynamic scenes (the paper's Figure 12 idea): makes again only the texels whose centre lies in
  // the scene-local box [lo, hi] (x, y; widened by a texel each way) from `scene`, a changed
  // version of the one the map was made from (an object added, moved or removed inside the box; for
  // a move, one call per footprint or one box holding both). The result equals build(scene, rays,
  // options) bit for bit. Returns the count of texels made again, or -1, leaving the map as it was,
  // where the changed scene would give another map: its bounds move the grid, or its highest point
  // crosses a multiple of 16 m (which moves the rays' start), or the options differ, or the map was
  // loaded from a file. Then build it again. Parallel (oneTBB).
  std::int64_t update_region(const Scene& scene, const RayScene& rays, const ZenithOptions& options,
                             std::array<double, 2> lo, std::array<double, 2> hi);

  // Every texel's heights and the map's frame equal (what update_region promises).
  bool same_as(const ZenithDepthMap& other) const;

  // As a GeoTIFF in the scene's CRS: one float32 band per layer ("layer_1" the top, NaN where a
  // texel has fewer), world heights, with the options as metadata. `origin`: Scene::origin.
  void save(const std::string& path, const Scene& scene, const WriteOptions& options) const;
  // Reads a map saved by save() for a scene with `origin` and CRS `crs_wkt`. Throws skyview::Error
  // naming the file where it is not such a map or does not cover the scene.
  static ZenithDepthMap load(const std::string& path, const Scene& scene);

 private:
  std::size_t index(int col, int row) const { return static_cast<std::size_t>(row) * width_ + col; }
  // The grid and the rays' start height a build of `rays`' scene uses, without texels.
  static ZenithDepthMap frame_of(const RayScene& rays, const ZenithOptions& options);

  int width_ = 0, height_ = 0, max_layers_ = 0;
  double resolution_ = 1.0, x0_ = 0.0, y0_ = 0.0;
  std::int64_t truncated_ = 0;
  float ray_top_ = 0;              // scene-local z the downward rays start from (NaN: loaded)
  double merge_gap_ = 0;           // the options' (update_region checks them)
  std::vector<std::uint8_t> cut_;  // per texel: 1 where truncated (empty when loaded)
  std::vector<std::uint8_t> counts_;
  std::vector<std::uint64_t> offsets_;  // into values_, one per texel
  // What the large scale's march reads per texel, in one cache line: the count and the top height
  // (a height field's whole texel); offsets_ only for layered texels. Made by pack().
  struct Packed {
    float first;
    std::uint32_t count;
  };
  std::vector<Packed> packed_;
  void pack();
  std::vector<float> values_;
};

}  // namespace skyview
