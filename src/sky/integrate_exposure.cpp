// Time integration of a sky model into an exposure map. Per step the sky is tabulated once on
// (row zenith angle) × (angle from the sun) and every cell reads that table: cos γ of a cell is
// a·cos(φ − φ_sun) + b with per-row a and b, so a cell costs a few multiplies, a square root and
// a lerp instead of the model's exponentials. Steps run in parallel into per-thread maps.
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#ifdef __SSE2__
#include <immintrin.h>
#endif
#include <cmath>
#include <numbers>
#include <string>

#include "skyview/core/error.h"
#include "skyview/sky/exposure_map.h"

namespace skyview {
namespace {

struct Geometry {
  int width, height, samples;
  std::vector<double> theta, sin_theta, cos_theta, solid_angle;
  std::vector<double> cos_phi, sin_phi;
  std::vector<double> gamma;  // γ_j = 2·asin(j / (samples − 1))
};

// Per-thread sums. The diffuse band is summed in float over a chunk of steps (fast) and flushed
// into double after each chunk, so a year of steps loses no precision.
struct Accumulator {
  std::vector<double> direct, diffuse;
  std::vector<float> partial_diffuse;
  std::vector<float> table;
  std::vector<float> cos_dphi, position;
  explicit Accumulator(const Geometry& g)
      : direct(static_cast<std::size_t>(g.width) * g.height, 0.0),
        diffuse(direct.size(), 0.0),
        partial_diffuse(direct.size(), 0.0f),
        table(static_cast<std::size_t>(g.height) * g.samples),
        cos_dphi(g.width),
        position(g.width) {}
  void flush() {
    for (std::size_t i = 0; i < diffuse.size(); ++i) diffuse[i] += partial_diffuse[i];
    std::fill(partial_diffuse.begin(), partial_diffuse.end(), 0.0f);
  }
};

// sqrt over a row; SSE2 (x86-64 baseline) does four at once, which the compiler will not do for
// std::sqrt without -fno-math-errno.
void sqrt_in_place(float* v, int n) {
  int x = 0;
#ifdef __SSE2__
  for (; x + 4 <= n; x += 4) _mm_storeu_ps(v + x, _mm_sqrt_ps(_mm_loadu_ps(v + x)));
#endif
  for (; x < n; ++x) v[x] = std::sqrt(v[x]);
}

void add_diffuse(const Geometry& g, const SkyInstant& sky, float hours, Accumulator& acc) {
  sky.tabulate(g.theta, g.gamma, acc.table.data());
  const double sz = std::sin(sky.sun_zenith()), cz = std::cos(sky.sun_zenith());
  const double cs = std::cos(sky.sun_azimuth()), ss = std::sin(sky.sun_azimuth());
  for (int x = 0; x < g.width; ++x) acc.cos_dphi[x] = static_cast<float>(g.cos_phi[x] * cs + g.sin_phi[x] * ss);
  const float last = static_cast<float>(g.samples - 1);
  float* pos = acc.position.data();
  for (int y = 0; y < g.height; ++y) {
    const float a = static_cast<float>(g.sin_theta[y] * sz), b = static_cast<float>(g.cos_theta[y] * cz);
    const float* t = acc.table.data() + static_cast<std::size_t>(y) * g.samples;
    float* out = acc.partial_diffuse.data() + static_cast<std::size_t>(y) * g.width;
    // Table position sin(γ/2)·(n−1), with 1 − cos γ = 2 sin²(γ/2).
    const float half_scaled = 0.5f * last * last;
    for (int x = 0; x < g.width; ++x) pos[x] = std::max(0.0f, half_scaled * (1.0f - (a * acc.cos_dphi[x] + b)));
    sqrt_in_place(pos, g.width);
    for (int x = 0; x < g.width; ++x) {
      const int k = std::min(static_cast<int>(pos[x]), g.samples - 2);
      const float f = pos[x] - static_cast<float>(k);
      out[x] += hours * (t[k] + f * (t[k + 1] - t[k]));
    }
  }
}

void add_sun(const Geometry& g, const SkyInstant& sky, double hours, const ExposureOptions& o, Accumulator& acc) {
  const double energy = sky.direct_normal() * hours;  // Wh/m² normal to the beam
  if (!(energy > 0.0)) return;
  const double z = sky.sun_zenith(), az = sky.sun_azimuth(), r = sky.sun_angular_radius();
  const Direction s{std::sin(z) * std::sin(az), std::sin(z) * std::cos(az), std::cos(z)};
  // Basis across the beam: e1 horizontal (along increasing azimuth), e2 = s × e1.
  const Direction e1{std::cos(az), -std::sin(az), 0.0};
  const Direction e2{s[1] * e1[2] - s[2] * e1[1], s[2] * e1[0] - s[0] * e1[2], s[0] * e1[1] - s[1] * e1[0]};
  struct Sample {
    double zenith, azimuth, weight;
  };
  std::vector<Sample> samples;
  double total = 0.0;
  for (int ring = 0; ring < o.disc_rings; ++ring) {
    const double rho = r * std::sqrt((ring + 0.5) / o.disc_rings);  // equal-area rings
    const double w = std::max(sky.sun_radiance(rho), 0.0);
    for (int k = 0; k < o.disc_sectors; ++k) {
      const double alpha = 2 * std::numbers::pi * (k + 0.5 * (ring % 2)) / o.disc_sectors;
      Direction d;
      for (int i = 0; i < 3; ++i) {
        d[i] = std::cos(rho) * s[i] + std::sin(rho) * (std::cos(alpha) * e1[i] + std::sin(alpha) * e2[i]);
      }
      double daz = std::atan2(d[0], d[1]);
      if (daz < 0) daz += 2 * std::numbers::pi;
      samples.push_back({std::acos(std::clamp(d[2], -1.0, 1.0)), daz, w});
      total += w;
    }
  }
  for (Sample& p : samples) p.weight = total > 0.0 ? p.weight / total : 1.0 / samples.size();
  for (const Sample& p : samples) {
    const double fx = p.azimuth / (2 * std::numbers::pi) * g.width - 0.5;
    const double fy = std::clamp(p.zenith / (std::numbers::pi / 2) * g.height - 0.5, 0.0, g.height - 1.0);
    const double x0f = std::floor(fx), y0f = std::floor(fy);
    const double tx = fx - x0f, ty = fy - y0f;
    const int x0 = (static_cast<int>(x0f) % g.width + g.width) % g.width, x1 = (x0 + 1) % g.width;
    const int y0 = static_cast<int>(y0f), y1 = std::min(y0 + 1, g.height - 1);
    const double e = energy * p.weight;
    acc.direct[static_cast<std::size_t>(y0) * g.width + x0] += e * (1 - tx) * (1 - ty) / g.solid_angle[y0];
    acc.direct[static_cast<std::size_t>(y0) * g.width + x1] += e * tx * (1 - ty) / g.solid_angle[y0];
    acc.direct[static_cast<std::size_t>(y1) * g.width + x0] += e * (1 - tx) * ty / g.solid_angle[y1];
    acc.direct[static_cast<std::size_t>(y1) * g.width + x1] += e * tx * ty / g.solid_angle[y1];
  }
}

}  // namespace

ExposureMap integrate_exposure(const SkyModel& model, std::span<const ExposureStep> steps, const ExposureOptions& o) {
  if (o.gamma_samples < 8 || o.disc_rings < 1 || o.disc_sectors < 1) {
    throw Error("exposure map: gamma_samples must be >= 8 and the disc needs at least one sample");
  }
  ExposureMap map(o.width, o.height);
  Geometry g{o.width, o.height, o.gamma_samples, {}, {}, {}, {}, {}, {}, {}};
  for (int y = 0; y < o.height; ++y) {
    const double theta = map.zenith_of_row(y + 0.5);
    g.theta.push_back(theta);
    g.sin_theta.push_back(std::sin(theta));
    g.cos_theta.push_back(std::cos(theta));
    g.solid_angle.push_back(map.cell_solid_angle(y));
  }
  for (int x = 0; x < o.width; ++x) {
    g.cos_phi.push_back(std::cos(map.azimuth_of_column(x + 0.5)));
    g.sin_phi.push_back(std::sin(map.azimuth_of_column(x + 0.5)));
  }
  for (int j = 0; j < o.gamma_samples; ++j) g.gamma.push_back(2.0 * std::asin(double(j) / (o.gamma_samples - 1)));

  for (const ExposureStep& s : steps) {
    if (!(s.hours >= 0.0) || !std::isfinite(s.conditions.sun_zenith) || !std::isfinite(s.conditions.sun_azimuth)) {
      throw Error("exposure map: a time step has a negative length or no sun position");
    }
  }
  tbb::enumerable_thread_specific<Accumulator> per_thread([&] { return Accumulator(g); });
  // Chunks of at most 64 steps: few enough float additions per cell to stay exact to ~1e-5.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, steps.size(), 16), [&](const auto& range) {
    Accumulator& acc = per_thread.local();
    for (std::size_t begin = range.begin(); begin < range.end(); begin += 64) {
      bool any = false;
      for (std::size_t i = begin; i < std::min(begin + 64, range.end()); ++i) {
        const ExposureStep& s = steps[i];
        if (s.hours == 0.0) continue;
        const auto sky = model.at(s.conditions);
        if (sky->has_diffuse()) {
          add_diffuse(g, *sky, static_cast<float>(s.hours), acc);
          any = true;
        }
        if (s.conditions.sun_zenith < std::numbers::pi / 2) add_sun(g, *sky, s.hours, o, acc);
      }
      if (any) acc.flush();
    }
  });
  std::vector<double> direct(map.band(ExposureBand::direct).size(), 0.0), diffuse(direct.size(), 0.0);
  for (const Accumulator& acc : per_thread) {
    for (std::size_t i = 0; i < direct.size(); ++i) {
      direct[i] += acc.direct[i];
      diffuse[i] += acc.diffuse[i];
    }
  }
  std::copy(direct.begin(), direct.end(), map.band(ExposureBand::direct).begin());
  std::copy(diffuse.begin(), diffuse.end(), map.band(ExposureBand::diffuse).begin());
  return map;
}

}  // namespace skyview
