#pragma once
// The sun against a cell's horizon: the test skyview exposure --method exact, skyview shadow and
// skyview sunhours share. A horizon field holds the horizon of N uniform directions; towards the
// sun's azimuth it is interpolated linearly between the two directions either side, and the sun's
// centre is visible where its elevation is above that. For soft shadows the visible fraction of
// the solar disc is the part of the disc above the horizon line (taken level across the disc).
#include <span>
#include <vector>

#include "skyview/sky/exposure_map.h"
#include "skyview/sky/sky_model.h"

namespace skyview {

// One time step's sun, for tests against horizons.
struct SunStep {
  double azimuth = 0.0;    // radians clockwise from north
  double elevation = 0.0;  // radians, topocentric and refracted
  Direction direction{0, 0, 1};
  double beam = 0.0;      // direct-normal exposure of the step, DNI × hours (Wh/m²)
  double hours = 0.0;     // the step's length
  double time_utc = 0.0;  // its representative instant, where known (Unix seconds)
};

// The steps with the sun's centre above the horizontal and a beam (night and beamless hours cost
// nothing afterwards), each with the model's direct-normal irradiance times its hours.
std::vector<SunStep> sun_steps(const SkyModel& model, std::span<const ExposureStep> steps);

SunStep sun_step(double azimuth, double elevation);  // direction from the angles; no beam

// The two directions of a uniform set (direction k at rotation + 2πk/n) either side of an azimuth,
// and the weight of the second: the horizon towards it is (1 − f) h[k0] + f h[k1].
struct SunBracket {
  int k0 = 0, k1 = 0;
  double f = 0.0;
};
SunBracket bracket_azimuth(double azimuth, int directions, double rotation);

inline double horizon_towards(const SunBracket& b, double h0, double h1) { return h0 + b.f * (h1 - h0); }

// The visible share of a disc of angular radius r whose centre stands d above a level horizon
// line (d < 0: below): 0 for d <= −r, 1 for d >= r, the circular segment's area in between.
double visible_disc_fraction(double d, double r);

}  // namespace skyview
