// Per-cell exposure sums, direction by direction.
#include "exposure/exposure_sums.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "skyview/core/error.h"

namespace skyview::detail {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr Direction kUp{0, 0, 1};

}  // namespace

struct ExposureSums::State {
  const ExposureSetup& setup;
  Window window;
  std::size_t cells;
  int next = 0;
  std::vector<Direction> normal;  // the cell's surface (Horn); NaN on nodata
  std::vector<float> tilt;        // its slope, radians
  // Wh/m²: the tilted surface and a horizontal one, sky (fast: sun too) and, exact, sun.
  std::vector<double> direct, diffuse, direct_h, diffuse_h;
  GapPlanes planes;  // exact: pairs the directions either side of each gap

  State(const Terrain& t, const Window& w, const ExposureSetup& s)
      : setup(s), window(w), cells(static_cast<std::size_t>(w.cols) * w.rows), planes(s.directions, cells) {
    normal.resize(cells);
    tilt.resize(cells);
    direct.assign(cells, 0.0), diffuse.assign(cells, 0.0), direct_h.assign(cells, 0.0), diffuse_h.assign(cells, 0.0);
    tbb::parallel_for(0, w.rows, [&](int wr) {
      for (int wc = 0; wc < w.cols; ++wc) {
        const std::size_t c = static_cast<std::size_t>(wr) * w.cols + wc;
        const int col = w.col0 + wc, row = w.row0 + wr;
        if (!t.valid(col, row)) {
          normal[c] = {NAN, NAN, NAN};
          tilt[c] = kNaN;
          continue;
        }
        double slope, aspect;
        horn_slope_aspect(t, col, row, slope, aspect);
        normal[c] = {std::sin(slope) * std::sin(aspect), std::sin(slope) * std::cos(aspect), std::cos(slope)};
        if (slope == 0.0) normal[c] = kUp;
        tilt[c] = static_cast<float>(slope);
      }
    });
  }

  // The sky through slice k for the cells [c0, c1).
  void add_sky(int k, const float* plane, const HorizonField& field, std::size_t c0, std::size_t c1) {
    const float top = static_cast<float>(std::numbers::pi / 2);
    for (std::size_t c = c0; c < c1; ++c) {
      const float h = plane[c];
      if (std::isnan(h)) continue;
      const double turn = field.rotation.empty() ? 0.0 : field.rotation[c];
      SkyExposure sums[2];
      const Direction normals[2] = {normal[c], kUp};
      const bool flat = normal[c][2] == 1.0;
      setup.sampler->add_slice(k, h, top, {normals, flat ? 1u : 2u}, {sums, flat ? 1u : 2u}, turn);
      if (flat) sums[1] = sums[0];
      diffuse[c] += sums[0].diffuse;
      diffuse_h[c] += sums[1].diffuse;
      if (setup.method == ExposureMethod::fast) {
        direct[c] += sums[0].direct;
        direct_h[c] += sums[1].direct;
      }
    }
  }

  // The sky of gap k (between directions k and k + 1) for the cells [c0, c1), horizons h0 and h1.
  void add_sky_gap(int k, const float* h0, const float* h1, std::size_t c0, std::size_t c1) {
    for (std::size_t c = c0; c < c1; ++c) {
      if (std::isnan(h0[c]) || std::isnan(h1[c])) continue;
      SkyExposure sums[2];
      const Direction normals[2] = {normal[c], kUp};
      const bool flat = normal[c][2] == 1.0;
      setup.sampler->add_gap(k, h0[c], h1[c], {normals, flat ? 1u : 2u}, {sums, flat ? 1u : 2u});
      if (flat) sums[1] = sums[0];
      diffuse[c] += sums[0].diffuse;
      diffuse_h[c] += sums[1].diffuse;
      if (setup.method == ExposureMethod::fast) {
        direct[c] += sums[0].direct;
        direct_h[c] += sums[1].direct;
      }
    }
  }

