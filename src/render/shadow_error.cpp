// Shadow errors: receivers are binned in a uniform grid of the largest edge radius, so each finds
// the receivers within its own radius among the 27 cells around it.
#include "skyview/render/shadow_error.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_map>

#include "skyview/core/error.h"

namespace skyview {

namespace {

bool lit(float v) { return v >= 0.5f; }

}  // namespace

ShadowError shadow_error(const ShadowReceivers& receivers, const ShadowResult& exact, const ShadowResult& method,
                         double edge_texels) {
  const std::size_t n = receivers.points.size();
  if (exact.visibility.size() != n || method.visibility.size() != n || method.texel.size() != n) {
    throw Error("shadow_error: results of " + std::to_string(exact.visibility.size()) + " and " +
                std::to_string(method.visibility.size()) + " receivers for " + std::to_string(n) + " points");
  }
  ShadowError e;
  e.receivers = n;
  double radius = 0.0;
  for (float t : method.texel) radius = std::max(radius, edge_texels * t);
  // Edges: a receiver with one of the other exact state within its radius.
  std::vector<char> edge(n, 0);
  if (radius > 0.0) {
    auto key = [&](int x, int y, int z) {
      return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(x) & 0x1FFFFF) << 42) |
             (static_cast<std::uint64_t>(static_cast<std::uint32_t>(y) & 0x1FFFFF) << 21) |
             (static_cast<std::uint64_t>(static_cast<std::uint32_t>(z) & 0x1FFFFF));
    };
    auto cell = [&](float v) { return static_cast<int>(std::floor(v / radius)); };
    std::unordered_map<std::uint64_t, std::vector<std::size_t>> grid;
    for (std::size_t k = 0; k < n; ++k) {
      const Vec3f& p = receivers.points[k];
      grid[key(cell(p[0]), cell(p[1]), cell(p[2]))].push_back(k);
    }
    for (std::size_t k = 0; k < n; ++k) {
      const Vec3f& p = receivers.points[k];
      const double r = edge_texels * method.texel[k], r2 = r * r;
      const bool state = lit(exact.visibility[k]);
      const int cx = cell(p[0]), cy = cell(p[1]), cz = cell(p[2]);
      for (int dz = -1; dz <= 1 && !edge[k]; ++dz) {
        for (int dy = -1; dy <= 1 && !edge[k]; ++dy) {
          for (int dx = -1; dx <= 1 && !edge[k]; ++dx) {
            const auto it = grid.find(key(cx + dx, cy + dy, cz + dz));
            if (it == grid.end()) continue;
            for (std::size_t j : it->second) {
              if (lit(exact.visibility[j]) == state) continue;
              const Vec3f& q = receivers.points[j];
              const double a = q[0] - p[0], b = q[1] - p[1], c = q[2] - p[2];
              if (a * a + b * b + c * c <= r2) {
                edge[k] = 1;
                break;
              }
            }
          }
        }
      }
    }
  }
  double abs_sum = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    e.edge_receivers += edge[k];
    abs_sum += std::abs(static_cast<double>(method.visibility[k]) - exact.visibility[k]);
    const bool truth = lit(exact.visibility[k]), got = lit(method.visibility[k]);
    if (truth == got) continue;
    ++e.wrong;
    ++(edge[k] ? e.wrong_edge : e.wrong_interior);
    ++(got ? e.leaks : e.acne);
  }
  e.mean_abs = n ? abs_sum / static_cast<double>(n) : 0.0;
  return e;
}

}  // namespace skyview
