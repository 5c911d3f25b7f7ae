// The exposure sampler of Section 6 (Eqs. 7–10) on the exposure map's mip-map pyramid.
#include "skyview/sky/exposure_sampler.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "skyview/core/error.h"

namespace skyview {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTurn = 2 * kPi;
// Surfaces one call serves with the same samples.
constexpr std::size_t kMaxNormals = 8;

// The extremes of n·ω over a slice of sky [from, to] × [low, high] for a surface facing up or
// sideways (n_z ≥ 0). n·ω = n_z sin e + a cos e cos(φ − along), a = |n_h|: over the arc, cos(φ − along)
// is extreme at its ends or where it passes `along` (+1) or its opposite (−1); over the elevations,
// the minimum with the smallest cosine c is at `low` (n_z sin e + a c cos e rises on [0, π/2] for
// c ≤ 0, and is positive for c > 0), the maximum with the largest at an end or at its peak.
struct Extremes {
  double min = 0, max = 0;
};
Extremes extremes(const Direction& n, double across, double sin_from, double cos_from, double sin_to, double cos_to,
                  double sin_low, double cos_low, double sin_high, double cos_high) {
  const double ux = n[0] / across, uy = n[1] / across;  // the horizontal part, unit
  const double c_from = ux * sin_from + uy * cos_from, c_to = ux * sin_to + uy * cos_to;
  // sin(along − from) and sin(to − along): both ≥ 0 where `along` lies within the arc (under half a turn).
  const double after_from = ux * cos_from - uy * sin_from, before_to = sin_to * uy - cos_to * ux;
  const double c_max = after_from >= 0 && before_to >= 0 ? 1.0 : std::max(c_from, c_to);
  const double c_min = after_from <= 0 && before_to <= 0 ? -1.0 : std::min(c_from, c_to);
  Extremes e;
  e.min = std::min(n[2] * sin_low + across * c_min * cos_low, n[2] * sin_high + across * c_min * cos_high);
  e.max = std::max(n[2] * sin_low + across * c_max * cos_low, n[2] * sin_high + across * c_max * cos_high);
  // The peak, where tan e = n_z / (a c): above `low` and below `high`?
  const double ac = across * c_max;
  if (ac > 0 && n[2] * cos_low > ac * sin_low && n[2] * cos_high < ac * sin_high) e.max = std::hypot(n[2], ac);
  return e;
}

}  // namespace

