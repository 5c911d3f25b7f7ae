#include "skyview/sky_view/sky_view.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <memory>
#include <vector>

#include "horizon/fast_atan.h"
#include "skyview/core/error.h"
#include "skyview/core/large_pages.h"

namespace skyview {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// sin and cos of x in [0, π/2] without a library call, so that a loop over cells vectorises:
// Taylor series to degrees 15 and 16 on [0, π/4] (truncation below 5e-17), reflected about π/4
// for the upper half. Exact at 0: sin 0 = 0, cos 0 = 1.
inline void sincos_quarter(double x, double& s, double& c) {
  const bool upper = x > 0.25 * kPi;
  const double y = upper ? 0.5 * kPi - x : x, y2 = y * y;
  const double sy =
      y * (1.0 + y2 * (-1.0 / 6 +
                       y2 * (1.0 / 120 +
                             y2 * (-1.0 / 5040 + y2 * (1.0 / 362880 +
                                                       y2 * (-1.0 / 39916800 + y2 * (1.0 / 6227020800 +
                                                                                     y2 * (-1.0 / 1307674368000))))))));
  const double cy =
      1.0 +
      y2 * (-0.5 + y2 * (1.0 / 24 +
                         y2 * (-1.0 / 720 + y2 * (1.0 / 40320 +
                                                  y2 * (-1.0 / 3628800 + y2 * (1.0 / 479001600 +
                                                                               y2 * (-1.0 / 87178291200 +
                                                                                     y2 * (1.0 / 20922789888000))))))));
  s = upper ? cy : sy;
  c = upper ? sy : cy;
}

// The sector azimuths' cosines and sines and the sectors' weights, shared by every cell. Sums
// over sectors weigh each by `weight` (n times its share Δ_k / 2π: exactly 1 for uniform sectors,
// so that their sums keep their bits) and are divided by n at the end.
struct Sectors {
  int n;
  std::vector<double> weight;  // n Δ_k / 2π
  std::vector<double> half;    // sin(Δ_k / 2)
  std::vector<double> cos_phi, sin_phi;
  explicit Sectors(const DirectionSet& set)
      : n(set.size()), weight(n, 1.0), half(n, std::sin(kPi / n)), cos_phi(n), sin_phi(n) {
    const bool uniform = set.is_uniform();
    for (int k = 0; k < n; ++k) {
      cos_phi[k] = std::cos(set.offset[k]);
      sin_phi[k] = std::sin(set.offset[k]);
      if (!uniform) weight[k] = n * set.share[k], half[k] = std::sin(kPi * set.share[k]);
    }
  }
  explicit Sectors(int n) : Sectors(DirectionSet::uniform(n)) {}
};

constexpr int kChunk = 256;  // cells summed together, their sums in the first-level cache

// A chunk of consecutive cells of the window: what their sectors share (the surface's tilt, and the offset of
// the sectors from the aspect) and the sums over the sectors so far.
struct SkySums {
  double cb[kChunk], sb[kChunk], tb[kChunk];                // cosine, sine and tangent of the slope
  double cos_offset[kChunk], sin_offset[kChunk];            // of rotation - aspect
  double svf[kChunk], visibility[kChunk], surface[kChunk];  // Σ sin² H0, Σ sin H0, Σ surface share
  double openness[kChunk], lowest[kChunk];                  // Σ (90° - h), Σ (90° + lowest angle)

  void set_tilt(int i, double cos_slope, double sin_slope, double tan_slope, double cos_off, double sin_off) {
    cb[i] = cos_slope, sb[i] = sin_slope, tb[i] = tan_slope;
    cos_offset[i] = cos_off, sin_offset[i] = sin_off;
  }
  void clear(int i) { svf[i] = visibility[i] = surface[i] = openness[i] = lowest[i] = 0.0; }

