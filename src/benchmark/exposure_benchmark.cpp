// skyview exposure's speed against error.
#include "skyview/benchmark/exposure_benchmark.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <numbers>
#include <sstream>

#include "skyview/benchmark/pareto_plot.h"
#include "skyview/sky_view/sky_view.h"

namespace skyview {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// Max (or min) over the square of side 2r + 1 cells around each cell, nodata left out: a row pass
// then a column pass.
Grid<float> square_extreme(const Grid<float>& in, int r, bool maximum) {
  const int w = in.width(), h = in.height();
  auto better = [maximum](float a, float b) {
    if (std::isnan(a)) return b;
    if (std::isnan(b)) return a;
    return maximum ? std::max(a, b) : std::min(a, b);
  };
  Grid<float> rows(w, h, kNaN), out(w, h, kNaN);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      float v = kNaN;
      for (int d = std::max(0, x - r); d <= std::min(w - 1, x + r); ++d) v = better(v, in(d, y));
      rows(x, y) = v;
    }
  }
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      float v = kNaN;
      for (int d = std::max(0, y - r); d <= std::min(h - 1, y + r); ++d) v = better(v, rows(x, d));
      out(x, y) = v;
    }
  }
  return out;
}

ExposureBands run(const Terrain& terrain, const ExposureSky& sky, const ExposureBenchConfig& c) {
  const auto engine = make_horizon_engine(c.horizon_method, c.params);
  ExposureRequest request;
  request.method = c.method;
  request.sampler = c.sampler;
  ProgressCounter progress;
  return compute_exposure(*engine, terrain, Window::whole(terrain), sky, request, progress);
}

nlohmann::json stats_json(const ErrorStats& e) {
  return {{"rmse", e.rmse}, {"bias", e.bias}, {"p99_abs", e.p99}, {"max_abs", e.max_abs}, {"cells", e.cells}};
}

std::string percent(double v) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(2) << 100 * v << "%";
  return s.str();
}

}  // namespace

const char* cell_kind_name(CellKind kind) {
  switch (kind) {
    case CellKind::roof:
      return "roofs";
    case CellKind::street:
      return "streets";
    case CellKind::north_slope:
      return "north slopes";
    case CellKind::wall_foot:
      return "wall feet";
    default:
      return "other";
  }
}

std::vector<ExposureBenchConfig> default_exposure_bench_grid() {
  std::vector<ExposureBenchConfig> grid;
  auto add = [&](const std::string& series, ExposureMethod method, const std::string& horizon, int directions,
                 int samples, SamplerReads reads) {
    ExposureBenchConfig c;
    c.series = series;
    c.method = method;
    c.horizon_method = horizon;
    c.params.directions = directions;
    c.params.samples = samples;
    c.params.azimuth_origin = AzimuthOrigin::grid;
    c.sampler.reads = reads;
    std::ostringstream label;
    label << (method == ExposureMethod::exact ? "exact " : "") << horizon << " d=" << directions;
    if (horizon == "sampled") label << " s=" << samples;
    if (method == ExposureMethod::fast) label << (reads == SamplerReads::area ? " area" : " mipmap");
    c.label = label.str();
    grid.push_back(c);
  };
  for (int d : {8, 16, 32, 64, 128})
    add("fast, sweep, area reads", ExposureMethod::fast, "sweep", d, 0, SamplerReads::area);
  // Cheaper horizons and coarser gaps at 64 directions.
  add("fast, sweep, area reads", ExposureMethod::fast, "sweep", 64, 16, SamplerReads::area);
  grid.back().label += " near=16";
  for (int parts : {1, 2}) {
    add("fast, sweep, area reads", ExposureMethod::fast, "sweep", 64, 0, SamplerReads::area);
    grid.back().sampler.gap_parts = parts;
    grid.back().label += " parts=" + std::to_string(parts);
  }
  for (int d : {8, 16, 32})
    add("fast, sweep, mip-map reads", ExposureMethod::fast, "sweep", d, 0, SamplerReads::mipmap);
  // The paper's 8 x (8 + 8) and 16 x (16 + 16): N_dir directions, S_dir + S_dir samples each.
  for (int d : {8, 16}) {
    add("paper: sampled, mip-map reads", ExposureMethod::fast, "sampled", d, 2 * d, SamplerReads::mipmap);
    add("sampled, area reads", ExposureMethod::fast, "sampled", d, 2 * d, SamplerReads::area);
  }
  for (int d : {16, 64}) add("exact", ExposureMethod::exact, "sweep", d, 0, SamplerReads::area);
  return grid;
}

