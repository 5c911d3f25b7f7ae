#pragma once
// A PNG picture of an exposure map in the style of Figure 2 of the solar-exposure paper: the
// diffuse band on top and the direct band below, each with its own colour scale (kWh m⁻² sr⁻¹).
#include <optional>
#include <string>
#include <utility>

#include "skyview/sky/exposure_map.h"

namespace skyview {

// Both panels in the magma ramp (colour_ramp.h), from 0 to each band's top (below), or over
// `range` (Wh m-2 sr-1, --preview-range) so that two maps compare. Throws skyview::Error if
// `path` exists and !overwrite, or if writing fails. Written atomically.
void write_exposure_preview(const std::string& path, const ExposureMap& map, bool overwrite,
                            std::optional<std::pair<double, double>> range = std::nullopt);

}  // namespace skyview