  void add_lowest(const float* low, int count, double weight) {
    for (int i = 0; i < count; ++i) lowest[i] += weight * (90.0 + low[i] * (180.0 / kPi));
  }
};

// Sector k's share (the formulas of sky_view.h) for cells [0, count) of `sums` with horizons
// h[0, count). The sky starts at H = max(h, t, 0), where t = atan(-tan β cos(φ - A)) is the
// surface's own horizon; it beats the other two only on slopes facing away from the sector. One
// sine and cosine per cell serve all three products, and the offset's cosine comes from the
// angle-sum formula: the loop has no library call and runs as vectors. Without kTilted the
// surface's share (a square root, an arctangent and a division per cell) is not summed: runs that
// write no svf_surface never read it, and it took more than half of this loop's time (perf, 4000²).
template <bool kTilted>
__attribute__((always_inline)) inline void sector_sums(SkySums& sums, const Sectors& s, int k, const float* h,
                                                       int count) {
  constexpr double kInvPi = 1.0 / kPi, kDegrees = 180.0 / kPi;
  const double cos_phi = s.cos_phi[k], sin_phi = s.sin_phi[k], half = s.half[k];
  const double weight = s.weight[k], share = weight / s.n;
  for (int i = 0; i < count; ++i) {
    const double hk = h[i];
    const double above = hk > 0.0 ? hk : 0.0;
    double sin_above, cos_above;
    sincos_quarter(above, sin_above, cos_above);
    sums.svf[i] += weight * (sin_above * sin_above);
    sums.visibility[i] += weight * sin_above;
    if constexpr (kTilted) {
      const double cos_rel = cos_phi * sums.cos_offset[i] - sin_phi * sums.sin_offset[i];
      const double x = -sums.tb[i] * cos_rel;  // tangent of the surface's own horizon
      const bool surface_wins = x * cos_above > sin_above;
      const double cos_t = 1.0 / std::sqrt(1.0 + x * x);
      const double H = surface_wins ? detail::fast_atan(x) : above;
      const double cH = surface_wins ? cos_t : cos_above, sH = surface_wins ? x * cos_t : sin_above;
      sums.surface[i] +=
          sums.cb[i] * cH * cH * share + sums.sb[i] * cos_rel * half * (0.5 * kPi - H - sH * cH) * kInvPi;
    }
    sums.openness[i] += weight * (90.0 - hk * kDegrees);
  }
}

// sector_sums, compiled for baseline x86-64 and for AVX2.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_ADDRESS__)
__attribute__((target_clones("avx2", "default")))
#endif
void add_sector(SkySums& sums, const Sectors& s, int k, const float* h, int count, bool tilted) {
  if (tilted)
    sector_sums<true>(sums, s, k, h, count);
  else
    sector_sums<false>(sums, s, k, h, count);
}

// Directions [first, first + count) of planes laid out as in HorizonField (`cells` apart; lower
// null or likewise), for the chunk's cells from cell `c0` of the window; `tilted`: the surface's
// share too.
void add_planes(SkySums& sums, const Sectors& sectors, int first, int count, const float* upper, const float* lower,
                std::size_t cells, std::size_t c0, int n, bool tilted) {
  for (int k = 0; k < count; ++k) add_sector(sums, sectors, first + k, upper + cells * k + c0, n, tilted);
  if (lower) {
    for (int k = 0; k < count; ++k) sums.add_lowest(lower + cells * k + c0, n, sectors.weight[first + k]);
  }
}

// One cell's sums over its n horizons h[0, n), in double throughout.
const SkySums& one_cell(const float* h, int n, double rotation, double slope, double aspect, SkySums& sums) {
  const Sectors sectors(n);
  sums.set_tilt(0, std::cos(slope), std::sin(slope), std::tan(slope), std::cos(rotation - aspect),
                std::sin(rotation - aspect));
  sums.clear(0);
  for (int k = 0; k < n; ++k) add_sector(sums, sectors, k, h + k, 1, true);
  return sums;
}

}  // namespace

