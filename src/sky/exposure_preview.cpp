// Exposure-map preview: two colour-mapped panels with scale bars, drawn with OpenCV (opencv_png.h
// writes them).
#include "skyview/sky/exposure_preview.h"

#include <algorithm>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "preview/opencv_png.h"
#include "skyview/preview/colour_ramp.h"
#include "skyview/raster/raster_io.h"

namespace skyview {
namespace {

constexpr int kBar = 24, kLabel = 110, kMargin = 8, kTitle = 22;

// Upper end of the colour scale: the maximum for the smooth diffuse band; for the direct band a
// high percentile of the lit cells, so the solstice edges of the sun band show rather than a few
// cells where the sun dwelt longest.
double scale_top(const std::vector<float>& v, bool robust) {
  std::vector<float> lit;
  for (float x : v) {
    if (x > 0.0f) lit.push_back(x);
  }
  if (lit.empty()) return 1.0;
  if (!robust) return *std::max_element(lit.begin(), lit.end());
  const std::size_t k = static_cast<std::size_t>(0.995 * (lit.size() - 1));
  std::nth_element(lit.begin(), lit.begin() + k, lit.end());
  return lit[k];
}

cv::Vec3b bgr(double t) {
  const auto c = ramp_colour(ColourRamp::magma, t);
  return {c[2], c[1], c[0]};
}

void draw_panel(cv::Mat& canvas, int top, const ExposureMap& map, ExposureBand band, const char* title,
                const std::optional<std::pair<double, double>>& range) {
  const auto& v = map.band(band);
  const double lo = range ? range->first : 0.0;
  const double hi = range ? range->second : scale_top(v, band == ExposureBand::direct);
  const double span = hi > lo ? hi - lo : 1.0;
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      canvas.at<cv::Vec3b>(top + kTitle + y, kMargin + x) =
          bgr((v[static_cast<std::size_t>(y) * map.width() + x] - lo) / span);
    }
  }
  const cv::Scalar ink(0, 0, 0);
  cv::putText(canvas, title, {kMargin, top + kTitle - 6}, cv::FONT_HERSHEY_SIMPLEX, 0.5, ink, 1, cv::LINE_AA);
  // Colour bar with its end values, in kWh m-2 sr-1.
  const int bx = kMargin * 2 + map.width();
  for (int y = 0; y < map.height(); ++y) {
    const cv::Vec3b c = bgr(1.0 - static_cast<double>(y) / std::max(map.height() - 1, 1));
    cv::line(canvas, {bx, top + kTitle + y}, {bx + kBar, top + kTitle + y}, cv::Scalar(c[0], c[1], c[2]));
  }
  char text[64];
  std::snprintf(text, sizeof text, "%.4g", hi / 1000.0);
  cv::putText(canvas, text, {bx + kBar + 4, top + kTitle + 12}, cv::FONT_HERSHEY_SIMPLEX, 0.4, ink, 1, cv::LINE_AA);
  std::snprintf(text, sizeof text, "%.4g", lo / 1000.0);
  cv::putText(canvas, text, {bx + kBar + 4, top + kTitle + map.height()}, cv::FONT_HERSHEY_SIMPLEX, 0.4, ink, 1,
              cv::LINE_AA);
  cv::putText(canvas, "kWh/m2/sr", {bx + kBar + 4, top + kTitle + map.height() / 2}, cv::FONT_HERSHEY_SIMPLEX, 0.4, ink,
              1, cv::LINE_AA);
}

}  // namespace

void write_exposure_preview(const std::string& path, const ExposureMap& map, bool overwrite,
                            std::optional<std::pair<double, double>> range) {
  check_output_writable(path, overwrite);
  const int panel = kTitle + map.height() + kMargin;
  cv::Mat canvas(2 * panel + kMargin, map.width() + 3 * kMargin + kBar + kLabel, CV_8UC3, cv::Scalar(255, 255, 255));
  draw_panel(canvas, kMargin, map, ExposureBand::diffuse, "diffuse (zenith top, N-E-S-W-N left to right)", range);
  draw_panel(canvas, kMargin + panel, map, ExposureBand::direct, "direct (sun splatted over its disc)", range);
  detail::write_bgr_png(path, canvas, overwrite);
}

}  // namespace skyview
