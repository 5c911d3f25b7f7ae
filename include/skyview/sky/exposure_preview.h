#pragma once
// A PNG picture of an exposure map in the style of Figure 2 of the solar-exposure paper: the
// diffuse band on top and the direct band below, each with its own colour scale (kWh m⁻² sr⁻¹).
#include <string>

#include "skyview/sky/exposure_map.h"

namespace skyview {

// Throws skyview::Error if `path` exists and !overwrite, or if writing fails. Written atomically.
void write_exposure_preview(const std::string& path, const ExposureMap& map, bool overwrite);

}  // namespace skyview