double svf_horizontal(const float* h, int n) {
  SkySums sums;
  return 1.0 - one_cell(h, n, 0, 0, 0, sums).svf[0] / n;
}

double sky_visibility(const float* h, int n) {
  SkySums sums;
  return 1.0 - one_cell(h, n, 0, 0, 0, sums).visibility[0] / n;
}

double svf_tilted(const float* h, int n, double rotation, double slope, double aspect) {
  SkySums sums;
  return std::clamp(one_cell(h, n, rotation, slope, aspect, sums).surface[0], 0.0, 1.0);
}

void horn_slope_aspect(const Terrain& t, int col, int row, double& slope, double& aspect) {
  auto has = [&](int dc, int dr) { return t.heights.in_grid(col + dc, row + dr) && t.valid(col + dc, row + dr); };
  auto z = [&](int dc, int dr) -> double { return t.heights(col + dc, row + dr); };
  // Horn (1981) weights three differences 1:2:1 across the centre line. Where a neighbour is
  // missing (raster edge, nodata) a difference falls back to one side, or drops out and the others
  // carry its weight: substituting the centre's height instead would halve the slope on a plane.
  auto derivative = [&](int ac, int ar) {  // along the pixel step (ac, ar); across is (ar, ac)
    double sum = 0, weight = 0;
    for (int k = -1; k <= 1; ++k) {
      const int oc = k * ar, orow = k * ac;  // this line's cell on the centre line
      const bool minus = has(oc - ac, orow - ar), centre = has(oc, orow), plus = has(oc + ac, orow + ar);
      double d;
      if (minus && plus)
        d = (z(oc + ac, orow + ar) - z(oc - ac, orow - ar)) / 2.0;
      else if (centre && plus)
        d = z(oc + ac, orow + ar) - z(oc, orow);
      else if (centre && minus)
        d = z(oc, orow) - z(oc - ac, orow - ar);
      else
        continue;
      const double w = k == 0 ? 2.0 : 1.0;
      sum += w * d, weight += w;
    }
    return weight > 0 ? sum / weight : 0.0;
  };
  const double dz_dcol = derivative(1, 0);
  const double dz_drow = derivative(0, 1);
  // Pixel-space gradient = J^T * ground gradient; solve for the east/north gradient.
  const Jacobian j = t.frame.at(col + t.origin_col, row + t.origin_row);
  const double det = j.a * j.d - j.b * j.c;
  const double g_east = (j.d * dz_dcol - j.c * dz_drow) / det;
  const double g_north = (-j.b * dz_dcol + j.a * dz_drow) / det;
  const double g = std::hypot(g_east, g_north);
  slope = std::atan(g);
  aspect = g > 0.0 ? std::atan2(-g_east, -g_north) : 0.0;
}

bool search_circle_leaves_raster(const Terrain& t, int col, int row, double radius) {
  if (std::isinf(radius)) return true;
  const Jacobian j = t.frame.at(col + t.origin_col, row + t.origin_row);
  const double det = j.a * j.d - j.b * j.c;
  // Half-extent, in pixels, of the image of a ground circle under the inverse Jacobian.
  const double half_cols = radius * std::hypot(j.d, j.b) / std::abs(det);
  const double half_rows = radius * std::hypot(j.c, j.a) / std::abs(det);
  const double gc = col + t.origin_col, gr = row + t.origin_row;
  return gc - half_cols < 0 || gr - half_rows < 0 || gc + half_cols > t.full_width - 1 ||
         gr + half_rows > t.full_height - 1;
}