Grid<unsigned char> classify_cells(const Terrain& t) {
  const int w = t.width(), h = t.height();
  const double cell = raster_centre_jacobian(t).min_cell_size();
  const int r = std::max(1, static_cast<int>(std::lround(10.0 / cell)));
  const Grid<float> high = square_extreme(t.heights, r, true), low = square_extreme(t.heights, r, false);
  const Grid<float> beside = square_extreme(t.heights, 1, true), lowest = square_extreme(t.heights, 1, false);
  Grid<unsigned char> kinds(w, h, static_cast<unsigned char>(CellKind::other));
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (!t.valid(x, y)) continue;
      double slope, aspect;
      horn_slope_aspect(t, x, y, slope, aspect);
      const float z = t.heights(x, y);
      CellKind kind = CellKind::other;
      if (beside(x, y) - z >= 2.5f && z - lowest(x, y) < 0.5f) {
        kind = CellKind::wall_foot;  // its Horn slope leans on the wall: tested by height alone
      } else if (slope < 10 * kDegree) {
        if (high(x, y) - z >= 2.5f) {
          kind = CellKind::street;
        } else if (z - low(x, y) >= 2.5f) {
          kind = CellKind::roof;
        }
      } else if (slope < 45 * kDegree && std::cos(aspect) > std::cos(45 * kDegree)) {
        kind = CellKind::north_slope;
      }
      kinds(x, y) = static_cast<unsigned char>(kind);
    }
  }
  return kinds;
}

ExposureBenchReference exposure_bench_reference(const Terrain& terrain, const ExposureSky& sky, int directions) {
  ExposureBenchConfig c;
  c.method = ExposureMethod::exact;
  c.params.directions = directions;
  c.params.azimuth_origin = AzimuthOrigin::grid;
  ExposureBenchReference ref;
  const auto t0 = std::chrono::steady_clock::now();
  ref.bands = run(terrain, sky, c);
  ref.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ref.directions = directions;
  ref.kinds = classify_cells(terrain);
  return ref;
}

std::vector<ExposureBenchResult> run_exposure_bench(const Terrain& terrain, const ExposureSky& sky,
                                                    const std::vector<ExposureBenchConfig>& configs,
                                                    const ExposureBenchReference& ref, int repeats,
                                                    const std::function<void(const ExposureBenchResult&)>& on_result) {
  std::vector<ExposureBenchResult> results(configs.size());
  std::vector<std::vector<double>> times(configs.size());
  const double floor = ref.floor_share * ref.bands.global_horizontal / 1000;  // kWh/m²
  const Grid<float>& exact = ref.bands.total;
  const Grid<float> zero(exact.width(), exact.height(), 0.0f);
  for (int round = 0; round < std::max(1, repeats); ++round) {
    for (std::size_t i = 0; i < configs.size(); ++i) {
      const auto t0 = std::chrono::steady_clock::now();
      const ExposureBands b = run(terrain, sky, configs[i]);
      times[i].push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      ExposureBenchResult& r = results[i];
      if (round == 0) {
        r.config = configs[i];
        // Relative errors, NaN where a cell is not judged, then by kind.
        Grid<float> relative(exact.width(), exact.height(), kNaN);
        for (std::size_t c = 0; c < exact.size(); ++c) {
          const float e = exact.values()[c], v = b.total.values()[c];
          if (e > floor && !std::isnan(v)) relative.values()[c] = static_cast<float>(v / e - 1.0);
        }
        r.all = compare_to_reference(relative, zero);
        for (int k = 1; k < 5; ++k) {
          Grid<float> only = relative;
          for (std::size_t c = 0; c < only.size(); ++c) {
            if (ref.kinds.values()[c] != k) only.values()[c] = kNaN;
          }
          r.by_kind[k] = compare_to_reference(only, zero);
        }
      }
      if (round == std::max(1, repeats) - 1) {
        std::vector<double> t = times[i];
        std::sort(t.begin(), t.end());
        const std::size_t n = t.size();
        r.seconds = n % 2 ? t[n / 2] : 0.5 * (t[n / 2 - 1] + t[n / 2]);
        if (on_result) on_result(r);
      }
    }
  }
  std::vector<ParetoPoint> points;
  for (const auto& r : results) points.push_back({r.config.series, r.seconds, r.all.p99, false});
  mark_pareto(points);
  for (std::size_t i = 0; i < results.size(); ++i) results[i].pareto = points[i].pareto;
  return results;
}

