// The image circle of a circular fish-eye photograph, from its rim against the black border.
#include "skyview/fisheye/image_circle.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "skyview/core/error.h"

namespace skyview {
namespace {

struct Point {
  double x, y;
};

// Kåsa's algebraic fit: x² + y² + D x + E y + F = 0 by least squares (3 x 3 normal equations).
bool fit_circle(const std::vector<Point>& p, ImageCircle& c) {
  if (p.size() < 8) return false;
  double mx = 0, my = 0;
  for (const Point& q : p) mx += q.x, my += q.y;
  mx /= p.size();
  my /= p.size();
  double suu = 0, svv = 0, suv = 0, suuu = 0, svvv = 0, suvv = 0, svuu = 0;
  for (const Point& q : p) {
    const double u = q.x - mx, v = q.y - my;
    suu += u * u, svv += v * v, suv += u * v;
    suuu += u * u * u, svvv += v * v * v, suvv += u * v * v, svuu += v * u * u;
  }
  const double det = suu * svv - suv * suv;
  if (!(std::abs(det) > 1e-9)) return false;
  const double bu = 0.5 * (suuu + suvv), bv = 0.5 * (svvv + svuu);
  const double uc = (bu * svv - bv * suv) / det, vc = (bv * suu - bu * suv) / det;
  c.cx = uc + mx;
  c.cy = vc + my;
  c.radius = std::sqrt(uc * uc + vc * vc + (suu + svv) / p.size());
  return std::isfinite(c.radius);
}

}  // namespace

ImageCircle inscribed_circle(int width, int height) {
  return {(width - 1) / 2.0, (height - 1) / 2.0, std::min(width, height) / 2.0, 0.0, 0, 0};
}

ImageCircle find_image_circle(const FisheyeImage& im) {
  const int w = im.width, h = im.height, ch = im.channels;
  auto bright = [&](int x, int y) {
    const std::uint8_t* p = im.pixels.data() + (static_cast<std::size_t>(y) * w + x) * ch;
    return ch == 1 ? p[0] : std::max({p[0], p[1], p[2]});
  };
  // The black border: brightness along the image's outer frame. A circle leaves the corners black.
  std::vector<double> frame;
  for (int x = 0; x < w; x += 2) frame.push_back(bright(x, 0)), frame.push_back(bright(x, h - 1));
  for (int y = 0; y < h; y += 2) frame.push_back(bright(0, y)), frame.push_back(bright(w - 1, y));
  std::vector<double> corners;
  const int patch = std::max(2, std::min(w, h) / 40);
  for (int y = 0; y < patch; ++y) {
    for (int x = 0; x < patch; ++x) {
      corners.push_back(bright(x, y)), corners.push_back(bright(w - 1 - x, y));
      corners.push_back(bright(x, h - 1 - y)), corners.push_back(bright(w - 1 - x, h - 1 - y));
    }
  }
  std::sort(corners.begin(), corners.end());
  const double black = corners[corners.size() * 99 / 100];
  constexpr const char* kHint = "; give --center and --radius (a full-frame fish-eye has no circle)";
  if (black > 40.0) throw Error(std::string("no image circle found: the corners are not black") + kHint);
  // Under-exposed canopy photographs keep their rim only a few levels above the black border.
  // A border of exact zeros (as cameras and converters write it) leaves any level above it to the
  // image, under-exposed canopy at the rim included; JPEG noise lifts a noisy black border by a few
  // levels more: twice its level above it.
  const double threshold = black == 0.0 ? 0.5 : 6.0 + 2.0 * black;
  auto cast_rays = [&](double cx, double cy, std::vector<Point>& edge) {
    edge.clear();
    const double reach = std::hypot(std::max(cx, w - 1 - cx), std::max(cy, h - 1 - cy));
    for (int a = 0; a < 720; ++a) {
      const double s = std::sin(a * M_PI / 360), c = std::cos(a * M_PI / 360);
      int run = 0;
      bool inside_seen = false;
      for (double r = reach; r > 0; r -= 0.5) {
        const int x = static_cast<int>(std::lround(cx + r * c)), y = static_cast<int>(std::lround(cy + r * s));
        if (x < 0 || y < 0 || x >= w || y >= h) continue;
        if (!inside_seen) {
          inside_seen = true;
          // A ray that enters the image on bright pixels leaves it inside the circle: the frame cuts it.
          if (bright(x, y) > threshold) break;
        }
        if (bright(x, y) > threshold) {
          if (++run == 8) {                                              // 8 half-pixel steps: four pixels
            edge.push_back({cx + (r + 3.75) * c, cy + (r + 3.75) * s});  // between the last dark and first bright
            break;
          }
        } else {
          run = 0;
        }
      }
    }
  };
  // Dark content (foliage, rock) at the rim stops a ray inside the circle, never outside it: the
  // circle is the one through the most edge points with (almost) none outside it. Candidates through
  // three edge points each (a fixed random sequence, so runs repeat), scored by the points within
  // tol of them less three for each point beyond 3 tol outside; the best refitted (Kåsa) to its points.
  ImageCircle circle{(w - 1) / 2.0, (h - 1) / 2.0, 0, 0, 0, 0};
  std::vector<Point> edge, kept;
  std::uint64_t state = 0x9E3779B97F4A7C15ull;
  auto next_index = [&](std::size_t n) {
    state ^= state << 13, state ^= state >> 7, state ^= state << 17;
    return static_cast<std::size_t>(state % n);
  };
  for (int pass = 0; pass < 2; ++pass) {
    cast_rays(circle.cx, circle.cy, edge);
    if (edge.size() < 8) throw Error(std::string("no image circle found: too little of a rim") + kHint);
    const double tol = std::max(2.0, 0.004 * std::min(w, h));
    double best = -1e300;
    ImageCircle best_circle = circle;
    for (int trial = 0; trial < 3000; ++trial) {
      const Point& p = edge[next_index(edge.size())];
      const Point& q = edge[next_index(edge.size())];
      const Point& r = edge[next_index(edge.size())];
      // The circle through p, q, r.
      const double d = 2 * (p.x * (q.y - r.y) + q.x * (r.y - p.y) + r.x * (p.y - q.y));
      if (std::abs(d) < 1e-6) continue;
      const double p2 = p.x * p.x + p.y * p.y, q2 = q.x * q.x + q.y * q.y, r2 = r.x * r.x + r.y * r.y;
      ImageCircle c;
      c.cx = (p2 * (q.y - r.y) + q2 * (r.y - p.y) + r2 * (p.y - q.y)) / d;
      c.cy = (p2 * (r.x - q.x) + q2 * (p.x - r.x) + r2 * (q.x - p.x)) / d;
      c.radius = std::hypot(p.x - c.cx, p.y - c.cy);
      if (!(c.radius > 0.2 * std::min(w, h)) || c.radius > std::hypot(w, h)) continue;
      double score = 0;
      for (const Point& e : edge) {
        const double dev = std::hypot(e.x - c.cx, e.y - c.cy) - c.radius;
        score += std::abs(dev) < tol ? 1.0 : dev > 3 * tol ? -3.0 : 0.0;
      }
      if (score > best) best = score, best_circle = c;
    }
    circle = best_circle;
    for (int refit = 0; refit < 3; ++refit) {
      kept.clear();
      for (const Point& e : edge) {
        if (std::abs(std::hypot(e.x - circle.cx, e.y - circle.cy) - circle.radius) < tol) kept.push_back(e);
      }
      if (!fit_circle(kept, circle)) throw Error(std::string("no image circle found: too little of a rim") + kHint);
    }
  }
  // The points must go round: at least 5 of 12 sectors of 30 degrees hold some (dark canopy hides the
  // rest of the rim of an under-exposed photograph; fewer than 8 is worth a look, ImageCircle::sectors).
  int sectors = 0;
  for (int k = 0; k < 12; ++k) {
    bool any = false;
    for (const Point& p : kept) {
      double a = std::atan2(p.y - circle.cy, p.x - circle.cx);
      if (a < 0) a += 2 * M_PI;
      any = any || static_cast<int>(a / (M_PI / 6)) == k;
    }
    sectors += any;
  }
  circle.sectors = sectors;
  if (kept.size() < 60 || sectors < 5 || circle.radius < 0.2 * std::min(w, h))
    throw Error(std::string("no image circle found: the bright area's rim is not a circle") + kHint);
  double sum = 0;
  for (const Point& p : kept) sum += std::pow(std::hypot(p.x - circle.cx, p.y - circle.cy) - circle.radius, 2);
  circle.rms = std::sqrt(sum / kept.size());
  circle.edge_points = static_cast<int>(kept.size());
  return circle;
}

}  // namespace skyview
