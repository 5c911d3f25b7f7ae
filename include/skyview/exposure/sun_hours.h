#pragma once
// Hours of direct sun per cell over a period (skyview sunhours; docs/commands/sunhours.md): each
// step's sun, at the step's middle, against the cell's horizon interpolated at the sun's azimuth
// between the two nearest of the engine's directions (the test of sun_horizon.h). Also the first
// and the last sunlit moment, the metric of right-to-light rules and thermal-comfort studies.
#include <span>
#include <vector>

#include "skyview/core/grid.h"
#include "skyview/core/progress.h"
#include "skyview/exposure/sun_horizon.h"
#include "skyview/horizon/horizon_engine.h"
#include "skyview/solar/solar_position.h"

namespace skyview {

// Steps of `step_s` seconds over [from, to) (the last one shortened) whose sun's centre, at the
// step's middle, is above the horizontal: time_utc its middle, hours its length, beam 0. Throws
// skyview::Error for an empty period, a step not shorter than it, or more than 10 million steps.
std::vector<SunStep> daylight_steps(const Site& site, double from_utc, double to_utc, double step_s);

struct SunHoursBands {
  Grid<float> sun_hours;  // hours with the sun's centre seen
  // Hours from the period's start to the start of the first sunlit step and to the end of the
  // last one; NaN where the sun is never seen.
  Grid<float> first_sun, last_sun;
};

// Sun hours of the cells of `window` from `engine`'s horizons (uniform directions, the same for
// every cell: not the sampled method). `start_utc`: the period's start.
SunHoursBands compute_sun_hours(const HorizonEngine& engine, const Terrain& terrain, const Window& window,
                                std::span<const SunStep> steps, double start_utc, ProgressCounter& progress);

}  // namespace skyview