namespace {

// A cell's tilt as the sums use it: floats, which only weight the sectors, so that SkyViewSums
// can keep them per cell and sky_view_products gives the same bits computing them per chunk.
struct Tilt {
  float cb = 1, sb = 0, tb = 0, aspect = 0;  // cosine, sine and tangent of the slope; aspect
};

Tilt tilt_at(const Terrain& t, int col, int row) {
  Tilt tilt;
  if (!t.valid(col, row)) return tilt;
  double slope = 0, aspect = 0;
  horn_slope_aspect(t, col, row, slope, aspect);
  tilt.cb = static_cast<float>(std::cos(slope)), tilt.sb = static_cast<float>(std::sin(slope));
  tilt.tb = static_cast<float>(std::tan(slope)), tilt.aspect = static_cast<float>(aspect);
  return tilt;
}

// The offset of a cell's sectors from its aspect, as cosine and sine (floats, as the tilt).
void sector_offset(double rotation, float aspect, float& cos_offset, float& sin_offset) {
  const double offset = rotation - aspect;
  cos_offset = static_cast<float>(std::cos(offset)), sin_offset = static_cast<float>(std::sin(offset));
}

// A cell's sums over all n directions.
struct Totals {
  double svf, visibility, surface, openness, lowest;
};

// Writes the products of window cell (wc, wr) from its totals over n directions, or leaves them
// NaN (nodata; --edge nodata where the search circle leaves the raster).
void write_cell(const Terrain& terrain, const Window& window, int wc, int wr, double radius, EdgeMode edge, int n,
                const Totals& sums, bool lower, ProductSet keep, SkyViewProducts& p, unsigned char& leaves) {
  const int col = window.col0 + wc, row = window.row0 + wr;
  if (!terrain.valid(col, row)) return;
  if (search_circle_leaves_raster(terrain, col, row, radius)) {
    leaves = 1;
    if (edge == EdgeMode::nodata) return;
  }
  if (keep.has(Product::svf)) p.svf(wc, wr) = static_cast<float>(1.0 - sums.svf / n);
  if (keep.has(Product::sky_visibility)) p.sky_visibility(wc, wr) = static_cast<float>(1.0 - sums.visibility / n);
  if (keep.has(Product::svf_surface)) p.svf_surface(wc, wr) = static_cast<float>(std::clamp(sums.surface, 0.0, 1.0));
  if (keep.has(Product::openness_positive)) p.openness_positive(wc, wr) = static_cast<float>(sums.openness / n);
  if (lower && keep.has(Product::openness_negative)) p.openness_negative(wc, wr) = static_cast<float>(sums.lowest / n);
}

// Each product's sum per cell of a chunk, in the order of Totals (SkyViewSums keeps its running
// sums in this order).
struct ProductSum {
  Product product;
  double (SkySums::*chunk)[kChunk];
};
constexpr ProductSum kSums[] = {
    {Product::svf, &SkySums::svf},
    {Product::sky_visibility, &SkySums::visibility},
    {Product::svf_surface, &SkySums::surface},
    {Product::openness_positive, &SkySums::openness},
    {Product::openness_negative, &SkySums::lowest},
};

SkyViewProducts empty_products(const Window& window, ProductSet keep) {
  SkyViewProducts p;
  for (const auto& [product, grid] : kProductGrids) {
    if (keep.has(product)) p.*grid = Grid<float>(window.cols, window.rows, kNaN);
  }
  return p;
}

}  // namespace

