#pragma once
// The picture of a shadow method's differences from exact shadow rays, like the hybrid shadow maps
// paper's figures: pixels where both agree in grey (light where sunlit, dark where in shadow), light
// leaking (the method sunlit, the rays in shadow) in red, acne (the method in shadow, the rays
// sunlit) in blue, and the sky white. Sunlit means visibility >= 0.5, as in shadow_error.h.
#include <cstdint>
#include <span>
#include <vector>

namespace skyview {

inline constexpr std::uint8_t kDiffSunlit[3] = {200, 200, 200}, kDiffShadow[3] = {110, 110, 110},
                              kDiffLeak[3] = {230, 30, 30}, kDiffAcne[3] = {30, 80, 240}, kDiffSky[3] = {255, 255, 255};

// RGB, 3 bytes per pixel, in the pixels' order; NaN in either input is sky. Throws skyview::Error
// when the two differ in size.
std::vector<std::uint8_t> shadow_difference_picture(std::span<const float> method, std::span<const float> exact);

}  // namespace skyview
