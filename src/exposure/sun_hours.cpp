// Sun hours: daylight steps against horizons interpolated at the sun's azimuth.
#include "skyview/exposure/sun_hours.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "exposure/horizon_feed.h"
#include "exposure/sun_gaps.h"
#include "skyview/core/error.h"

namespace skyview {

std::vector<SunStep> daylight_steps(const Site& site, double from, double to, double step_s) {
  if (!(to > from)) throw Error("the period is empty: --to must be later than --from");
  if (!(step_s > 0.0)) throw Error("the time step must be positive");
  if (!(step_s < to - from)) throw Error("the time step is not shorter than the period");
  if ((to - from) / step_s > 1e7) throw Error("more than 10 million time steps; use a longer --step");
  constexpr double kDegree = std::numbers::pi / 180.0;
  std::vector<SunStep> out;
  for (double start = from; start < to - 1e-6; start += step_s) {
    const double end = std::min(start + step_s, to), middle = 0.5 * (start + end);
    const SunPosition sun = solar_position(middle, site);
    if (!(sun.elevation_deg > 0.0)) continue;
    SunStep s = sun_step(sun.azimuth_deg * kDegree, sun.elevation_deg * kDegree);
    s.time_utc = middle;
    s.hours = (end - start) / 3600.0;
    out.push_back(s);
  }
  return out;
}

SunHoursBands compute_sun_hours(const HorizonEngine& engine, const Terrain& terrain, const Window& window,
                                std::span<const SunStep> steps, double start_utc, ProgressCounter& progress) {
  const HorizonParams& params = engine.params();
  if (params.spacing != AzimuthSpacing::uniform || engine.name() == "sampled") {
    throw Error(
        "sun hours interpolate the horizon between fixed, uniform directions: use sweep, march or raycast "
        "with uniform --azimuths");
  }
  const int n = params.directions;
  const double rotation = direction_set_rotation(params, terrain);
  const std::vector<detail::SunGap> gaps = detail::sort_into_gaps(steps, n, rotation);
  // Per gap, what a cell that sees all of its steps adds.
  struct Whole {
    double hours = 0, first = INFINITY, last = -INFINITY;
  };
  std::vector<Whole> whole(gaps.size());
  // Each step's start and end in hours from the period's start.
  std::vector<double> begins(steps.size()), ends(steps.size());
  for (std::size_t i = 0; i < steps.size(); ++i) {
    begins[i] = (steps[i].time_utc - start_utc) / 3600.0 - 0.5 * steps[i].hours;
    ends[i] = begins[i] + steps[i].hours;
  }
  for (std::size_t g = 0; g < gaps.size(); ++g) {
    for (const detail::SunGap::Sun& s : gaps[g].sun) {
      whole[g].hours += steps[s.step].hours;
      whole[g].first = std::min(whole[g].first, begins[s.step]);
      whole[g].last = std::max(whole[g].last, ends[s.step]);
    }
  }
  SunHoursBands out;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  out.sun_hours = out.first_sun = out.last_sun = Grid<float>(window.cols, window.rows, nan);

  struct Consumer final : detail::HorizonConsumer {
    std::size_t cells;
    Window block;
    int row0;
    std::vector<double> hours, first, last;
    std::vector<unsigned char> valid;
    detail::GapPlanes planes;
    const std::vector<detail::SunGap>& gaps;
    const std::vector<Whole>& whole;
    const std::vector<double>&begins, &ends;
    SunHoursBands& out;
    Consumer(const Window& b, int first_row, int n, const std::vector<detail::SunGap>& g, const std::vector<Whole>& w,
             const std::vector<double>& begin_of, const std::vector<double>& end_of, SunHoursBands& bands)
        : cells(static_cast<std::size_t>(b.cols) * b.rows),
          block(b),
          row0(first_row),
          hours(cells, 0.0),
          first(cells, INFINITY),
          last(cells, -INFINITY),
          valid(cells, 0),
          planes(n, cells),
          gaps(g),
          whole(w),
          begins(begin_of),
          ends(end_of),
          out(bands) {}
    void add(int first_direction, int count, const float* upper, const HorizonField&) override {
      if (first_direction == 0) {
        for (std::size_t c = 0; c < cells; ++c) valid[c] = !std::isnan(upper[c]);
      }
      planes.add(first_direction, count, upper, [&](int k, const float* h0, const float* h1) {
        const detail::SunGap& gap = gaps[static_cast<std::size_t>(k)];
        if (gap.sun.empty()) return;
        const Whole& all = whole[static_cast<std::size_t>(k)];
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells, 1024), [&](const auto& r) {
          for (std::size_t c = r.begin(); c < r.end(); ++c) {
            const double a = h0[c], b = h1[c];
            if (std::isnan(a) || std::isnan(b)) continue;
            if (std::max(a, b) < gap.lowest) {  // no horizon of the pair reaches this gap's sun
              hours[c] += all.hours;
              first[c] = std::min(first[c], all.first);
              last[c] = std::max(last[c], all.last);
              continue;
            }
            for (const detail::SunGap::Sun& s : gap.sun) {
              if (!(s.elevation > a + s.share * (b - a))) continue;
              hours[c] += ends[s.step] - begins[s.step];
              first[c] = std::min(first[c], begins[s.step]);
              last[c] = std::max(last[c], ends[s.step]);
            }
          }
        });
      });
    }
    void finish() override {
      for (int wr = 0; wr < block.rows; ++wr) {
        for (int wc = 0; wc < block.cols; ++wc) {
          const std::size_t c = static_cast<std::size_t>(wr) * block.cols + wc;
          if (!valid[c]) continue;
          out.sun_hours(wc, row0 + wr) = static_cast<float>(hours[c]);
          if (hours[c] > 0.0) {
            out.first_sun(wc, row0 + wr) = static_cast<float>(first[c]);
            out.last_sun(wc, row0 + wr) = static_cast<float>(last[c]);
          }
        }
      }
    }
  };
  detail::feed_horizons(engine, terrain, window, progress, kHorizonBlockBytes, [&](const Window& block) {
    return std::make_unique<Consumer>(block, block.row0 - window.row0, n, gaps, whole, begins, ends, out);
  });
  return out;
}

}  // namespace skyview
