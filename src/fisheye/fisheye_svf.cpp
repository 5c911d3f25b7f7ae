#include "skyview/fisheye/fisheye_svf.h"

#include <opencv2/imgproc.hpp>

#include <cmath>

#include "skyview/core/error.h"
#include "skyview/core/number_text.h"
#include "skyview/raster/raster_io.h"

namespace skyview {

FisheyeSvfResult fisheye_svf(const FisheyeImage& image, const FisheyeSvfOptions& o) {
  if (!(o.field_of_view >= 180.0 && o.field_of_view <= 360.0))
    throw Error("--fov must be within 180 .. 360 degrees: a narrower lens does not see the whole sky");
  const double edge_zenith = o.field_of_view / 2 * M_PI / 180.0;
  const double edge_r = projection_radius(o.projection, edge_zenith);
  if (!(edge_r > 0) || !std::isfinite(edge_r) || (o.projection == Projection::orthographic && o.field_of_view > 180.0))
    throw Error(std::string("the ") + projection_name(o.projection) + " projection cannot show " +
                number_text(o.field_of_view) + " degrees");
  if (image.channels == 1 && o.threshold != SkyThreshold::mask)
    throw Error("a one-band image is a mask: read it with --mask (photographs have three bands)");
  FisheyeSvfResult r;
  if (o.circle) {
    r.circle = *o.circle;
    if (!(r.circle.radius > 0) || r.circle.cx < 0 || r.circle.cy < 0 || r.circle.cx > image.width - 1 ||
        r.circle.cy > image.height - 1)
      throw Error("the given circle's centre must lie in the image and its radius be above 0");
  } else if (o.threshold == SkyThreshold::mask) {
    r.circle = inscribed_circle(image.width, image.height);
  } else {
    r.circle = find_image_circle(image);
    r.circle_found = true;
  }
  r.frame = {r.circle.cx, r.circle.cy, r.circle.radius / edge_r, o.projection, false};
  // Classify within the 90° circle only: below the horizon a wide lens sees the ground.
  ImageCircle sky_circle = r.circle;
  sky_circle.radius = r.frame.radius;
  r.classification = classify_sky(image, sky_circle, o.threshold);
  r.fractions = sky_fractions(r.classification.sky, image.width, image.height, r.frame, o.rings);
  return r;
}

void write_classified_png(const std::string& path, const FisheyeImage& image, const FisheyeSvfResult& r,
                          bool overwrite) {
  const int w = image.width, h = image.height;
  cv::Mat photo(h, w, image.channels == 3 ? CV_8UC3 : CV_8UC1, const_cast<std::uint8_t*>(image.pixels.data()));
  cv::Mat colour;
  if (image.channels == 3)
    colour = photo.clone();
  else
    cv::cvtColor(photo, colour, cv::COLOR_GRAY2RGB);
  cv::Mat classes(h, w, CV_8UC3, cv::Scalar(0, 0, 0));
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      double zenith, azimuth;
      if (!r.frame.direction(x, y, zenith, azimuth)) continue;
      const bool sky = r.classification.sky[static_cast<std::size_t>(y) * w + x] != 0;
      classes.at<cv::Vec3b>(y, x) = sky ? cv::Vec3b(255, 255, 255) : cv::Vec3b(60, 60, 60);
    }
  }
  const int thick = std::max(2, h / 300);
  const cv::Point c(static_cast<int>(std::lround(r.frame.cx)), static_cast<int>(std::lround(r.frame.cy)));
  for (cv::Mat* m : {&colour, &classes})
    cv::circle(*m, c, static_cast<int>(std::lround(r.frame.radius)), cv::Scalar(230, 40, 40), thick, cv::LINE_AA);
  cv::Mat both;
  cv::hconcat(colour, classes, both);
  const double scale = std::min(1.0, 640.0 / h);
  cv::Mat small;
  cv::resize(both, small, cv::Size(), scale, scale, cv::INTER_AREA);
  char text[96];
  std::snprintf(text, sizeof text, "svf %.3f  (annulus %.3f)", r.fractions.svf, r.fractions.svf_annulus);
  cv::putText(small, text, {10, 28}, cv::FONT_HERSHEY_SIMPLEX, 0.8, cv::Scalar(0, 0, 0), 4, cv::LINE_AA);
  cv::putText(small, text, {10, 28}, cv::FONT_HERSHEY_SIMPLEX, 0.8, cv::Scalar(255, 255, 255), 2, cv::LINE_AA);
  write_png(path, small.cols, small.rows, 3, small.ptr<std::uint8_t>(), overwrite);
}

}  // namespace skyview
