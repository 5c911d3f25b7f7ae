// The fish-eye picture of an observer's hemisphere: per pixel, its direction through the projection,
// sky where its elevation is above the horizon of its sector, otherwise the first terrain its ray
// meets (the march's rising steps give that distance), shaded by distance.
#include "skyview/fisheye/fisheye_view.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "fisheye/sector_lookup.h"
#include "skyview/core/error.h"
#include "skyview/sky/sky_colour.h"

namespace skyview {
namespace {

// A plain clear sky: deep blue at the zenith to pale at the horizon (no sun position given).
cv::Vec3b plain_sky(double zenith) {
  const double f = std::pow(zenith / (M_PI / 2), 1.5);
  return {static_cast<std::uint8_t>(60 + f * 140), static_cast<std::uint8_t>(120 + f * 100),
          static_cast<std::uint8_t>(205 + f * 40)};
}

// Terrain and buildings: dark near, lighter and bluer with distance (aerial perspective), so that
// walls a street apart stand out from the hills behind them.
cv::Vec3b obstacle(double distance) {
  const double far = 1.0 - std::exp(-distance / 250.0);
  const double near = 1.0 - std::exp(-distance / 25.0);
  const double g = 55 + 70 * near + 60 * far;
  return {static_cast<std::uint8_t>(g * 0.95), static_cast<std::uint8_t>(g * 0.97),
          static_cast<std::uint8_t>(std::min(255.0, g + 35 * far))};
}

void put_text(cv::Mat& image, const std::string& text, cv::Point at, double scale, bool centred = false) {
  const int font = cv::FONT_HERSHEY_SIMPLEX;
  const int thick = std::max(1, static_cast<int>(std::lround(scale * 2)));
  int base = 0;
  const cv::Size s = cv::getTextSize(text, font, scale, thick, &base);
  if (centred) at = {at.x - s.width / 2, at.y + s.height / 2};
  cv::putText(image, text, at, font, scale, cv::Scalar(0, 0, 0), thick + 2, cv::LINE_AA);
  cv::putText(image, text, at, font, scale, cv::Scalar(255, 255, 255), thick, cv::LINE_AA);
}

}  // namespace

FisheyeView fisheye_view(const Terrain& terrain, const Observer& observer, const FisheyeViewOptions& o) {
  if (o.size < 64 || o.size > 8192) throw Error("--size must be within 64 .. 8192 pixels");
  PointHorizonOptions h = o.horizons;
  if (h.method != "march") throw Error("the fish-eye view needs the march's distances: --method march");
  h.rising_steps = true;
  int n = o.directions;
  if (n == 0) {
    n = 64;
    while (n < M_PI * o.size) n *= 2;
  }
  h.params.directions = n;
  FisheyeView v;
  v.size = o.size;
  v.horizons = point_horizons(terrain, {observer}, h);
  v.problem = v.horizons.problem[0];
  if (!v.problem.empty()) return v;
  const double rotation = v.horizons.sector_rotation;
  v.values = point_sky_view(terrain, observer, v.horizons.of(0), n, rotation);
  v.frame = {(o.size - 1) / 2.0, (o.size - 1) / 2.0, o.size / 2.0, o.projection, o.mirror};
  std::optional<SkyColour> sky;
  if (o.sun) sky.emplace(o.sun->turbidity, o.sun->zenith, o.sun->azimuth);
  const int size = o.size;
  v.rgb.assign(static_cast<std::size_t>(size) * size * 3, 0);
  v.mask.assign(static_cast<std::size_t>(size) * size, 0);
  cv::Mat image(size, size, CV_8UC3, v.rgb.data());
  const float* up = v.horizons.of(0);
  const auto& rising = v.horizons.rising[0];
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      double zenith, azimuth;
      if (!v.frame.direction(x, y, zenith, azimuth)) continue;
      const double elevation = M_PI / 2 - zenith;
      const int k = detail::sector_of(azimuth, rotation, n);
      cv::Vec3b& px = image.at<cv::Vec3b>(y, x);
      if (elevation > up[k]) {
        v.mask[static_cast<std::size_t>(y) * size + x] = 255;
        if (sky) {
          const Srgb8 c = sky->display(zenith, azimuth);
          px = {c.r, c.g, c.b};
        } else {
          px = plain_sky(zenith);
        }
        continue;
      }
      // The first terrain the ray meets: the first step of the steepest slope at or above its own.
      const std::vector<RisingStep>& steps = rising[static_cast<std::size_t>(k)];
      const float t = static_cast<float>(std::tan(elevation));
      const auto hit = std::lower_bound(steps.begin(), steps.end(), t,
                                        [](const RisingStep& s, float slope) { return s.slope < slope; });
      px = obstacle(hit != steps.end() ? hit->distance : (steps.empty() ? 0.0f : steps.back().distance));
    }
  }
  if (!o.annotate) return v;
  const double scale = size / 1024.0;
  const int thick = std::max(1, static_cast<int>(std::lround(2 * scale)));
  // The horizon line: each sector's horizon at its centre azimuth.
  std::vector<cv::Point> line;
  for (int k = 0; k < n; ++k) {
    double px, py;
    v.frame.pixel(M_PI / 2 - std::max(0.0, static_cast<double>(up[k])), rotation + sector_azimuth(k, n), px, py);
    line.emplace_back(static_cast<int>(std::lround(px)), static_cast<int>(std::lround(py)));
  }
  cv::polylines(image, line, true, cv::Scalar(240, 70, 30), thick, cv::LINE_AA);
  if (o.sun && o.sun->zenith < M_PI / 2) {
    double sx, sy;
    v.frame.pixel(o.sun->zenith, o.sun->azimuth, sx, sy);
    const int k = detail::sector_of(o.sun->azimuth, rotation, n);
    const bool seen = M_PI / 2 - o.sun->zenith > up[k];
    cv::circle(image, {static_cast<int>(std::lround(sx)), static_cast<int>(std::lround(sy))},
               std::max(3, static_cast<int>(10 * scale)), cv::Scalar(255, 250, 215), seen ? cv::FILLED : thick,
               cv::LINE_AA);
  }
  const double r = v.frame.radius - 24 * scale;
  const char* letters[] = {"N", "E", "S", "W"};
  for (int i = 0; i < 4; ++i) {
    double px, py;
    v.frame.pixel(M_PI / 2 * (r / v.frame.radius), i * M_PI / 2, px, py);
    if (o.projection != Projection::equidistant) {  // letters just inside the rim, whatever the projection
      const double a = i * M_PI / 2;
      px = v.frame.cx + (o.mirror ? 1 : -1) * r * std::sin(a);
      py = v.frame.cy - r * std::cos(a);
    }
    put_text(image, letters[i], {static_cast<int>(px), static_cast<int>(py)}, 0.9 * scale, true);
  }
  char text[96];
  std::snprintf(text, sizeof text, "svf %.3f", v.values.svf);
  put_text(image, text, {static_cast<int>(12 * scale), static_cast<int>(40 * scale)}, 1.1 * scale);
  std::snprintf(text, sizeof text, "%s, %.2f m above ground", projection_name(o.projection), observer.height);
  put_text(image, text, {static_cast<int>(12 * scale), size - static_cast<int>(16 * scale)}, 0.6 * scale);
  return v;
}

}  // namespace skyview
