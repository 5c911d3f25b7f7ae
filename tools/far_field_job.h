#pragma once
// A tiled `skyview svf` at unlimited radius (docs/tiling.md): the near field exact within a halo
// of H metres (the method at --radius H), the far field beyond it from an overview pyramid of the
// whole raster, H chosen from --max-error (or a default bound) by the far field's error bound.
#include "tiled_job.h"

namespace skyview::cli {

// The far field's default bound on the svf error, where --max-error does not set one.
constexpr double kDefaultFarFieldError = 0.01;

// Builds the pyramid (one read of the raster by strips; or reads it: far_field_pyramid.h),
// chooses H and sets the job's engine to the same method at --radius H with the curvature the
// whole raster's reach gives; records the choice in the job's metadata (FAR_FIELD_*).
// `max_error` < 0: kDefaultFarFieldError.
void prepare_far_field(HorizonJob& job, double max_error);

}  // namespace skyview::cli
