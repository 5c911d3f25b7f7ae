// One preview for every command's band: the map in its colour ramp, a title above, the legend
// beside it, the scale bar below and a north arrow (docs/previews.md shows the layout).
#include "skyview/preview/raster_preview.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "map_furniture.h"
#include "skyview/raster/output_checks.h"
#include "skyview/raster/output_files.h"

namespace skyview {
namespace {

// The map is drawn no larger than this on its longer side (cells averaged) and no smaller than
// kSmallest (each cell a square of whole pixels), so that a 50-cell test raster and a 20,000-cell city both read.
constexpr int kLargest = 1200, kSmallest = 420;
constexpr int kMargin = 12, kTitle = 30, kPanel = 170, kBarWidth = 20, kScaleStrip = 40;
const cv::Scalar kInk(0, 0, 0, 255), kPaper(255, 255, 255, 255);
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;

// Cells per pixel of the drawn map: an integer above 1 (averaged) or the inverse of one (repeated).
double cells_per_pixel(int width, int height) {
  const int longest = std::max(width, height);
  if (longest > kLargest) return std::ceil(static_cast<double>(longest) / kLargest);
  if (longest < kSmallest) return 1.0 / ((kSmallest + longest - 1) / longest);
  return 1.0;
}

// The values drawn per pixel: means of the valid cells of each block, or the cell under it.
cv::Mat display_values(const Grid<float>& values, double s) {
  const int w = values.width(), h = values.height();
  if (s >= 1.0) {
    const int f = static_cast<int>(s);
    const int dw = (w + f - 1) / f, dh = (h + f - 1) / f;
    cv::Mat out(dh, dw, CV_32FC1);
    for (int y = 0; y < dh; ++y) {
      for (int x = 0; x < dw; ++x) {
        double sum = 0;
        int n = 0;
        for (int r = y * f; r < std::min(h, (y + 1) * f); ++r) {
          for (int c = x * f; c < std::min(w, (x + 1) * f); ++c) {
            const float v = values(c, r);
            if (!std::isnan(v)) sum += v, ++n;
          }
        }
        out.at<float>(y, x) = n ? static_cast<float>(sum / n) : NAN;
      }
    }
    return out;
  }
  const int up = static_cast<int>(std::lround(1.0 / s));
  cv::Mat out(h * up, w * up, CV_32FC1);
  for (int y = 0; y < out.rows; ++y)
    for (int x = 0; x < out.cols; ++x) out.at<float>(y, x) = values(x / up, y / up);
  return out;
}

// Round values for the legend's ticks: a step of 1, 2 or 5 times a power of ten nearest a quarter
// of the range, and the multiples of it within [lo, hi].
std::vector<double> round_ticks(double lo, double hi, double& step) {
  const double raw = (hi - lo) / 4.0;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  step = power;
  for (double m : {2.0, 5.0, 10.0})
    if (std::fabs(m * power - raw) < std::fabs(step - raw)) step = m * power;
  std::vector<double> ticks;
  for (double k = std::ceil(lo / step - 1e-9); k * step <= hi + step * 1e-9; k += 1.0) ticks.push_back(k * step);
  return ticks;
}

// "0.96", "20", "1.5e+05": as many decimals as the step needs.
std::string tick_text(double v, double step) {
  char text[32];
  if (std::fabs(v) < step * 1e-6) v = 0.0;  // no "-0.00"
  const int digits = std::clamp(static_cast<int>(std::ceil(-std::log10(step) - 1e-9)), 0, 6);
  if (std::fabs(v) >= 1e6 || step < 1e-6)
    std::snprintf(text, sizeof text, "%.3g", v);
  else
    std::snprintf(text, sizeof text, "%.*f", digits, v);
  return text;
}

std::string unit_text(const std::string& unit) {
  if (unit.empty() || unit == "1") return "(no unit)";
  if (unit == "degree") return "degrees";
  if (unit == "metre") return "metres";
  return unit;
}

void put(cv::Mat& canvas, const std::string& text, cv::Point at, double scale = 0.45) {
  cv::putText(canvas, text, at, kFont, scale, kInk, 1, cv::LINE_AA);
}

// Shortened from the left until it fits `pixels`.
std::string fitted(std::string text, double scale, int pixels) {
  int base = 0;
  while (text.size() > 4 && cv::getTextSize(text, kFont, scale, 1, &base).width > pixels) text = "..." + text.substr(4);
  return text;
}

// The legend at `x`, `y`: band and unit, the ramp upright (high values at the top) with round
// ticks, then how its limits were chosen. Returns the y below it.
int draw_legend(cv::Mat& canvas, int x, int y, int bar_height, const PreviewSpec& spec, double lo, double hi) {
  const int room = canvas.cols - x - kMargin;
  put(canvas, fitted(spec.band, 0.5, room), {x, y + 14}, 0.5);
  put(canvas, fitted(unit_text(spec.unit), 0.42, room), {x, y + 32}, 0.42);
  const int top = y + 44;
  for (int i = 0; i < bar_height; ++i) {
    const auto c = ramp_colour(spec.ramp, 1.0 - static_cast<double>(i) / std::max(1, bar_height - 1));
    cv::line(canvas, {x, top + i}, {x + kBarWidth - 1, top + i}, cv::Scalar(c[0], c[1], c[2], 255));
  }
  cv::rectangle(canvas, {x, top}, {x + kBarWidth - 1, top + bar_height - 1}, kInk, 1);
  double step = 1.0;
  for (double v : round_ticks(lo, hi, step)) {
    const int ty = top + bar_height - 1 - static_cast<int>(std::lround((bar_height - 1) * (v - lo) / (hi - lo)));
    cv::line(canvas, {x + kBarWidth, ty}, {x + kBarWidth + 4, ty}, kInk, 1);
    put(canvas, tick_text(v, step), {x + kBarWidth + 8, ty + 5}, 0.42);
  }
  int below = top + bar_height + 18;
  put(canvas, spec.range ? "range as given" : "2nd-98th percentile", {x, below}, 0.4);
  put(canvas, std::string(ramp_name(spec.ramp)) + ", nodata clear", {x, below + 16}, 0.4);
  return below + 16;
}

}  // namespace

std::string world_file_path(const std::string& png_path) {
  return std::filesystem::path(png_path).replace_extension(".pgw").string();
}

void write_raster_preview(const std::string& path, const Grid<float>& values, const PreviewSpec& spec, bool overwrite) {
  const bool georeferenced = spec.georef.has_geotransform;
  const std::string world = world_file_path(path), pam = path + ".aux.xml";
  check_output_writable(path, overwrite);
  check_output_writable(pam, overwrite);
  if (georeferenced) check_output_writable(world, overwrite);
  const auto [lo, hi] = preview_range(values, spec);
  const double s = cells_per_pixel(values.width(), values.height());
  const cv::Mat shown = display_values(values, s);
  const std::optional<double> metres = detail::metres_per_pixel(spec.georef, s);

  const int map_x = kMargin, map_y = kMargin + kTitle;
  const int bar_height = std::clamp(shown.rows * 3 / 5, 120, 320);
  const int legend_bottom = map_y + 44 + bar_height + 34;
  const int arrow = georeferenced ? 44 : 0;
  // The panel widens for a long band name (horizon_azimuth_168.75).
  int base = 0;
  const int panel = std::max(kPanel, cv::getTextSize(spec.band, kFont, 0.5, 1, &base).width + 4);
  const int width = map_x + shown.cols + 2 * kMargin + panel;
  const int height = std::max(map_y + shown.rows + (metres ? kScaleStrip : kMargin),
                              legend_bottom + (arrow ? arrow + 44 : 0) + kMargin);
  cv::Mat canvas(height, width, CV_8UC4, kPaper);  // RGBA, as write_png takes it

  // The map: nodata fully transparent, so that a basemap shows through it in QGIS.
  const double span = hi > lo ? hi - lo : 1.0;
  for (int y = 0; y < shown.rows; ++y) {
    for (int x = 0; x < shown.cols; ++x) {
      const float v = shown.at<float>(y, x);
      cv::Vec4b& px = canvas.at<cv::Vec4b>(map_y + y, map_x + x);
      if (std::isnan(v)) {
        px = cv::Vec4b(0, 0, 0, 0);
        continue;
      }
      const auto c = ramp_colour(spec.ramp, (v - lo) / span);
      px = cv::Vec4b(c[0], c[1], c[2], 255);
    }
  }
  put(canvas, fitted(spec.title, 0.55, width - 2 * kMargin), {kMargin, kMargin + 16}, 0.55);
  const int panel_x = map_x + shown.cols + 2 * kMargin;
  const int below_legend = draw_legend(canvas, panel_x, map_y, bar_height, spec, lo, hi);
  if (georeferenced) {
    detail::draw_north_arrow(canvas, {panel_x + 22, below_legend + 36 + arrow / 2}, arrow, spec.georef);
  }
  if (metres) {
    detail::draw_scale_bar(canvas, {map_x + 4, map_y + shown.rows + 10}, *metres, std::max(40, shown.cols / 3));
  }

  write_png(path, canvas.cols, canvas.rows, 4, canvas.ptr<std::uint8_t>(0), overwrite);
  if (georeferenced) {
    // The map's top-left pixel is at (map_x, map_y) of the picture: the world file places the
    // picture so that the map lies on its cells.
    write_output_file(world, detail::world_file_text(spec.georef, -map_x * s, -map_y * s, s), overwrite);
  }
  char range[64];
  std::snprintf(range, sizeof range, "%.9g,%.9g", lo, hi);
  write_output_file(pam,
                    detail::pam_text(georeferenced ? spec.georef.crs_wkt : std::string(),
                                     {{"PREVIEW_TITLE", spec.title},
                                      {"PREVIEW_BAND", spec.band},
                                      {"PREVIEW_UNIT", spec.unit},
                                      {"PREVIEW_RAMP", ramp_name(spec.ramp)},
                                      {"PREVIEW_RANGE", range},
                                      {"PREVIEW_STRETCH", spec.range ? "fixed" : "2nd to 98th percentile"}}),
                    overwrite);
}

}  // namespace skyview
