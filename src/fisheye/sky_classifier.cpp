// Sky classification of fish-eye images: an existing mask, or Otsu's threshold over the pixels
// inside the image circle (OpenCV's Otsu on the circle's histogram).
#include "skyview/fisheye/sky_classifier.h"

#include <opencv2/imgproc.hpp>

#include <cmath>

#include "skyview/core/error.h"

namespace skyview {

SkyClassification classify_sky(const FisheyeImage& im, const ImageCircle& circle, SkyThreshold method) {
  const int w = im.width, h = im.height;
  const std::size_t n = static_cast<std::size_t>(w) * h;
  SkyClassification out;
  out.sky.assign(n, 0);
  auto inside = [&](int x, int y) { return std::hypot(x - circle.cx, y - circle.cy) <= circle.radius; };
  if (method == SkyThreshold::mask) {
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const std::uint8_t* p = im.pixels.data() + (static_cast<std::size_t>(y) * w + x) * im.channels;
        bool any = false;
        for (int c = 0; c < im.channels; ++c) any = any || p[c] != 0;
        out.sky[static_cast<std::size_t>(y) * w + x] = any && inside(x, y) ? 255 : 0;
      }
    }
    return out;
  }
  if (im.channels < 3) throw Error("a one-band image is a mask: classify it with --mask, not --threshold");
  // The feature as 8-bit values of the pixels inside the circle, in one row for OpenCV's Otsu.
  std::vector<std::uint8_t> feature(n, 0), inner;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * w + x;
      const std::uint8_t* p = im.pixels.data() + i * 3;
      const double sum = double(p[0]) + p[1] + p[2];
      feature[i] = method == SkyThreshold::otsu
                       ? p[2]
                       : static_cast<std::uint8_t>(std::lround(sum > 0 ? 255.0 * p[2] / sum : 0));
      if (inside(x, y)) inner.push_back(feature[i]);
    }
  }
  if (inner.empty()) throw Error("the image circle holds no pixel");
  cv::Mat row(1, static_cast<int>(inner.size()), CV_8UC1, inner.data()), binary;
  const double t = cv::threshold(row, binary, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU);
  out.threshold = method == SkyThreshold::otsu ? t : t / 255.0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * w + x;
      out.sky[i] = feature[i] > t && inside(x, y) ? 255 : 0;
    }
  }
  return out;
}

}  // namespace skyview