SkyViewProducts sky_view_products(const Terrain& terrain, const Window& window, const HorizonField& field,
                                  double radius, EdgeMode edge) {
  SkyViewProducts p = empty_products(window, ProductSet::all());
  const int w = window.cols, h = window.rows, n = field.directions;
  const bool lower = !field.lower.empty();
  std::vector<unsigned char> leaves(static_cast<std::size_t>(w) * h, 0);
  if (field.sectors.size() != n)
    throw Error("sky-view products: the field's sectors are not its directions (internal error)");
  const Sectors sectors(field.sectors);
  // Rows in chunks of cells, each summed over every direction's plane with its sums in the
  // first-level cache: contiguous reads, and nothing kept per cell.
  tbb::parallel_for(0, h, [&](int wr) {
    auto sums = std::make_unique<SkySums>();
    for (int c0 = 0; c0 < w; c0 += kChunk) {
      const int count = std::min(kChunk, w - c0);
      const std::size_t first = field.cell(c0, wr);
      for (int i = 0; i < count; ++i) {
        const Tilt tilt = tilt_at(terrain, window.col0 + c0 + i, window.row0 + wr);
        float cos_offset, sin_offset;
        sector_offset(field.cell_rotation(first + i), tilt.aspect, cos_offset, sin_offset);
        sums->set_tilt(i, tilt.cb, tilt.sb, tilt.tb, cos_offset, sin_offset);
        sums->clear(i);
      }
      add_planes(*sums, sectors, 0, n, field.upper.data(), lower ? field.lower.data() : nullptr, field.cells(), first,
                 count, true);
      for (int i = 0; i < count; ++i) {
        const Totals totals{sums->svf[i], sums->visibility[i], sums->surface[i], sums->openness[i], sums->lowest[i]};
        write_cell(terrain, window, c0 + i, wr, radius, edge, n, totals, lower, ProductSet::all(), p,
                   leaves[first + i]);
      }
    }
  });
  for (unsigned char l : leaves) p.edge_cells += l;
  return p;
}

// What SkyViewSums keeps per cell of the window: a running sum for each kept product (the others
// stay null) and, for svf_surface, the tilt and the sectors' offset from the aspect (set with the
// first direction, which brings the cell's rotation). All of it is uninitialised huge-page memory
// that the first batch writes in parallel (its sums start from zero in the chunk): zeroing 64 bytes a
// cell on one thread with a fault every 4 KB took a fifth of a default run's CPU time at 1000 x 1000
// (perf, Dec 7).
struct SkyViewSums::State {
  const Terrain& terrain;
  Window window;
  Sectors sectors;     // sectors.n: the directions
  ProductSet keep;     // the products summed
  std::size_t cells;   // of the window
  int next = 0;        // the next direction to add
  bool lower = false;  // lowest angles were added
  LargeBuffer<Tilt> tilt;
  LargeBuffer<float> cos_offset, sin_offset;
  LargeBuffer<double> sums[std::size(kSums)];  // kSums' order

  State(const Terrain& t, const Window& w, int n, ProductSet k)
      : terrain(t), window(w), sectors(n), keep(k), cells(static_cast<std::size_t>(w.cols) * w.rows) {
    for (std::size_t s = 0; s < std::size(kSums); ++s) {
      if (keep.has(kSums[s].product)) sums[s] = allocate_large<double>(cells);
    }
    if (!keep.has(Product::svf_surface)) return;
    tilt = allocate_large<Tilt>(cells);
    cos_offset = allocate_large<float>(cells), sin_offset = allocate_large<float>(cells);
    tbb::parallel_for(0, w.rows, [&](int wr) {
      for (int wc = 0; wc < w.cols; ++wc)
        tilt[static_cast<std::size_t>(wr) * w.cols + wc] = tilt_at(t, w.col0 + wc, w.row0 + wr);
    });
  }

  // kSums' order is Totals' order.
  double sum(std::size_t s, std::size_t c) const { return sums[s] ? sums[s][c] : 0.0; }
  Totals totals(std::size_t c) const { return {sum(0, c), sum(1, c), sum(2, c), sum(3, c), sum(4, c)}; }
  // Window cells [c0, c0 + n)'s sums to and from the chunk's first n cells, one array at a time (the
  // first batch starts from zero). A product not kept still sums into its chunk array (the loop is
  // shared), which nothing reads, so it is neither loaded nor cleared.
  void load(std::size_t c0, int n, SkySums& chunk, bool first) const {
    for (std::size_t s = 0; s < std::size(kSums); ++s) {
      if (!sums[s]) continue;
      if (first)
        std::fill_n(chunk.*kSums[s].chunk, n, 0.0);
      else
        std::copy_n(sums[s].get() + c0, n, chunk.*kSums[s].chunk);
    }
  }
  void store(std::size_t c0, int n, const SkySums& chunk) {
    for (std::size_t s = 0; s < std::size(kSums); ++s) {
      if (sums[s]) std::copy_n(chunk.*kSums[s].chunk, n, sums[s].get() + c0);
    }
  }
};