ExposureSampler::ExposureSampler(const ExposurePyramid& pyramid, int directions, double rotation,
                                 const SamplerOptions& options)
    : directions_(directions), rotation_(rotation), reads_(options.reads) {
  const ExposurePyramid::Level& base = pyramid.level(0);
  map_width_ = base.width;
  map_height_ = base.height;
  if (directions < 1 || directions > map_width_) {
    throw Error("exposure sampler: " + std::to_string(directions) + " directions for a map " +
                std::to_string(map_width_) + " cells wide (1 .. its width)");
  }
  if (options.max_sample_rows < 0 || options.cut_rows < 1)
    throw Error("exposure sampler: max_sample_rows must be 0 or more and cut_rows 1 or more");
  slice_cells_ = static_cast<double>(map_width_) / directions;
  max_rows_ = options.max_sample_rows > 0 ? std::min<double>(options.max_sample_rows, slice_cells_) : slice_cells_;
  cut_rows_ = options.cut_rows;
  gap_parts_ = options.gap_parts;
  if (gap_parts_ < 1 || gap_parts_ > 64) throw Error("exposure sampler: gap_parts must be within 1 .. 64");
  if (reads_ == SamplerReads::mipmap) {
    for (int k = 0; k < pyramid.levels(); ++k) {
      const ExposurePyramid::Level& l = pyramid.level(k);
      Level out;
      out.width = l.width;
      out.height = l.height;
      out.cell_side = 1 << k;
      out.texels.resize(static_cast<std::size_t>(l.width) * l.height * 6);
      for (int y = 0; y < l.height; ++y) {
        // Blocks on the map's far edges hold fewer cells when its size is not a power of two.
        const int rows = std::min(out.cell_side, map_height_ - y * out.cell_side);
        for (int x = 0; x < l.width; ++x) {
          const int cols = std::min(out.cell_side, map_width_ - x * out.cell_side);
          const std::size_t i = static_cast<std::size_t>(y) * l.width + x;
          const double per_cell = 1.0 / (static_cast<double>(rows) * cols);
          for (int c = 0; c < 3; ++c) {
            out.texels[6 * i + c] = static_cast<float>(l.direct_moment[i][c] * per_cell);
            out.texels[6 * i + 3 + c] = static_cast<float>(l.diffuse_moment[i][c] * per_cell);
          }
        }
      }
      levels_.push_back(std::move(out));
    }
  } else {
    const std::size_t stride = static_cast<std::size_t>(map_width_ + 1) * 6;
    table_.assign(stride * (map_height_ + 1), 0.0);
    for (int y = 0; y < map_height_; ++y) {
      const double* above = table_.data() + stride * y;
      double* row = table_.data() + stride * (y + 1);
      double run[6] = {0, 0, 0, 0, 0, 0};
      for (int x = 0; x < map_width_; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * map_width_ + x;
        for (int c = 0; c < 3; ++c) {
          run[c] += base.direct_moment[i][c];
          run[3 + c] += base.diffuse_moment[i][c];
        }
        for (int c = 0; c < 6; ++c) row[6 * (x + 1) + c] = above[6 * (x + 1) + c] + run[c];
      }
    }
  }
  for (int k = 0; k < directions_; ++k) {
    const double from = rotation_ + kTurn / directions_ * (k - 0.5);
    edge_sin_.push_back(std::sin(from));
    edge_cos_.push_back(std::cos(from));
  }
  if (reads_ == SamplerReads::area) {
    columns_.resize(directions_);
    for (int k = 0; k < directions_; ++k) {
      const double xa = ((rotation_ - kPi / directions_) / kTurn + static_cast<double>(k) / directions_) * map_width_;
      columns_[k].resize(static_cast<std::size_t>(map_height_) + 1);
      for (int y = 1; y <= map_height_; ++y) rectangle(xa, xa + slice_cells_, 0.0, y, columns_[k][y]);
    }
    // The parts of each gap between direction k and the next.
    const double part = slice_cells_ / gap_parts_;
    gap_columns_.resize(static_cast<std::size_t>(directions_) * gap_parts_);
    for (int k = 0; k < directions_; ++k) {
      const double x0 = (rotation_ / kTurn + static_cast<double>(k) / directions_) * map_width_;
      for (int j = 0; j < gap_parts_; ++j) {
        std::vector<Moments>& col = gap_columns_[static_cast<std::size_t>(k) * gap_parts_ + j];
        col.resize(static_cast<std::size_t>(map_height_) + 1);
        for (int y = 1; y <= map_height_; ++y) rectangle(x0 + j * part, x0 + (j + 1) * part, 0.0, y, col[y]);
      }
    }
  }
  // Running sums of the full samples of an interval open to the zenith, from the top row down.
  cached_.resize(directions_);
  const int full = static_cast<int>(std::floor(map_height_ / max_rows_ + 1e-9));
  for (int k = 0; k < directions_; ++k) {
    const double xa = ((rotation_ - kPi / directions_) / kTurn + static_cast<double>(k) / directions_) * map_width_;
    cached_[k].resize(static_cast<std::size_t>(full) + 1);
    for (int j = 0; j < full; ++j) {
      cached_[k][j + 1] = cached_[k][j];
      read(xa, xa + slice_cells_, (j + 0.5) * max_rows_, max_rows_, cached_[k][j + 1]);
    }
  }
}

double ExposureSampler::row_of(double elevation) const {
  return std::clamp((kPi / 2 - elevation) / (kPi / 2), 0.0, 1.0) * map_height_;
}

int ExposureSampler::sample_count(float horizon, float opening) const {
  const double top = row_of(opening), bottom = row_of(std::max(0.0f, horizon));
  if (!(bottom > top)) return 0;
  return std::max(1, static_cast<int>(std::ceil((bottom - top) / max_rows_ - 1e-9)));
}

