// Turning a period or a weather file into exposure-map time steps.
#include "skyview/sky/exposure_steps.h"

#include <cmath>
#include <numbers>

#include "skyview/solar/civil_time.h"
#include "skyview/core/error.h"

namespace skyview {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

SkyConditions conditions_at(const Site& site, double t) {
  const SunPosition sun = solar_position(t, site);
  SkyConditions c;
  c.sun_zenith = sun.zenith_deg * kDegree;
  c.sun_azimuth = sun.azimuth_deg * kDegree;
  c.day_of_year = day_of_year_utc(t);
  return c;
}

}  // namespace

int day_of_year_utc(double t) {
  const auto days = static_cast<std::int64_t>(std::floor(t / 86400.0));
  const CivilDate d = civil_from_days(days);
  return static_cast<int>(days - days_from_civil(CivilDate{d.year, 1, 1})) + 1;
}

std::vector<ExposureStep> regular_steps(const Site& site, double from, double to, double step_s) {
  if (!(to > from)) throw Error("the period is empty: --to must be later than --from");
  if (!(step_s > 0.0)) throw Error("the time step must be positive");
  const double count = std::ceil((to - from) / step_s - 1e-9);
  if (count > 1e7) throw Error("more than 10 million time steps; use a longer --step");
  std::vector<ExposureStep> steps;
  steps.reserve(static_cast<std::size_t>(count));
  for (double start = from; start < to - 1e-6; start += step_s) {
    const double end = std::min(start + step_s, to);
    ExposureStep s;
    s.conditions = conditions_at(site, 0.5 * (start + end));
    s.hours = (end - start) / 3600.0;
    steps.push_back(s);
  }
  return steps;
}

std::vector<ExposureStep> epw_steps(const EpwFile& file, const Site& site, std::optional<TimePeriod> period) {
  std::vector<ExposureStep> steps;
  auto add = [&](const EpwRecord& r, double t) {
    ExposureStep s;
    s.conditions = conditions_at(site, t);
    s.conditions.global_horizontal = r.global_horizontal;
    s.conditions.direct_normal = r.direct_normal;
    s.conditions.diffuse_horizontal = r.diffuse_horizontal;
    s.hours = 1.0;
    steps.push_back(s);
  };
  if (!period) {
    for (const EpwRecord& r : file.records) add(r, r.time_utc);
  } else {
    if (!(period->to_utc > period->from_utc)) throw Error("the period is empty: --to must be later than --from");
    const int first = civil_from_days(static_cast<std::int64_t>(std::floor(period->from_utc / 86400.0))).year - 1;
    const int last = civil_from_days(static_cast<std::int64_t>(std::floor(period->to_utc / 86400.0))).year + 1;
    for (int year = first; year <= last; ++year) {
      for (const EpwRecord& r : file.records) {
        if (r.month == 2 && r.day == 29 && !(year % 4 == 0 && (year % 100 != 0 || year % 400 == 0))) continue;
        const double shift = static_cast<double>(days_from_civil(CivilDate{year, r.month, r.day}) -
                                                 days_from_civil(CivilDate{r.year, r.month, r.day})) *
                             86400.0;
        const double t = r.time_utc + shift;
        if (t >= period->from_utc && t < period->to_utc) add(r, t);
      }
    }
  }
  if (steps.empty()) throw Error("no weather record falls within the period");
  return steps;
}

}  // namespace skyview
