#pragma once
// Bilinear height lookup between cell centres: the surface model every method shares (the
// ray-cast reference triangulates the same centres). A sample touching a nodata cell is
// skipped: nodata never occludes.
#include <cmath>

#include "skyview/raster/terrain.h"

namespace skyview::detail {

class HeightSampler {
 public:
  explicit HeightSampler(const Terrain& t) : z_(t.heights.data()), w_(t.width()), h_(t.height()) {}

  bool inside(double col, double row) const { return col >= 0.0 && row >= 0.0 && col <= w_ - 1 && row <= h_ - 1; }

  // Height at a point known to be inside; NaN when a contributing cell is nodata. A diagonal ray's
  // steps land a rounding error off the cell centres, where a nodata neighbour weighted by 1e-16
  // would drop a valid sample: a NaN is judged again with points within 1e-9 cell of a grid line
  // put on it (only then, so that every other sample costs nothing more).
  double at(double col, double row) const {
    const double z = blend(col, row);
    return std::isnan(z) ? blend(on_line(col), on_line(row)) : z;
  }

 private:
  double blend(double col, double row) const {
    const int c0 = static_cast<int>(col), r0 = static_cast<int>(row);
    const double fc = col - c0, fr = row - r0;
    const int c1 = c0 + (fc > 0.0), r1 = r0 + (fr > 0.0);  // stays in range on the last row/column
    const float* a = z_ + static_cast<std::ptrdiff_t>(r0) * w_;
    const float* b = z_ + static_cast<std::ptrdiff_t>(r1) * w_;
    const double top = a[c0] + fc * (static_cast<double>(a[c1]) - a[c0]);
    const double bottom = b[c0] + fc * (static_cast<double>(b[c1]) - b[c0]);
    return top + fr * (bottom - top);
  }
  static double on_line(double x) {
    const double nearest = std::round(x);
    return std::abs(x - nearest) < 1e-9 ? nearest : x;
  }

  const float* z_;
  int w_, h_;
};

}  // namespace skyview::detail