int SkyViewSums::bytes_per_cell(ProductSet keep) {
  int bytes = 0;
  for (const ProductSum& sum : kSums) bytes += keep.has(sum.product) ? static_cast<int>(sizeof(double)) : 0;
  if (keep.has(Product::svf_surface)) bytes += static_cast<int>(sizeof(Tilt) + 2 * sizeof(float));
  return bytes;
}

SkyViewSums::SkyViewSums(const Terrain& terrain, const Window& window, int directions, ProductSet keep)
    : s_(std::make_unique<State>(terrain, window, directions, keep)) {}

SkyViewSums::~SkyViewSums() = default;

void SkyViewSums::add(int first, int count, const float* upper, const float* lower, const HorizonField& rotations) {
  State& st = *s_;
  if (first != st.next || count < 1 || first + count > st.sectors.n)
    throw Error("sky-view sums: directions must be added in order (internal error)");
  if (first == 0) {
    st.lower = lower != nullptr;
    // The field names its sectors once the engine has set them: they come with the first batch.
    if (rotations.sectors.size() != st.sectors.n)
      throw Error("sky-view sums: the field's sectors are not the directions added (internal error)");
    st.sectors = Sectors(rotations.sectors);
  }
  if (st.lower != (lower != nullptr))
    throw Error("sky-view sums: lowest angles for some directions only (internal error)");
  const std::size_t cells = st.cells;
  const bool tilted = st.keep.has(Product::svf_surface);
  // Chunks of cells, each summed over the batch's planes with its sums in the first-level cache.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells, kChunk), [&](const tbb::blocked_range<std::size_t>& r) {
    auto chunk = std::make_unique<SkySums>();
    for (std::size_t c0 = r.begin(); c0 < r.end(); c0 += kChunk) {
      const int n = static_cast<int>(std::min<std::size_t>(kChunk, r.end() - c0));
      if (tilted) {  // the level loop (no svf_surface) reads no tilt
        for (int i = 0; i < n; ++i) {
          const std::size_t c = c0 + i;
          const Tilt& tilt = st.tilt[c];
          if (first == 0) sector_offset(rotations.cell_rotation(c), tilt.aspect, st.cos_offset[c], st.sin_offset[c]);
          chunk->set_tilt(i, tilt.cb, tilt.sb, tilt.tb, st.cos_offset[c], st.sin_offset[c]);
        }
      }
      st.load(c0, n, *chunk, first == 0);
      add_planes(*chunk, st.sectors, first, count, upper, lower, cells, c0, n, tilted);
      st.store(c0, n, *chunk);
    }
  });
  st.next += count;
}

SkyViewProducts SkyViewSums::finish(double radius, EdgeMode edge) const {
  const State& st = *s_;
  if (st.next != st.sectors.n) throw Error("sky-view sums: not every direction was added (internal error)");
  const Window& window = st.window;
  SkyViewProducts p = empty_products(window, st.keep);
  std::vector<unsigned char> leaves(st.cells, 0);
  tbb::parallel_for(0, window.rows, [&](int wr) {
    for (int wc = 0; wc < window.cols; ++wc) {
      const std::size_t c = static_cast<std::size_t>(wr) * window.cols + wc;
      write_cell(st.terrain, window, wc, wr, radius, edge, st.sectors.n, st.totals(c), st.lower, st.keep, p, leaves[c]);
    }
  });
  for (unsigned char l : leaves) p.edge_cells += l;
  return p;
}

}  // namespace skyview