  // The sun of gap k (between directions k and k + 1) for the cells [c0, c1), horizons h0 and h1.
  void add_sun(int k, const float* h0, const float* h1, std::size_t c0, std::size_t c1) {
    const SunGap& gap = setup.gaps[static_cast<std::size_t>(k)];
    if (gap.sun.empty()) return;
    for (std::size_t c = c0; c < c1; ++c) {
      const double a = h0[c], b = h1[c];
      if (std::isnan(a) || std::isnan(b)) continue;
      const Direction& n = normal[c];
      if (std::max(a, b) < gap.lowest) {
        // No horizon of the pair reaches this gap's sun: every step is seen, and where the surface
        // is no steeper than the lowest sun, every one falls on its front (n·s ≥ sin(e − slope)).
        direct_h[c] += gap.beam[2];
        if (tilt[c] <= gap.lowest) {
          direct[c] += n[0] * gap.beam[0] + n[1] * gap.beam[1] + n[2] * gap.beam[2];
          continue;
        }
        double sum = 0.0;
        for (const SunGap::Sun& s : gap.sun) {
          const double cosine = n[0] * s.direction[0] + n[1] * s.direction[1] + n[2] * s.direction[2];
          if (cosine > 0.0) sum += s.beam * cosine;
        }
        direct[c] += sum;
        continue;
      }
      double sum = 0.0, sum_h = 0.0;
      for (const SunGap::Sun& s : gap.sun) {
        if (!(s.elevation > a + s.share * (b - a))) continue;
        sum_h += s.beam * s.direction[2];
        const double cosine = n[0] * s.direction[0] + n[1] * s.direction[1] + n[2] * s.direction[2];
        if (cosine > 0.0) sum += s.beam * cosine;
      }
      direct[c] += sum;
      direct_h[c] += sum_h;
    }
  }
};

ExposureSums::ExposureSums(const Terrain& terrain, const Window& window, const ExposureSetup& setup)
    : s_(std::make_unique<State>(terrain, window, setup)) {}

ExposureSums::~ExposureSums() = default;

void ExposureSums::add(int first, int count, const float* upper, const HorizonField& field) {
  State& st = *s_;
  const int n = st.setup.directions;
  if (first != st.next || count < 1 || first + count > n)
    throw Error("exposure sums: directions must be added in order (internal error)");
  if (first == 0 && std::abs(std::remainder(field.sector_rotation - st.setup.rotation, 2 * std::numbers::pi)) > 1e-9)
    throw Error("exposure sums: the field's directions are not the sampler's (internal error)");
  const std::size_t cells = st.cells;
  const bool exact = st.setup.method == ExposureMethod::exact;
  const bool gaps = st.setup.sky_by_gaps;
  if (!gaps) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
      for (int i = 0; i < count; ++i) st.add_sky(first + i, upper + cells * i, field, r.begin(), r.end());
    });
  }
  if (gaps || exact) {
    st.planes.add(first, count, upper, [&](int gap, const float* h0, const float* h1) {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
        if (gaps) st.add_sky_gap(gap, h0, h1, r.begin(), r.end());
        if (exact) st.add_sun(gap, h0, h1, r.begin(), r.end());
      });
    });
  }
  st.next += count;
}

void ExposureSums::finish(const SkyViewProducts& products, int row0, ExposureBands& out) const {
  const State& st = *s_;
  if (st.next != st.setup.directions) throw Error("exposure sums: not every direction was added (internal error)");
  const Window& w = st.window;
  const double ghi = st.setup.global_horizontal;
  tbb::parallel_for(0, w.rows, [&](int wr) {
    for (int wc = 0; wc < w.cols; ++wc) {
      const std::size_t c = static_cast<std::size_t>(wr) * w.cols + wc;
      const int orow = row0 + wr;
      const float svf = products.svf(wc, wr), svf_surface = products.svf_surface(wc, wr);
      double albedo = st.setup.albedo;
      if (st.setup.albedo_grid) albedo = (*st.setup.albedo_grid)(wc, orow);
      const bool valid = !std::isnan(st.normal[c][2]) && !std::isnan(svf);  // svf: nodata at the edge
      auto put = [&](Grid<float>& g, double wh) { g(wc, orow) = valid ? static_cast<float>(wh / 1000.0) : kNaN; };
      // The isotropic reflected term: the unobstructed global horizontal exposure, times the albedo,
      // over the part of the surface's view that is not sky.
      const double reflected = albedo * ghi * (1.0 - svf_surface);
      const double reflected_h = albedo * ghi * (1.0 - svf);
      put(out.direct, st.direct[c]);
      put(out.diffuse, st.diffuse[c]);
      put(out.reflected, reflected);
      put(out.total, st.direct[c] + st.diffuse[c] + reflected);
      put(out.horizontal_total, st.direct_h[c] + st.diffuse_h[c] + reflected_h);
      out.svf(wc, orow) = valid ? svf : kNaN;
    }
  });
}

}  // namespace skyview::detail
