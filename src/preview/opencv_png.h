#pragma once
// Pictures drawn with OpenCV, whose colour images are BGR, written as PNG by write_png (RGB, through
// GDAL's PNG driver: OpenCV's own codecs would bring 15 more shared libraries to every run's start).
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

#include "skyview/raster/raster_io.h"

namespace skyview::detail {

inline void write_bgr_png(const std::string& path, const cv::Mat& bgr, bool overwrite) {
  cv::Mat rgb;
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  write_png(path, rgb.cols, rgb.rows, 3, rgb.ptr<std::uint8_t>(0), overwrite);
}

}  // namespace skyview::detail
