// Polar horizon plots, one panel per observer, as an upward-looking equidistant fish-eye.
#include "skyview/fisheye/horizon_plot.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "fisheye/sector_lookup.h"
#include "skyview/core/error.h"
#include "skyview/fisheye/projection.h"
#include "skyview/horizon/direction_set.h"
#include "skyview/raster/raster_io.h"

namespace skyview {
namespace {

constexpr int kPanel = 320, kLabel = 44, kColumns = 4;

void text(cv::Mat& m, const std::string& s, cv::Point at, double scale, bool centred) {
  int base = 0;
  const cv::Size size = cv::getTextSize(s, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &base);
  if (centred) at = {at.x - size.width / 2, at.y + size.height / 2};
  cv::putText(m, s, at, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(30, 30, 30), 1, cv::LINE_AA);
}

void draw_panel(cv::Mat panel, const HorizonPlot& p) {
  const FisheyeFrame frame{kPanel / 2.0, kPanel / 2.0, kPanel / 2.0 - 22, Projection::equidistant, false};
  const int n = static_cast<int>(p.horizons.size());
  for (int y = 0; y < kPanel; ++y) {
    for (int x = 0; x < kPanel; ++x) {
      double zenith, azimuth;
      if (!frame.direction(x, y, zenith, azimuth)) continue;
      cv::Vec3b& px = panel.at<cv::Vec3b>(y, x);
      if (n == 0) {
        px = {225, 225, 225};
        continue;
      }
      const int k = detail::sector_of(azimuth, p.rotation, n);
      px = M_PI / 2 - zenith > p.horizons[static_cast<std::size_t>(k)] ? cv::Vec3b(205, 228, 250)
                                                                       : cv::Vec3b(120, 120, 120);
    }
  }
  const cv::Point c(kPanel / 2, kPanel / 2);
  for (double ring : {30.0, 60.0, 90.0}) {
    cv::circle(panel, c, static_cast<int>(std::lround(frame.radius * ring / 90.0)), cv::Scalar(90, 90, 90), 1,
               cv::LINE_AA);
  }
  if (n > 0) {
    std::vector<cv::Point> line;
    for (int k = 0; k < n; ++k) {
      double px, py;
      frame.pixel(M_PI / 2 - std::max(0.0, double(p.horizons[static_cast<std::size_t>(k)])),
                  p.rotation + sector_azimuth(k, n), px, py);
      line.emplace_back(static_cast<int>(std::lround(px)), static_cast<int>(std::lround(py)));
    }
    cv::polylines(panel, line, true, cv::Scalar(220, 50, 30), 2, cv::LINE_AA);
  }
  const char* letters[] = {"N", "E", "S", "W"};
  for (int i = 0; i < 4; ++i) {
    const double a = i * M_PI / 2, r = frame.radius + 11;
    text(panel, letters[i], {static_cast<int>(c.x - r * std::sin(a)), static_cast<int>(c.y - r * std::cos(a))}, 0.45,
         true);
  }
  char line[160];
  if (std::isnan(p.svf))
    std::snprintf(line, sizeof line, "%s: no values", p.label.c_str());
  else
    std::snprintf(line, sizeof line, "%s: svf %.3f", p.label.c_str(), p.svf);
  text(panel, line, {kPanel / 2, kPanel + kLabel / 2 - 4}, 0.55, true);
}

}  // namespace

void write_horizon_plots(const std::string& path, const std::vector<HorizonPlot>& plots, bool overwrite) {
  if (plots.empty()) throw Error("no horizons to plot");
  if (plots.size() > kMaxHorizonPlots)
    throw Error("at most " + std::to_string(kMaxHorizonPlots) + " horizon plots fit one picture");
  const int count = static_cast<int>(plots.size());
  const int cols = std::min(count, kColumns), rows = (count + kColumns - 1) / kColumns;
  const int w = cols * kPanel, h = rows * (kPanel + kLabel);
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(w) * h * 3, 255);
  cv::Mat image(h, w, CV_8UC3, rgb.data());
  for (int i = 0; i < count; ++i) {
    const cv::Rect cell((i % kColumns) * kPanel, (i / kColumns) * (kPanel + kLabel), kPanel, kPanel + kLabel);
    draw_panel(image(cell), plots[static_cast<std::size_t>(i)]);
  }
  write_png(path, w, h, 3, rgb.data(), overwrite);
}

}  // namespace skyview
