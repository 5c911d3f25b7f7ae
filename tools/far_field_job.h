#pragma once
// A tiled `skyview svf` at unlimited radius (docs/tiling.md): the near field exact within a halo
// of H metres (the method at --radius H), the far field beyond it from an overview pyramid of the
// whole raster, H chosen from --max-error (or a default bound) by the far field's error bound.
#include <string>

#include "tiled_job.h"

namespace skyview::cli {

// The far field's default bound on the svf error, where --max-error does not set one.
constexpr double kDefaultFarFieldError = 0.01;

// Builds the pyramid (one read of the raster by strips; or reads it: far_field_pyramid.h),
// chooses H and sets the job's engine to the same method at --radius H with the curvature the
// whole raster's reach gives; records the choice in the job's metadata (FAR_FIELD_*).
// `max_error` < 0: kDefaultFarFieldError.
void prepare_far_field(HorizonJob& job, double max_error);

// --far-field-error of svf, horizon and exposure (TileRequest::far_error); `asked_by` names the
// other option that sets it where this one is not given ("--max-error, else "), or nothing.
void add_far_field_option(CLI::App& app, TileRequest& tiling, const std::string& asked_by);

// Throws UsageError for --far-field-error given to a run without a far field (not tiled, or a radius).
void check_far_field_option(const CLI::App& app, const HorizonJob& job);

// The far field on a command's summary line: ", far field beyond 630 m with svf error at most 0.0086
// and horizon angles within 1.2 degrees"; empty without one.
std::string far_field_summary(const HorizonJob& job);

}  // namespace skyview::cli
