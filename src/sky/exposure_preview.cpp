// Exposure-map preview: two colour-mapped panels with scale bars, drawn with OpenCV (opencv_png.h
// writes them).
#include "skyview/sky/exposure_preview.h"

#include <algorithm>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "preview/opencv_png.h"
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

void draw_panel(cv::Mat& canvas, int top, const ExposureMap& map, ExposureBand band, const char* title) {
  const auto& v = map.band(band);
  const double hi = scale_top(v, band == ExposureBand::direct);
  cv::Mat grey(map.height(), map.width(), CV_8UC1);
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      grey.at<unsigned char>(y, x) =
          cv::saturate_cast<unsigned char>(255.0 * v[static_cast<std::size_t>(y) * map.width() + x] / hi);
    }
  }
  cv::Mat colour;
  cv::applyColorMap(grey, colour, cv::COLORMAP_JET);
  const cv::Scalar ink(0, 0, 0);
  cv::putText(canvas, title, {kMargin, top + kTitle - 6}, cv::FONT_HERSHEY_SIMPLEX, 0.5, ink, 1, cv::LINE_AA);
  colour.copyTo(canvas(cv::Rect(kMargin, top + kTitle, map.width(), map.height())));
  // Colour bar with its end values, in kWh m-2 sr-1.
  const int bx = kMargin * 2 + map.width();
  for (int y = 0; y < map.height(); ++y) {
    cv::Mat one(1, 1, CV_8UC1, cv::Scalar(255 - 255 * y / std::max(map.height() - 1, 1)));
    cv::Mat c;
    cv::applyColorMap(one, c, cv::COLORMAP_JET);
    cv::line(canvas, {bx, top + kTitle + y}, {bx + kBar, top + kTitle + y}, c.at<cv::Vec3b>(0, 0));
  }
  char text[64];
  std::snprintf(text, sizeof text, "%.4g", hi / 1000.0);
  cv::putText(canvas, text, {bx + kBar + 4, top + kTitle + 12}, cv::FONT_HERSHEY_SIMPLEX, 0.4, ink, 1, cv::LINE_AA);
  cv::putText(canvas, "0", {bx + kBar + 4, top + kTitle + map.height()}, cv::FONT_HERSHEY_SIMPLEX, 0.4, ink, 1,
              cv::LINE_AA);
  cv::putText(canvas, "kWh/m2/sr", {bx + kBar + 4, top + kTitle + map.height() / 2}, cv::FONT_HERSHEY_SIMPLEX, 0.4, ink,
              1, cv::LINE_AA);
}

}  // namespace

void write_exposure_preview(const std::string& path, const ExposureMap& map, bool overwrite) {
  check_output_writable(path, overwrite);
  const int panel = kTitle + map.height() + kMargin;
  cv::Mat canvas(2 * panel + kMargin, map.width() + 3 * kMargin + kBar + kLabel, CV_8UC3, cv::Scalar(255, 255, 255));
  draw_panel(canvas, kMargin, map, ExposureBand::diffuse, "diffuse (zenith top, N-E-S-W-N left to right)");
  draw_panel(canvas, kMargin + panel, map, ExposureBand::direct, "direct (sun splatted over its disc)");
  detail::write_bgr_png(path, canvas, overwrite);
}

}  // namespace skyview