void ExposureSampler::rectangle(double xa, double xb, double y0, double y1, Moments& acc) const {
  // The table is bilinear between its nodes (the map is constant within a cell): exact for any
  // fraction of a cell. Azimuth wraps: a column beyond the map's width is a whole turn further.
  struct Column {
    int i;
    double f, turns;
  };
  auto column = [&](double x) {
    const double turns = std::floor(x / map_width_);
    const double in = x - turns * map_width_;
    const int i = std::min(static_cast<int>(in), map_width_ - 1);
    return Column{i, in - i, turns};
  };
  const Column a = column(xa), b = column(xb);
  const std::size_t stride = static_cast<std::size_t>(map_width_ + 1) * 6;
  for (const auto& [y, sign] : {std::pair{y1, 1.0}, std::pair{y0, -1.0}}) {
    const int j = std::clamp(static_cast<int>(y), 0, map_height_ - 1);
    const double fy = std::clamp(y - j, 0.0, 1.0);
    const double* top = table_.data() + stride * j;
    const double* bottom = top + stride;
    const double* ta = top + 6 * a.i;
    const double* ba = bottom + 6 * a.i;
    const double* tb = top + 6 * b.i;
    const double* bb = bottom + 6 * b.i;
    const double* turn_top = top + 6 * map_width_;
    const double* turn_bottom = bottom + 6 * map_width_;
    const double turns = b.turns - a.turns;
    for (int c = 0; c < 6; ++c) {
      const double at_a = ta[c] + a.f * (ta[6 + c] - ta[c]) +
                          fy * (ba[c] + a.f * (ba[6 + c] - ba[c]) - ta[c] - a.f * (ta[6 + c] - ta[c]));
      const double at_b = tb[c] + b.f * (tb[6 + c] - tb[c]) +
                          fy * (bb[c] + b.f * (bb[6 + c] - bb[c]) - tb[c] - b.f * (tb[6 + c] - tb[c]));
      const double turn = turn_top[c] + fy * (turn_bottom[c] - turn_top[c]);
      acc.m[c] += sign * (at_b - at_a + turns * turn);
    }
  }
}

ExposureSampler::Moments ExposureSampler::column(const std::vector<Moments>& col, double y) const {
  const int j = std::clamp(static_cast<int>(y), 0, map_height_ - 1);
  const double f = std::clamp(y - j, 0.0, 1.0);
  Moments m;
  for (int c = 0; c < 6; ++c) m.m[c] = col[j].m[c] + f * (col[j + 1].m[c] - col[j].m[c]);
  return m;
}

void ExposureSampler::bilinear(int level, double x, double y, double weight, Moments& acc) const {
  const Level& l = levels_[level];
  const double u = x / l.cell_side - 0.5, v = y / l.cell_side - 0.5;
  const double u0 = std::floor(u), v0 = std::floor(v);
  const double fu = u - u0;
  double fv = v - v0;
  int i0 = static_cast<int>(u0) % l.width;
  if (i0 < 0) i0 += l.width;
  const int i1 = i0 + 1 == l.width ? 0 : i0 + 1;  // azimuth wraps around
  int j0 = static_cast<int>(v0), j1 = j0 + 1;     // rows stop at the zenith and the horizon
  if (j0 < 0) j0 = j1 = 0, fv = 0.0;
  if (j1 >= l.height) j0 = j1 = l.height - 1, fv = 0.0;
  const float* row0 = l.texels.data() + static_cast<std::size_t>(j0) * l.width * 6;
  const float* row1 = l.texels.data() + static_cast<std::size_t>(j1) * l.width * 6;
  const double w00 = weight * (1 - fu) * (1 - fv), w10 = weight * fu * (1 - fv);
  const double w01 = weight * (1 - fu) * fv, w11 = weight * fu * fv;
  for (int c = 0; c < 6; ++c) {
    acc.m[c] += w00 * row0[6 * i0 + c] + w10 * row0[6 * i1 + c] + w01 * row1[6 * i0 + c] + w11 * row1[6 * i1 + c];
  }
}

void ExposureSampler::read_mipmap(double xa, double xb, double y, double height, Moments& acc) const {
  // Eq. 9 between the two nearest levels, times Eq. 10's cells.
  const int top = static_cast<int>(levels_.size()) - 1;
  const double b = std::clamp(std::log2(std::max(height, 1.0)), 0.0, static_cast<double>(top));
  const int l0 = static_cast<int>(b), l1 = std::min(l0 + 1, top);
  const double t = b - l0, area = (xb - xa) * height, x = 0.5 * (xa + xb);
  bilinear(l0, x, y, area * (1 - t), acc);
  if (t > 0.0) bilinear(l1, x, y, area * t, acc);
}

