// Plain text clouds: one point per line, x y z as the first three fields, separated by spaces,
// tabs, commas or semicolons; later fields (intensity, colour) are ignored, so every point is
// unclassified. Lines starting with '#' or '//' and a first line of column names are skipped.
// The file is read twice (bounds, then points), streamed both times.
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>

#include "skyview/core/error.h"
#include "skyview/dsm/point_cloud.h"

namespace skyview {
namespace {

bool is_separator(char c) { return c == ' ' || c == '\t' || c == ',' || c == ';' || c == '\r'; }

// Parses the first three numbers of `line`; false when it is not a point.
bool parse_xyz(const std::string& line, double xyz[3]) {
  const char* p = line.data();
  const char* end = p + line.size();
  for (int i = 0; i < 3; ++i) {
    while (p < end && is_separator(*p)) ++p;
    const auto [next, ec] = std::from_chars(p, end, xyz[i]);
    if (ec != std::errc() || next == p || (next < end && !is_separator(*next))) return false;
    p = next;
  }
  return std::isfinite(xyz[0]) && std::isfinite(xyz[1]) && std::isfinite(xyz[2]);
}

bool is_comment_or_blank(const std::string& line) {
  std::size_t i = line.find_first_not_of(" \t\r");
  return i == std::string::npos || line[i] == '#' || line.compare(i, 2, "//") == 0;
}

class TextCloud final : public PointCloud {
 public:
  explicit TextCloud(const std::string& path) : PointCloud(path) {
    start_bounds();
    scan([&](const double* p) {
      include_in_bounds(p[0], p[1]);
      ++point_count_;
    });
    settle_bounds();
  }

  void read_points(const std::function<void(const std::vector<LasPoint>&)>& chunk,
                   std::size_t chunk_points) const override {
    std::vector<LasPoint> points;
    points.reserve(std::min<std::size_t>(chunk_points, 1 << 20));
    scan([&](const double* p) {
      points.push_back({p[0], p[1], p[2], 0, 1, 1, 1});
      if (points.size() >= chunk_points) {
        chunk(points);
        points.clear();
      }
    });
    if (!points.empty()) chunk(points);
  }

 private:
  template <class F>
  void scan(F&& point) const {
    std::ifstream in(path_);
    if (!in) throw Error("cannot open '" + path_ + "': no such file or not readable");
    std::string line;
    double xyz[3];
    bool first = true;  // the first line that is not a comment may name the columns
    for (std::uint64_t n = 1; std::getline(in, line); ++n) {
      if (is_comment_or_blank(line)) continue;
      // A header names columns; a line that starts with a number is data, however short.
      const auto start = line.find_first_not_of(" \t");
      const bool may_be_header = first && start != std::string::npos && !std::strchr("0123456789+-.", line[start]);
      first = false;
      if (parse_xyz(line, xyz)) {
        point(xyz);
      } else if (!may_be_header) {
        throw Error("'" + path_ + "' line " + std::to_string(n) + ": expected x y z numbers, found '" +
                    line.substr(0, 60) + "'");
      }
    }
    if (in.bad()) throw Error("read error in '" + path_ + "'");
  }
};

}  // namespace

std::unique_ptr<PointCloud> detail::open_text_cloud(const std::string& path) {
  return std::make_unique<TextCloud>(path);
}

}  // namespace skyview
