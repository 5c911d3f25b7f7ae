#pragma once
// The colour ramps of the previews and which one suits a quantity (docs/previews.md).
#include <array>
#include <cstdint>
#include <string>

namespace skyview {

// Perceptually uniform ramps: sequential for quantities (viridis, cividis, magma), diverging for
// differences (a blue-white-red centred on zero), grey for masks.
enum class ColourRamp { viridis, cividis, magma, diverging, grey };

// The colour at `t` in [0, 1] along `ramp` (clamped), as 8-bit red, green, blue.
std::array<std::uint8_t, 3> ramp_colour(ColourRamp ramp, double t);

// The ramp's name as docs/previews.md gives it ("viridis").
const char* ramp_name(ColourRamp ramp);

// The ramp suited to a band, from its name and unit: viridis for sky-view factors and other
// fractions, cividis for angles in degrees (horizons, openness), magma for heights and energies,
// diverging for differences (names ending in "_difference" or "_error"), grey for 0/1 masks.
ColourRamp ramp_for_band(const std::string& band, const std::string& unit);

}  // namespace skyview
