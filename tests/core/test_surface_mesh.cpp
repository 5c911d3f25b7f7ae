// The surface mesh every method reads (the ray cast's triangles): which quads it covers, and the
// skirts that make every edge of it one that two triangles share, hung towards the open side.
#include <map>
#include <utility>

#include "skyview/horizon/surface_mesh.h"
#include "test_support.h"

using namespace skyview;
using namespace skyview::test;

namespace {

// A small raster with nodata along one side, a block hole, a lone nodata cell (four quads with one
// nodata corner around it) and a nodata corner; heights vary, so that quads split both ways.
Terrain holed_raster() {
  Terrain t = rasterize([](double e, double n) { return 3.0 * std::sin(0.7 * e) + 2.0 * std::cos(0.45 * n); }, 16, 13,
                        local_grid(16, 13, 1.0));
  for (int r = 0; r < 13; ++r) t.heights(15, r) = NAN;  // a side
  for (int r = 3; r < 6; ++r) {
    for (int c = 4; c < 8; ++c) t.heights(c, r) = NAN;  // a block
  }
  t.heights(11, 9) = NAN;  // a lone cell
  t.heights(0, 12) = NAN;  // a corner
  return t;
}

struct Point {
  double x, y;
};

Point position(const Terrain& t, const SurfaceMesh& m, unsigned v) {
  const std::size_t grid = static_cast<std::size_t>(t.width()) * t.height();
  if (v < grid) return {static_cast<double>(v % t.width()), static_cast<double>(v / t.width())};
  return {m.skirt_vertices[v - grid].col, m.skirt_vertices[v - grid].row};
}

// Whether p lies inside one of the surface's triangles, seen from above (pixel positions).
bool covered(const Terrain& t, const SurfaceMesh& m, Point p) {
  for (std::size_t i = 0; i < m.surface_triangles; ++i) {
    const Point a = position(t, m, m.triangles[3 * i]), b = position(t, m, m.triangles[3 * i + 1]),
                c = position(t, m, m.triangles[3 * i + 2]);
    auto side = [&](Point u, Point v) { return (v.x - u.x) * (p.y - u.y) - (v.y - u.y) * (p.x - u.x); };
    const double s1 = side(a, b), s2 = side(b, c), s3 = side(c, a);
    if ((s1 > 0 && s2 > 0 && s3 > 0) || (s1 < 0 && s2 < 0 && s3 < 0)) return true;
  }
  return false;
}

TEST(SurfaceMesh, EveryEdgeIsSharedAndEverySkirtHangsOnTheOpenSide) {
  const Terrain t = holed_raster();
  const std::size_t grid = static_cast<std::size_t>(t.width()) * t.height();
  for (const double sign : {1.0, -1.0}) {
    const SurfaceMesh m = surface_mesh(t, sign, 10.0);
    ASSERT_GT(m.surface_triangles, 0u);
    ASSERT_GT(m.triangles.size() / 3, m.surface_triangles) << "no skirts";
    // How many triangles hold each edge between two cells.
    std::map<std::pair<unsigned, unsigned>, int> holders;
    for (std::size_t i = 0; i < m.triangles.size(); i += 3) {
      for (int e = 0; e < 3; ++e) {
        const unsigned a = m.triangles[i + e], b = m.triangles[i + (e + 1) % 3];
        if (a < grid && b < grid) ++holders[{std::min(a, b), std::max(a, b)}];
      }
    }
    for (const auto& [edge, n] : holders) EXPECT_EQ(n, 2) << "edge " << edge.first << "-" << edge.second;
    // Each skirt (two triangles per edge, after the surface's) leans out over ground that no
    // triangle covers, and the other side of its edge is covered.
    for (std::size_t i = 3 * m.surface_triangles; i < m.triangles.size(); i += 6) {
      const Point p = position(t, m, m.triangles[i]), q = position(t, m, m.triangles[i + 1]);
      const Point q_out = position(t, m, m.triangles[i + 2]);
      const double ox = (q_out.x - q.x) / kSkirtOut, oy = (q_out.y - q.y) / kSkirtOut;  // unit outward
      EXPECT_NEAR(std::hypot(ox, oy), 1.0, 1e-9);
      const Point mid{0.5 * (p.x + q.x), 0.5 * (p.y + q.y)};
      EXPECT_FALSE(covered(t, m, {mid.x + 0.25 * ox, mid.y + 0.25 * oy}))
          << "skirt of edge at " << mid.x << "," << mid.y << " leans over the surface";
      EXPECT_TRUE(covered(t, m, {mid.x - 0.25 * ox, mid.y - 0.25 * oy})) << "edge at " << mid.x << "," << mid.y;
      // It hangs below its edge in the mesh's sign.
      const std::size_t bottom = m.triangles[i + 2] - grid;
      EXPECT_NEAR(sign * (m.skirt_vertices[bottom].z - t.heights(static_cast<int>(q.x), static_cast<int>(q.y))), -10.0,
                  1e-4);
    }
  }
}

// A quad is covered by two triangles where all four corners are valid, by the valid three's
// triangle where one is nodata, and not at all otherwise.
TEST(SurfaceMesh, QuadsAreCoveredWhereThreeCornersAreValid) {
  const Terrain t = holed_raster();
  const SurfaceMesh m = surface_mesh(t, 1.0, 10.0);
  std::size_t expected = 0;
  for (int r = 0; r + 1 < t.height(); ++r) {
    for (int c = 0; c + 1 < t.width(); ++c) {
      const int valid = t.valid(c, r) + t.valid(c + 1, r) + t.valid(c, r + 1) + t.valid(c + 1, r + 1);
      expected += valid == 4 ? 2 : valid == 3 ? 1 : 0;
      // The centre of a quad with two or more nodata corners is open; of a whole quad, covered.
      if (valid <= 2) {
        EXPECT_FALSE(covered(t, m, {c + 0.5, r + 0.5})) << c << "," << r;
      }
      if (valid == 4) {
        EXPECT_TRUE(covered(t, m, {c + 0.5 + 1e-3, r + 0.5 + 2e-3})) << c << "," << r;
      }
    }
  }
  EXPECT_EQ(m.surface_triangles, expected);
}

}  // namespace
