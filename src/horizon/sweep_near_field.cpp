#include "horizon/sweep_near_field.h"

#include <cmath>
#include <cstring>
#include <limits>

#include "horizon/fast_atan.h"

namespace skyview::detail::sweep {

namespace {

// Eight floats, the width of an AVX2 register (GCC's vector extension: two SSE registers in the
// baseline build).
using Floats8 = float __attribute__((vector_size(32)));

// (By reference: returning a vector type by value changes the ABI between the two builds.)
inline void load8(Floats8& v, const float* p) { std::memcpy(&v, p, sizeof v); }

// Near field of the cells [a, b) of the row at `major`: the highest slope of each cell's own ray
// over the crossings, into best[a, b) (indexed by minor), and with kLowest minus the lowest into
// lowest[a, b): the lowest angle's slope, which negated heights would give bit for bit (float
// rounding is symmetric), from the same loads. NaN heights lose every comparison, so nodata never
// occludes. Float slopes are good to 1e-7. Blocks of 32 cells that read every crossing inside the
// raster keep their heights and slopes in registers over all crossings (a crossing costs two loads
// and six or seven operations per eight cells); the rest, near the raster's sides, goes crossing by
// crossing. Inlined into near_field, which is compiled for baseline x86-64 and for AVX2.
template <bool kLowest>
__attribute__((always_inline)) inline void near_extremes(const SweepGeometry& g,
                                                         const std::vector<NearCrossing>& crossings, int major, int a,
                                                         int b, float* best, float* lowest) {
  constexpr float kNone = -std::numeric_limits<float>::infinity();
  std::fill(best + a, best + b, kNone);
  if (kLowest) std::fill(lowest + a, lowest + b, -kNone);  // the smallest slope until negated below
  const float* zrow = g.row(major);
  // The crossings whose rows exist from this row (they come in order of distance), and the cells
  // that read all of them inside the row.
  std::size_t count = 0;
  int all_lo = a, all_hi = b;
  // A crossing outside the raster's extent ends the track (SweepGeometry::major_lo); along a row,
  // cells whose crossing lies beyond it on the minor axis skip it.
  auto first_cell = [&](const NearCrossing& x) { return std::max({g.minor_first(x.across), -x.col0, -x.col1}); };
  auto last_cell = [&](const NearCrossing& x) {
    return std::min({g.minor_last(x.across), g.minor_n - x.col0, g.minor_n - x.col1});
  };
  for (const NearCrossing& x : crossings) {
    const int r1 = major + g.toward * x.ahead1;
    if (r1 < 0 || r1 >= g.major_n || !g.major_inside(major + g.toward * x.ahead)) break;
    all_lo = std::max(all_lo, first_cell(x));
    all_hi = std::min(all_hi, last_cell(x));
    ++count;
  }
  constexpr int kBlock = 32;
  const int blocks = all_hi > all_lo ? (all_hi - all_lo) / kBlock : 0;
  for (int block = 0; block < blocks; ++block) {
    const int m = all_lo + block * kBlock;
    Floats8 zc[4], top[4], bottom[4];
    for (int j = 0; j < 4; ++j) {
      load8(zc[j], zrow + m + 8 * j);
      top[j] = Floats8{} + kNone;
      bottom[j] = Floats8{} - kNone;
    }
    for (std::size_t i = 0; i < count; ++i) {
      const NearCrossing& x = crossings[i];
      const float* z0 = g.row(major + g.toward * x.ahead0) + (x.col0 + m);  // in the row: m >= -col0
      const float* z1 = g.row(major + g.toward * x.ahead1) + (x.col1 + m);
      const float w = x.w, scale = x.scale, drop = x.drop;
#pragma GCC unroll 4
      for (int j = 0; j < 4; ++j) {
        Floats8 h0, h1;
        load8(h0, z0 + 8 * j);
        load8(h1, z1 + 8 * j);
        const Floats8 v = (h0 + w * (h1 - h0) - zc[j]) * scale - drop;
        top[j] = v > top[j] ? v : top[j];
        if (kLowest) bottom[j] = v < bottom[j] ? v : bottom[j];
      }
    }
    std::memcpy(best + m, top, sizeof top);
    if (kLowest) {
      for (int j = 0; j < 4; ++j) bottom[j] = -bottom[j];
      std::memcpy(lowest + m, bottom, sizeof bottom);
    }
  }
  // The cells left over: crossing by crossing, each within the cells that read it inside the row.
  auto by_crossing = [&](int lo, int hi) {
    for (std::size_t i = 0; i < count && lo < hi; ++i) {
      const NearCrossing& x = crossings[i];
      const int ma = std::max(lo, first_cell(x));
      const int mb = std::min(hi, last_cell(x));
      const float* z0 = g.row(major + g.toward * x.ahead0);
      const float* z1 = g.row(major + g.toward * x.ahead1);
      const int c0 = x.col0, c1 = x.col1;
      const float w = x.w, scale = x.scale, drop = x.drop;
      for (int m = ma; m < mb; ++m) {
        const float zi = z0[m + c0] + w * (z1[m + c1] - z0[m + c0]);
        const float v = (zi - zrow[m]) * scale - drop;
        best[m] = v > best[m] ? v : best[m];
        if (kLowest) lowest[m] = v < lowest[m] ? v : lowest[m];
      }
    }
    if (kLowest) {
      for (int m = lo; m < hi; ++m) lowest[m] = -lowest[m];
    }
  };
  if (blocks > 0) {
    by_crossing(a, all_lo);
    by_crossing(all_lo + blocks * kBlock, b);
  } else {
    by_crossing(a, b);
  }
}

}  // namespace

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_ADDRESS__)
__attribute__((target_clones("avx2", "default")))
#endif
void near_field(const SweepGeometry& g, const std::vector<NearCrossing>& crossings, int major, int a, int b,
                float* best, float* lowest) {
  if (lowest)
    near_extremes<true>(g, crossings, major, a, b, best, lowest);
  else
    near_extremes<false>(g, crossings, major, a, b, best, lowest);
}

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_ADDRESS__)
__attribute__((target_clones("avx2", "default")))
#endif
void write_angles(const SweepGeometry& g, const Window& window, int major, int a, int b, float* best, double sign,
                  float* plane) {
  const float* zrow = g.row(major);
  for (int m = a; m < b; ++m) {
    const double v = best[m];
    const double atan_v = sign * fast_atan(v);  // computed for every cell: no branch in the loop
    const float angle = static_cast<float>(v == -kInf ? 0.0 : atan_v);
    best[m] = std::isnan(zrow[m]) ? std::numeric_limits<float>::quiet_NaN() : angle;
  }
  if (g.by_rows) {
    float* out = plane + static_cast<std::size_t>(major - window.row0) * window.cols + (a - window.col0);
    std::memcpy(out, best + a, sizeof(float) * static_cast<std::size_t>(b - a));
  } else {
    float* out = plane + static_cast<std::size_t>(a - window.row0) * window.cols + (major - window.col0);
    for (int m = a; m < b; ++m, out += window.cols) *out = best[m];
  }
}

}  // namespace skyview::detail::sweep