nlohmann::json exposure_bench_to_json(const std::string& raster, const ExposureBenchReference& ref,
                                      const std::vector<ExposureBenchResult>& results) {
  nlohmann::json j;
  j["raster"] = raster;
  j["reference"] = {{"method", "exact, sweep"},
                    {"directions", ref.directions},
                    {"seconds", ref.seconds},
                    {"judged_above_share_of_global_horizontal", ref.floor_share}};
  for (const auto& r : results) {
    nlohmann::json row{{"label", r.config.label},
                       {"series", r.config.series},
                       {"seconds", r.seconds},
                       {"relative_error_all", stats_json(r.all)},
                       {"pareto", r.pareto}};
    for (int k = 1; k < 5; ++k)
      row[std::string("relative_error_") + cell_kind_name(CellKind(k))] = stats_json(r.by_kind[k]);
    j["results"].push_back(row);
  }
  return j;
}

std::string exposure_bench_to_markdown(const std::string& raster, const ExposureBenchReference& ref,
                                       const std::vector<ExposureBenchResult>& results) {
  std::ostringstream md;
  md << "### " << raster << "\n\nReference: exact, sweep, " << ref.directions << " directions (" << std::fixed
     << std::setprecision(1) << ref.seconds << " s). Relative error of the total, value / exact - 1, over cells whose "
     << "exact total exceeds " << 100 * ref.floor_share << "% of the unobstructed global horizontal.\n\n";
  md << "| configuration | time (s) | RMSE | p99 all | p99 roofs | p99 streets | p99 north slopes | p99 wall feet | "
        "Pareto |\n|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : results) {
    md << "| " << r.config.label << " | " << std::setprecision(2) << r.seconds << " | " << percent(r.all.rmse) << " | "
       << percent(r.all.p99);
    for (int k = 1; k < 5; ++k) md << " | " << (r.by_kind[k].cells > 0 ? percent(r.by_kind[k].p99) : "-");
    md << " | " << (r.pareto ? "yes" : "") << " |\n";
  }
  md << "\nCells: ";
  for (int k = 1; k < 5; ++k)
    md << cell_kind_name(CellKind(k)) << " " << (results.empty() ? 0 : results[0].by_kind[k].cells)
       << (k < 4 ? ", " : "");
  md << " (of " << (results.empty() ? 0 : results[0].all.cells) << " judged).\n";
  return md.str();
}

void plot_exposure_bench(const std::string& png_path, const std::string& title,
                         const std::vector<ExposureBenchResult>& results, bool overwrite) {
  std::vector<ParetoPoint> points;
  for (const auto& r : results) points.push_back({r.config.series, r.seconds, r.all.p99, r.pareto});
  plot_pareto(png_path, title, "p99 |total / exact - 1|", points,
              {{"fast, sweep, area reads", {200, 60, 60}},
               {"fast, sweep, mip-map reads", {200, 60, 200}},
               {"paper: sampled, mip-map reads", {40, 120, 230}},
               {"sampled, area reads", {60, 170, 60}},
               {"exact", {20, 20, 20}}},
              overwrite);
}

}  // namespace skyview
