#pragma once
// The sweep's hulls (sweep.cpp): one line's upper convex hull of the profile seen so far, and the
// tangent to it from a nearer point. Inline: they are the sweep's innermost loop.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "horizon/sweep_geometry.h"

namespace skyview::detail::sweep {

struct HullPoint {
  double t, z;
};

// The tangent from p (nearer than every hull point) to an upper hull stored far-to-near is
// where slopes stop rising: slopes from an outside point along a convex chain are unimodal. Every
// hull point lies ahead of p (t - p.t has one sign), so slopes compare by cross products.
inline bool rises(const HullPoint& a, const HullPoint& b, const HullPoint& p) {
  return (a.z - p.z) * (b.t - p.t) < (b.z - p.z) * (a.t - p.t);
}

// One line's upper hull in a slice of its band's arena, the highest point it ever held (a bound on
// any tangent from below) and copies of its two nearest points: the tangent is the nearest point
// over flat ground (where curvature makes the profile a dome), and the copies sit in the small
// array of lines that the cells read in turn.
struct LineHull {
  HullPoint* points = nullptr;
  std::size_t n = 0;
  double top = -kInf;
  HullPoint last{0, 0}, before_last{0, 0};
  double first_t = 0;  // position of the farthest point (pops stop before it)
  // The last tangent point found for the strip on either side of the line (cells there differ
  // in height, so their tangents differ); pops only remove nearer points.
  std::size_t hint[2] = {0, 0};

  void clear() {
    n = 0;
    top = -kInf;
    hint[0] = hint[1] = 0;
  }

  // `same`: a sample nearer than this to the nearest point (a minor crossing that rounding put on
  // a row crossing) would make two points of equal slope from every viewer, and the tangent
  // search needs slopes strictly rising up to the tangent: the higher of the two stays.
  // Returns p's tangent point on the hull before it (the point it now lies behind: the pops remove
  // exactly the points under the slope to their farther neighbour); null if none or merged.
  // Without kCopies the copies and the top that far-field queries read are not kept: lines that
  // hold every cell (cells_on_lines) are never queried.
  template <bool kCopies = true>
  const HullPoint* push(const HullPoint& p, double same) {
    if (n > 0 && points[n - 1].t - p.t < same) {
      if (p.z <= points[n - 1].z) return nullptr;
      --n;
    }
    while (n >= 2) {
      const HullPoint& a = points[n - 1];
      const HullPoint& b = points[n - 2];
      if ((a.z - p.z) * (b.t - p.t) > (b.z - p.z) * (a.t - p.t)) break;
      --n;
    }
    if constexpr (kCopies) {
      if (n > 0) before_last = points[n - 1];
      if (n == 0) first_t = p.t;
    }
    points[n++] = p;
    if constexpr (kCopies) {
      last = p;
      top = std::max(top, p.z);
    }
    return n >= 2 ? &points[n - 2] : nullptr;
  }

  // Whether no point of the hull rises above slope s from p, judged from the copies alone: the
  // hull is concave, so beyond its nearest point it lies under the line through its two nearest
  // points and under its highest point; the slope from p to that envelope is monotone on each of
  // its two pieces, so their ends bound it.
  bool under_slope(const HullPoint& p, double s) const {
    if (n == 0) return true;
    auto under = [&](double qt, double qz) { return qz - p.z <= s * (qt - p.t); };
    if (!under(last.t, last.z)) return false;
    if (n == 1) return true;
    const double dt = before_last.t - last.t, dz = before_last.z - last.z;
    if (dz <= 0.0) return under(first_t, last.z);
    const double reach = last.t + (top - last.z) * (dt / dz);  // where the line meets the top
    return (reach >= first_t || under(reach, top)) && under(first_t, top);
  }

  // Slope of the tangent from p. Slopes rise along the hull up to the tangent point T and fall
  // after it, so "slope rises into i" holds exactly for i <= T. The nearest point is tried from
  // the copies; otherwise the search gallops from this line's previous tangent point (the same
  // distant peak, mostly) to bracket T, then bisects.
  double tangent_slope(const HullPoint& p, int side) {
    std::size_t& hint = this->hint[side];
    if (n == 1 || rises(before_last, last, p)) {
      hint = n - 1;
      return (last.z - p.z) / (last.t - p.t);
    }
    const HullPoint* h = points;
    auto rises_into = [&](std::size_t i) { return i == 0 || rises(h[i - 1], h[i], p); };
    std::size_t lo, hi;  // rises_into(lo) holds, rises_into(hi) does not
    const std::size_t start = std::min(hint, n - 2);
    if (rises_into(start)) {
      lo = start, hi = n - 1;
      for (std::size_t step = 1; lo + step < hi; step *= 2) {
        if (!rises_into(lo + step)) {
          hi = lo + step;
          break;
        }
        lo += step;
      }
    } else {
      hi = start, lo = 0;
      for (std::size_t step = 1; step < hi; step *= 2) {
        if (rises_into(hi - step)) {
          lo = hi - step;
          break;
        }
        hi -= step;
        if (step >= hi) break;
      }
    }
    while (hi - lo > 1) {
      const std::size_t mid = lo + (hi - lo) / 2;
      (rises_into(mid) ? lo : hi) = mid;
    }
    hint = lo;
    return (h[lo].z - p.z) / (h[lo].t - p.t);
  }
};

}  // namespace skyview::detail::sweep
