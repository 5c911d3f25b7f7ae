#pragma once
// The time steps an exposure map integrates: regular steps between two instants with the sun
// from SPA, or the hours of an EPW weather file with their measured irradiances.
#include <optional>
#include <vector>

#include "skyview/sky/epw.h"
#include "skyview/sky/exposure_map.h"
#include "skyview/solar/solar_position.h"

namespace skyview {

// Steps of `step_s` seconds covering [from, to) (the last one shortened to end at `to`), each
// represented by its midpoint. Throws skyview::Error when to <= from or step_s <= 0, or for more
// than 10 million steps.
std::vector<ExposureStep> regular_steps(const Site& site, double from_utc, double to_utc, double step_s);

// One step of one hour per EPW record, at the instant its irradiance refers to, carrying the
// measured GHI, DNI and DHI. Without a period the records keep their own (possibly mixed) years;
// with one, the file is read as a typical year repeated over every calendar year the period
// touches, and records whose instant falls in [from, to) are kept (a missing 29 February stays
// missing). Throws skyview::Error when no record falls in the period.
struct TimePeriod {
  double from_utc = 0.0, to_utc = 0.0;
};
std::vector<ExposureStep> epw_steps(const EpwFile& file, const Site& site, std::optional<TimePeriod> period = {});

// Day of the year (1..366) of a Unix time, in UTC.
int day_of_year_utc(double unix_time_utc);

}  // namespace skyview
