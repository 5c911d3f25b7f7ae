#include "map_furniture.h"

#include <cpl_string.h>
#include <ogr_spatialref.h>

#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>

namespace skyview::detail {
namespace {

const cv::Scalar kInk(0, 0, 0, 255), kPaper(255, 255, 255, 255);

}  // namespace

std::optional<double> metres_per_pixel(const GeoReference& georef, double cells_per_pixel) {
  if (!georef.has_geotransform) return std::nullopt;
  double metres_per_unit = 1.0;  // no CRS: skyview takes the units for metres (and says so on reading)
  if (!georef.crs_wkt.empty()) {
    OGRSpatialReference crs;
    if (crs.importFromWkt(georef.crs_wkt.c_str()) != OGRERR_NONE || crs.IsGeographic()) return std::nullopt;
    metres_per_unit = crs.GetLinearUnits();
  }
  const auto& g = georef.geotransform;
  const double cell = std::hypot(g[1], g[4]) * metres_per_unit;
  if (!(cell > 0.0) || !std::isfinite(cell)) return std::nullopt;
  return cell * cells_per_pixel;
}

int draw_scale_bar(cv::Mat& rgba, cv::Point origin, double metres_per_pixel, int max_pixels) {
  const double most = metres_per_pixel * max_pixels;
  double length = std::pow(10.0, std::floor(std::log10(most)));
  for (double step : {5.0, 2.0}) {
    if (length * step <= most) {
      length *= step;
      break;
    }
  }
  const int pixels = std::max(1, static_cast<int>(std::lround(length / metres_per_pixel)));
  const int h = 6, half = pixels / 2;
  // Two halves, black and white, as on printed maps.
  cv::rectangle(rgba, {origin.x, origin.y}, {origin.x + half, origin.y + h}, kInk, cv::FILLED);
  cv::rectangle(rgba, {origin.x + half, origin.y}, {origin.x + pixels, origin.y + h}, kPaper, cv::FILLED);
  cv::rectangle(rgba, {origin.x, origin.y}, {origin.x + pixels, origin.y + h}, kInk, 1);
  char text[32];
  if (length >= 1000.0)
    std::snprintf(text, sizeof text, "%g km", length / 1000.0);
  else if (length >= 1.0)
    std::snprintf(text, sizeof text, "%g m", length);
  else
    std::snprintf(text, sizeof text, "%g cm", length * 100.0);
  const double scale = 0.42;
  cv::putText(rgba, "0", {origin.x - 3, origin.y + h + 15}, cv::FONT_HERSHEY_SIMPLEX, scale, kInk, 1, cv::LINE_AA);
  int base = 0;
  const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &base);
  cv::putText(rgba, text, {origin.x + pixels - size.width / 2, origin.y + h + 15}, cv::FONT_HERSHEY_SIMPLEX, scale,
              kInk, 1, cv::LINE_AA);
  return pixels;
}

void draw_north_arrow(cv::Mat& rgba, cv::Point centre, int length, const GeoReference& georef) {
  // The pixel step that moves towards +y: the geotransform's 2x2 part inverted, applied to (0, 1).
  const auto& g = georef.geotransform;
  const double det = g[1] * g[5] - g[2] * g[4];
  double dx = -g[2] / det, dy = g[1] / det;
  const double n = std::hypot(dx, dy);
  if (!(n > 0.0) || !std::isfinite(n)) return;
  dx /= n;
  dy /= n;
  const double half = length / 2.0;
  const cv::Point2d tip(centre.x + dx * half, centre.y + dy * half), tail(centre.x - dx * half, centre.y - dy * half);
  // A filled head with a notch: the left half black, the right half outlined.
  const cv::Point2d side(-dy, dx);
  const double w = length * 0.22;
  const cv::Point2d back = tail + (tip - tail) * 0.25;
  const cv::Point left(cv::Point2d(tail) + side * w), right(cv::Point2d(tail) - side * w);
  const std::vector<cv::Point> dark{cv::Point(tip), left, cv::Point(back)};
  const std::vector<cv::Point> light{cv::Point(tip), right, cv::Point(back)};
  cv::fillConvexPoly(rgba, dark, kInk, cv::LINE_AA);
  cv::fillConvexPoly(rgba, light, kPaper, cv::LINE_AA);
  cv::polylines(rgba, std::vector<std::vector<cv::Point>>{{cv::Point(tip), left, cv::Point(back), right}}, true, kInk,
                1, cv::LINE_AA);
  const cv::Point label(static_cast<int>(tip.x + dx * 12 - 5), static_cast<int>(tip.y + dy * 12 + 5));
  cv::putText(rgba, "N", label, cv::FONT_HERSHEY_SIMPLEX, 0.5, kInk, 1, cv::LINE_AA);
}

std::string world_file_text(const GeoReference& georef, double col0, double row0, double cells_per_pixel) {
  const auto& g = georef.geotransform;
  const double a = g[1] * cells_per_pixel, b = g[2] * cells_per_pixel;
  const double d = g[4] * cells_per_pixel, e = g[5] * cells_per_pixel;
  // A world file names the centre of the top-left pixel.
  const double c = g[0] + col0 * g[1] + row0 * g[2] + 0.5 * (a + b);
  const double f = g[3] + col0 * g[4] + row0 * g[5] + 0.5 * (d + e);
  char text[512];
  std::snprintf(text, sizeof text, "%.17g\n%.17g\n%.17g\n%.17g\n%.17g\n%.17g\n", a, d, b, e, c, f);
  return text;
}

std::string pam_text(const std::string& crs_wkt, const std::vector<std::pair<std::string, std::string>>& items) {
  const auto xml = [](const std::string& s) {
    char* escaped = CPLEscapeString(s.c_str(), -1, CPLES_XML);
    std::string out(escaped);
    CPLFree(escaped);
    return out;
  };
  std::string text = "<PAMDataset>\n";
  if (!crs_wkt.empty()) text += "  <SRS>" + xml(crs_wkt) + "</SRS>\n";
  text += "  <Metadata>\n";
  for (const auto& [key, value] : items) text += "    <MDI key=\"" + xml(key) + "\">" + xml(value) + "</MDI>\n";
  text += "  </Metadata>\n</PAMDataset>\n";
  return text;
}

}  // namespace skyview::detail