void ExposureSampler::read(double xa, double xb, double y, double height, Moments& acc) const {
  if (reads_ == SamplerReads::mipmap) {
    read_mipmap(xa, xb, y, height, acc);
    return;
  }
  rectangle(xa, xb, std::max(0.0, y - 0.5 * height), std::min<double>(map_height_, y + 0.5 * height), acc);
}

void ExposureSampler::cut(const Direction& d, double along, double across, double from, double width, double y0,
                          double y1, const std::vector<Moments>* table, Moments& acc) const {
  const double to_column = map_width_ / kTurn;
  const int parts = std::max(1, static_cast<int>(std::ceil((y1 - y0) / cut_rows_ - 1e-9)));
  const double rows = (y1 - y0) / parts;
  const double da = std::remainder(from - along, kTurn);  // the arc's start from `along`, in [−π, π]
  // Parts wholly in front run together and, with the arc's column table, are read at once.
  double run_from = -1.0;
  auto flush = [&](double to) {
    if (run_from < 0.0) return;
    if (table) {
      const Moments a = column(*table, run_from), b = column(*table, to);
      for (int c = 0; c < 6; ++c) acc.m[c] += b.m[c] - a.m[c];
    } else {
      read(from * to_column, (from + width) * to_column, 0.5 * (run_from + to), to - run_from, acc);
    }
    run_from = -1.0;
  };
  for (int p = 0; p < parts; ++p) {
    const double top = y0 + p * rows, y = top + 0.5 * rows;
    const double elevation = (1.0 - y / map_height_) * (kPi / 2);
    // In front where cos(φ − along) > −n_z tan e / |n_h|: an arc of half-width w about `along`.
    const double c = -d[2] * std::tan(elevation) / across;
    const double w = c >= 1.0 ? 0.0 : c <= -1.0 ? kPi : std::acos(c);
    double pieces[2][2];
    int count = 0;
    double covered = 0.0;
    for (const double centre : {0.0, kTurn}) {
      const double a = std::max(da, centre - w), b = std::min(da + width, centre + w);
      if (b > a) pieces[count][0] = a, pieces[count][1] = b, ++count, covered += b - a;
    }
    if (covered >= width * (1 - 1e-12)) {
      if (run_from < 0.0) run_from = top;
      continue;
    }
    flush(top);
    for (int i = 0; i < count; ++i)
      read((along + pieces[i][0]) * to_column, (along + pieces[i][1]) * to_column, y, rows, acc);
  }
  flush(y1);
}

void ExposureSampler::add_arc(double from, double width, const std::vector<Moments>* table, double low, double high,
                              std::span<const Direction> normals, std::span<SkyExposure> out) const {
  const std::size_t n = normals.size();
  const double y_top = row_of(high), y_bottom = row_of(low);
  const double xa = from * map_width_ / kTurn, xb = xa + width * map_width_ / kTurn;
  auto rows = [&](double y0, double y1) {
    Moments m;
    if (table) {
      const Moments a = column(*table, y0), b = column(*table, y1);
      for (int c = 0; c < 6; ++c) m.m[c] = b.m[c] - a.m[c];
    } else {
      rectangle(xa, xb, y0, y1, m);
    }
    return m;
  };
  bool have_open = false;
  Moments open;
  double sin_from = 0, cos_from = 0, sin_to = 0, cos_to = 0, sin_low = 0, cos_low = 1, sin_high = 1, cos_high = 0;
  bool angles = false;
  for (std::size_t i = 0; i < n; ++i) {
    const Direction& d = normals[i];
    if (d[2] < 0.0) throw Error("exposure sampler: a surface facing down (normal z < 0)");
    const double across = std::sqrt(d[0] * d[0] + d[1] * d[1]);
    // Sines and cosines as needed: a level surface takes every arc whole.
    if (across > 0.0 && !angles) {
      angles = true;
      sin_from = std::sin(from), cos_from = std::cos(from), sin_to = std::sin(from + width);
      cos_to = std::cos(from + width);
      if (low > 0.0) sin_low = std::sin(low), cos_low = std::cos(low);
      if (high < kPi / 2) sin_high = std::sin(high), cos_high = std::cos(high);
    }
    // In front of the whole arc (most surfaces face up, most of the sky is above their tilt), of
    // none of it, or of part.
    bool whole = across == 0.0 || across * cos_low <= d[2] * sin_low;
    if (!whole) {
      const Extremes e = extremes(d, across, sin_from, cos_from, sin_to, cos_to, sin_low, cos_low, sin_high, cos_high);
      if (e.max <= 0.0) continue;
      whole = e.min >= 0.0;
    }
    Moments m;
    if (whole) {
      if (!have_open) open = rows(y_top, y_bottom), have_open = true;
      m = open;
    } else {
      // In front at every azimuth above the surface's tilt; below it, cut.
      const double y_tilt = std::clamp(row_of(std::atan2(across, d[2])), y_top, y_bottom);
      m = rows(y_top, y_tilt);
      cut(d, std::atan2(d[0], d[1]), across, from, width, y_tilt, y_bottom, table, m);
    }
    const double direct = d[0] * m.m[0] + d[1] * m.m[1] + d[2] * m.m[2];
    const double diffuse = d[0] * m.m[3] + d[1] * m.m[4] + d[2] * m.m[5];
    if (direct > 0.0) out[i].direct += direct;
    if (diffuse > 0.0) out[i].diffuse += diffuse;
  }
}

