// The time-against-error plot every benchmark draws.
#include "skyview/benchmark/pareto_plot.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "preview/opencv_png.h"

namespace skyview {

void mark_pareto(std::vector<ParetoPoint>& points) {
  for (auto& p : points) {
    p.pareto = std::none_of(points.begin(), points.end(), [&](const ParetoPoint& o) {
      return &o != &p && o.seconds <= p.seconds && o.error <= p.error && (o.seconds < p.seconds || o.error < p.error);
    });
  }
}

void plot_pareto(const std::string& png_path, const std::string& title, const std::string& error_label,
                 const std::vector<ParetoPoint>& points, const std::vector<SeriesColour>& colours, bool overwrite) {
  const int W = 900, H = 600, left = 90, right = 30, top = 50, bottom = 70;
  cv::Mat img(H, W, CV_8UC3, cv::Scalar(255, 255, 255));
  double tmin = 1e30, tmax = 0, emin = 1e30, emax = 0;
  for (const auto& p : points) {
    tmin = std::min(tmin, p.seconds), tmax = std::max(tmax, p.seconds);
    emin = std::min(emin, std::max(p.error, 1e-5)), emax = std::max(emax, std::max(p.error, 1e-5));
  }
  const double lt0 = std::floor(std::log10(tmin)), lt1 = std::ceil(std::log10(tmax) + 1e-9);
  const double le0 = std::floor(std::log10(emin)), le1 = std::ceil(std::log10(emax) + 1e-9);
  auto px = [&](double t, double e) {
    const double x = left + (std::log10(t) - lt0) / std::max(1e-9, lt1 - lt0) * (W - left - right);
    const double y =
        H - bottom - (std::log10(std::max(e, 1e-5)) - le0) / std::max(1e-9, le1 - le0) * (H - top - bottom);
    return cv::Point(static_cast<int>(x), static_cast<int>(y));
  };
  const cv::Scalar grey(200, 200, 200), black(0, 0, 0);
  for (double d = lt0; d <= lt1; ++d) {
    cv::line(img, px(std::pow(10, d), std::pow(10, le0)), px(std::pow(10, d), std::pow(10, le1)), grey);
    std::ostringstream l;
    l << std::pow(10, d) << " s";
    cv::putText(img, l.str(), px(std::pow(10, d), std::pow(10, le0)) + cv::Point(-20, 22), cv::FONT_HERSHEY_SIMPLEX,
                0.45, black);
  }
  for (double d = le0; d <= le1; ++d) {
    cv::line(img, px(std::pow(10, lt0), std::pow(10, d)), px(std::pow(10, lt1), std::pow(10, d)), grey);
    std::ostringstream l;
    l << std::pow(10, d);
    cv::putText(img, l.str(), px(std::pow(10, lt0), std::pow(10, d)) + cv::Point(-75, 5), cv::FONT_HERSHEY_SIMPLEX,
                0.45, black);
  }
  // Centred above the plot, clear of the axis label at its top left.
  int baseline = 0;
  const cv::Size title_size = cv::getTextSize(title, cv::FONT_HERSHEY_SIMPLEX, 0.6, 1, &baseline);
  cv::putText(img, title, cv::Point((W - title_size.width) / 2, 24), cv::FONT_HERSHEY_SIMPLEX, 0.6, black);
  cv::putText(img, "time per run (log)", cv::Point(W / 2 - 60, H - 20), cv::FONT_HERSHEY_SIMPLEX, 0.5, black);
  cv::putText(img, error_label, cv::Point(5, top - 10), cv::FONT_HERSHEY_SIMPLEX, 0.5, black);
  auto colour_of = [&](const std::string& series) {
    for (const auto& [name, c] : colours) {
      if (name == series) return cv::Scalar(c[0], c[1], c[2]);
    }
    return black;
  };
  std::vector<const ParetoPoint*> front;
  for (const auto& p : points) {
    if (p.pareto) front.push_back(&p);
  }
  std::sort(front.begin(), front.end(), [](auto* a, auto* b) { return a->seconds < b->seconds; });
  for (std::size_t i = 1; i < front.size(); ++i) {
    cv::line(img, px(front[i - 1]->seconds, front[i - 1]->error), px(front[i]->seconds, front[i]->error),
             cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  }
  for (const auto& p : points)
    cv::circle(img, px(p.seconds, p.error), p.pareto ? 6 : 4, colour_of(p.series), cv::FILLED, cv::LINE_AA);
  int y = top + 10;
  std::set<std::string> shown;
  for (const auto& p : points) shown.insert(p.series);
  for (const auto& [name, c] : colours) {
    if (!shown.count(name)) continue;
    cv::circle(img, cv::Point(W - 215, y), 5, cv::Scalar(c[0], c[1], c[2]), cv::FILLED, cv::LINE_AA);
    cv::putText(img, name, cv::Point(W - 203, y + 5), cv::FONT_HERSHEY_SIMPLEX, 0.5, black);
    y += 20;
  }
  cv::putText(img, "line: Pareto front", cv::Point(W - 215, y + 5), cv::FONT_HERSHEY_SIMPLEX, 0.45, black);
  detail::write_bgr_png(png_path, img, overwrite);
}

}  // namespace skyview
