#pragma once
// Earth curvature and refraction: a target at ground distance d appears lower by
// drop = (1 - k) d^2 / (2 R), k the refraction coefficient (0.13 for standard air).
// Folding the drop into the target's height keeps every method exact in the same model.
#include <string>

#include "skyview/horizon/horizon_engine.h"

namespace skyview::detail {

// Coefficient c of drop = c d^2 for the requested mode; "auto" turns curvature on when the
// drop at `max_distance` would change an angle by more than 0.01 degrees.
double curvature_coefficient(const HorizonParams& params, double max_distance, double earth_radius);

}  // namespace skyview::detail