void ExposureSampler::add_gap(int k, float h0, float h1, std::span<const Direction> normals,
                              std::span<SkyExposure> out) const {
  if (reads_ != SamplerReads::area) throw Error("exposure sampler: gaps are read with area reads only");
  if (normals.size() > kMaxNormals || out.size() != normals.size()) {
    throw Error("exposure sampler: " + std::to_string(normals.size()) + " normals (at most " +
                std::to_string(kMaxNormals) + ") and " + std::to_string(out.size()) + " sums");
  }
  if (std::isnan(h0) || std::isnan(h1)) return;
  const double width = kTurn / directions_ / gap_parts_;
  const double from = rotation_ + kTurn / directions_ * k;
  for (int j = 0; j < gap_parts_; ++j) {
    // The horizon at the part's middle, on the line between the two directions'.
    const double t = (j + 0.5) / gap_parts_;
    const double low = std::max(0.0, h0 + t * (static_cast<double>(h1) - h0));
    if (!(kPi / 2 > low)) continue;
    add_arc(from + j * width, width, &gap_columns_[static_cast<std::size_t>(k) * gap_parts_ + j], low, kPi / 2, normals,
            out);
  }
}

void ExposureSampler::add_slice(int k, float horizon, float opening, std::span<const Direction> normals,
                                std::span<SkyExposure> out, double turn) const {
  if (normals.size() > kMaxNormals || out.size() != normals.size()) {
    throw Error("exposure sampler: " + std::to_string(normals.size()) + " normals (at most " +
                std::to_string(kMaxNormals) + ") and " + std::to_string(out.size()) + " sums");
  }
  const double low = std::max(0.0, static_cast<double>(horizon));
  const double high = std::min(kPi / 2, static_cast<double>(opening));
  if (!(high > low)) return;  // NaN (nodata) included
  const double width = kTurn / directions_;
  const double from = rotation_ + turn + width * (k - 0.5);
  if (reads_ == SamplerReads::area) {
    // Exact reads add up: the samples in front of a surface are read together (at the sampler's
    // rotation from the slice's column table), and only those its plane crosses are cut.
    add_arc(from, width, turn == 0.0 ? &columns_[static_cast<std::size_t>(k)] : nullptr, low, high, normals, out);
    return;
  }
  // Mip-map reads, Eq. 7's samples. Per surface: the whole slice in front of it, none of it
  // (discarded), or part of it.
  enum Stand { whole, none, part };
  Stand stand[kMaxNormals];
  bool any_whole = false, any_part = false;
  const std::size_t n = normals.size();
  // Sines and cosines as needed: a level surface takes every slice whole.
  bool angles = false;
  double sin_from = 0, cos_from = 0, sin_to = 0, cos_to = 0, sin_low = 0, cos_low = 1, sin_high = 1, cos_high = 0;
  double across[kMaxNormals];
  for (std::size_t i = 0; i < n; ++i) {
    const Direction& d = normals[i];
    if (d[2] < 0.0) throw Error("exposure sampler: a surface facing down (normal z < 0)");
    across[i] = std::sqrt(d[0] * d[0] + d[1] * d[1]);
    if (across[i] == 0.0) {
      stand[i] = whole;
      any_whole = true;
      continue;
    }
    if (!angles) {
      angles = true;
      const int next = k + 1 == directions_ ? 0 : k + 1;
      sin_from = turn == 0.0 ? edge_sin_[k] : std::sin(from), cos_from = turn == 0.0 ? edge_cos_[k] : std::cos(from);
      sin_to = turn == 0.0 ? edge_sin_[next] : std::sin(from + width);
      cos_to = turn == 0.0 ? edge_cos_[next] : std::cos(from + width);
      if (low > 0.0) sin_low = std::sin(low), cos_low = std::cos(low);
      if (high < kPi / 2) sin_high = std::sin(high), cos_high = std::cos(high);
    }
    // Most surfaces face up and most slices lie wholly in front of them: a quick test first.
    if (across[i] * cos_low <= d[2] * sin_low) {
      stand[i] = whole;
    } else {
      const Extremes e =
          extremes(d, across[i], sin_from, cos_from, sin_to, cos_to, sin_low, cos_low, sin_high, cos_high);
      stand[i] = e.min >= 0.0 ? whole : e.max <= 0.0 ? none : part;
    }
    any_whole = any_whole || stand[i] == whole;
    any_part = any_part || stand[i] == part;
  }
  if (!any_whole && !any_part) return;
  auto add = [&](std::size_t i, const Moments& m) {
    const Direction& d = normals[i];
    const double direct = d[0] * m.m[0] + d[1] * m.m[1] + d[2] * m.m[2];
    const double diffuse = d[0] * m.m[3] + d[1] * m.m[4] + d[2] * m.m[5];
    if (direct > 0.0) out[i].direct += direct;
    if (diffuse > 0.0) out[i].diffuse += diffuse;
  };
  const double y_top = row_of(high), y_bottom = row_of(low);
  const double xa = from * map_width_ / kTurn, xb = xa + slice_cells_;
  // Eq. 7: samples `max_rows_` high (slice-wide squares by default) from h' down, the last one
  // shortened to end at h. A surface the whole slice faces takes every sample's moment with a
  // positive cosine, so their sum (cached for an interval open to the zenith) serves for all.
  const double rows = max_rows_;
  const int full = static_cast<int>(std::floor((y_bottom - y_top) / rows + 1e-9));
  const double rest_top = y_top + full * rows, rest = y_bottom - rest_top;
  const bool has_rest = rest > 1e-9 * map_height_;
  const bool cached = turn == 0.0 && y_top == 0.0;
  if (any_whole) {
    Moments m;
    if (cached) {
      m = cached_[k][full];
    } else {
      for (int j = 0; j < full; ++j) read(xa, xb, y_top + (j + 0.5) * rows, rows, m);
    }
    if (has_rest) read(xa, xb, rest_top + 0.5 * rest, rest, m);
    for (std::size_t i = 0; i < n; ++i) {
      if (stand[i] == whole) add(i, m);
    }
  }
  if (!any_part) return;
  for (std::size_t i = 0; i < n; ++i) {
    if (stand[i] != part) continue;
    // Each sample keeps the azimuths in front of the surface, its moment's cosine clamped.
    const Direction& d = normals[i];
    const double along = std::atan2(d[0], d[1]);
    for (int j = 0; j <= full; ++j) {
      const double top = y_top + j * rows, height = j < full ? rows : (has_rest ? rest : 0.0);
      if (height <= 0.0) continue;
      Moments m;
      cut(d, along, across[i], from, width, top, top + height, nullptr, m);
      add(i, m);
    }
  }
}

SkyExposure ExposureSampler::exposure(const Direction& normal, std::span<const float> horizon,
                                      std::span<const float> opening, double turn) const {
  if (static_cast<int>(horizon.size()) != directions_ || (!opening.empty() && opening.size() != horizon.size())) {
    throw Error("exposure sampler: " + std::to_string(horizon.size()) + " horizons (and " +
                std::to_string(opening.size()) + " opening angles) for " + std::to_string(directions_) + " directions");
  }
  SkyExposure sum;
  for (int k = 0; k < directions_; ++k) {
    add_slice(k, horizon[k], opening.empty() ? static_cast<float>(kPi / 2) : opening[k], {&normal, 1}, {&sum, 1}, turn);
  }
  return sum;
}

}  // namespace skyview
