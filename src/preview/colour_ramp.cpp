#include "skyview/preview/colour_ramp.h"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace skyview {
namespace {

// The sequential ramps are OpenCV's copies of matplotlib's tables (256 entries each).
struct RampTable {
  std::array<std::array<std::uint8_t, 3>, 256> rgb;
  explicit RampTable(int opencv_map) {
    cv::Mat levels(1, 256, CV_8UC1);
    for (int i = 0; i < 256; ++i) levels.at<std::uint8_t>(0, i) = static_cast<std::uint8_t>(i);
    cv::Mat bgr;
    cv::applyColorMap(levels, bgr, opencv_map);
    for (int i = 0; i < 256; ++i) {
      const cv::Vec3b c = bgr.at<cv::Vec3b>(0, i);
      rgb[static_cast<std::size_t>(i)] = {c[2], c[1], c[0]};
    }
  }
};

// ColorBrewer's RdBu with 11 classes, blue (low) to red (high), interpolated linearly: white
// sits at the middle, where a difference is zero.
constexpr std::array<std::array<double, 3>, 11> kDiverging{{{5, 48, 97},
                                                            {33, 102, 172},
                                                            {67, 147, 195},
                                                            {146, 197, 222},
                                                            {209, 229, 240},
                                                            {247, 247, 247},
                                                            {253, 219, 199},
                                                            {244, 165, 130},
                                                            {214, 96, 77},
                                                            {178, 24, 43},
                                                            {103, 0, 31}}};

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

}  // namespace

std::array<std::uint8_t, 3> ramp_colour(ColourRamp ramp, double t) {
  t = std::isnan(t) ? 0.0 : std::clamp(t, 0.0, 1.0);
  switch (ramp) {
    case ColourRamp::grey: {
      const auto g = static_cast<std::uint8_t>(std::lround(255.0 * t));
      return {g, g, g};
    }
    case ColourRamp::diverging: {
      const double x = t * (kDiverging.size() - 1);
      const std::size_t i = std::min(static_cast<std::size_t>(x), kDiverging.size() - 2);
      const double f = x - static_cast<double>(i);
      std::array<std::uint8_t, 3> c{};
      for (int k = 0; k < 3; ++k)
        c[k] = static_cast<std::uint8_t>(std::lround(kDiverging[i][k] * (1 - f) + kDiverging[i + 1][k] * f));
      return c;
    }
    default:
      break;
  }
  static const RampTable viridis(cv::COLORMAP_VIRIDIS), cividis(cv::COLORMAP_CIVIDIS), magma(cv::COLORMAP_MAGMA);
  const RampTable& table = ramp == ColourRamp::viridis ? viridis : ramp == ColourRamp::cividis ? cividis : magma;
  return table.rgb[static_cast<std::size_t>(std::lround(255.0 * t))];
}

const char* ramp_name(ColourRamp ramp) {
  switch (ramp) {
    case ColourRamp::viridis:
      return "viridis";
    case ColourRamp::cividis:
      return "cividis";
    case ColourRamp::magma:
      return "magma";
    case ColourRamp::diverging:
      return "diverging";
    case ColourRamp::grey:
      return "grey";
  }
  return "viridis";
}

ColourRamp ramp_for_band(const std::string& band, const std::string& unit) {
  if (ends_with(band, "_difference") || ends_with(band, "_error") || band == "difference") return ColourRamp::diverging;
  if (band == "sunlit" || ends_with(band, "_mask")) return ColourRamp::grey;
  if (unit == "degree") return ColourRamp::cividis;
  if (unit == "metre" || unit == "m" || unit == "hours" || unit.rfind("kWh", 0) == 0 || unit.rfind("Wh", 0) == 0)
    return ColourRamp::magma;
  return ColourRamp::viridis;
}

}  // namespace skyview
