#include "skyview/benchmark/method_benchmark.h"

#include "skyview/benchmark/pareto_plot.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>

#include "skyview/core/error.h"
#include "skyview/raster/raster_io.h"

namespace skyview {

std::string BenchConfig::label() const {
  std::ostringstream s;
  s << method << " d=" << params.directions;
  if (method == "sampled") s << " s=" << params.samples;
  if (params.spacing == AzimuthSpacing::grid_lines)
    s << " grid lines";  // every direction exact: no near steps, no far lines
  else if (method == "sweep")
    s << " near=" << params.samples << (params.far_lines == 1 ? " 1 line" : " 2 lines");
  if (method == "sampled" || method == "march") s << " r=" << (params.radius == 0 ? 500 : params.radius);
  return s.str();
}

std::vector<BenchConfig> default_bench_grid(const std::vector<std::string>& methods) {
  if (methods.empty()) throw Error("no method given (sampled, march, sweep)");
  std::vector<BenchConfig> grid;
  std::set<std::string> seen;
  for (const std::string& m : methods) {
    if (!seen.insert(m).second) throw Error("method '" + m + "' given twice");
    if (m == "sampled") {
      for (int d : {8, 16, 32}) {
        for (int s : {8, 16, 32, 64}) {
          BenchConfig c{m, {}};
          c.params.directions = d;
          c.params.samples = s;
          grid.push_back(c);
        }
      }
    } else if (m == "sweep") {
      // 128 and 256 directions: finer sectors than the 64-direction reference can judge, for the
      // error against the continuous svf (svf_continuous), which 64 sectors alone miss by about 0.01
      // at p99 in cities.
      for (int lines : {2, 1}) {
        for (int d : {8, 16, 32, 64, 128, 256}) {
          for (int near : {8, 16, 32, 64, 128}) {
            BenchConfig c{m, {}};
            c.params.directions = d;
            c.params.samples = near;
            c.params.far_lines = lines;
            grid.push_back(c);
          }
        }
      }
      // 16 directions along the grid's lines, each found exactly (--azimuths grid-lines).
      BenchConfig c{m, {}};
      c.params.directions = 16;
      c.params.spacing = AzimuthSpacing::grid_lines;
      grid.push_back(c);
    } else if (m == "march") {
      for (int d : {8, 16, 32, 64}) {
        BenchConfig c{m, {}};
        c.params.directions = d;
        grid.push_back(c);
      }
    } else {
      throw Error("unknown method '" + m + "' (sampled, march, sweep)");
    }
  }
  for (auto& c : grid) c.params.curvature = "off";  // the reference has no curvature
  return grid;
}

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

BenchReference compute_reference(const Terrain& terrain, int directions, AzimuthOrigin origin) {
  HorizonParams p;
  p.directions = directions;
  p.azimuth_origin = origin;
  p.rays = 0;
  p.curvature = "off";
  auto engine = make_horizon_engine("raycast", p);
  HorizonField field;
  ProgressCounter progress;
  const auto t0 = std::chrono::steady_clock::now();
  engine->compute(terrain, Window::whole(terrain), field, progress);
  BenchReference ref;
  ref.products = sky_view_products(terrain, Window::whole(terrain), field, engine->radius(), EdgeMode::open);
  ref.seconds = seconds_since(t0);
  ref.directions = directions;
  ref.azimuth_origin = origin;
  SvfCheckOptions o;
  o.azimuth_origin = origin;
  o.cells = kBenchContinuousCells;
  o.directions = kBenchContinuousSectors / 4;  // its four-times-finer sectors are the ones compared
  ref.continuous = std::make_shared<const SvfCheck>(terrain, o);
  return ref;
}

std::vector<BenchResult> run_bench(const Terrain& terrain, const std::vector<BenchConfig>& configs,
                                   const BenchReference& reference, int repeats,
                                   const std::function<void(const BenchResult&)>& on_result,
                                   std::vector<BenchSkipped>* skipped) {
  // Rounds over every configuration, not each configuration's runs in a row: the shared machine's
  // speed drifts by up to 2x within one bench (on Dec 3 the two-line sweeps, run first, timed 1.8x
  // slower on city.tif than in a run minutes before, while the one-line rows after them matched),
  // and rounds spread the drift over all configurations alike.
  const int rounds = std::max(1, repeats);
  for (const BenchConfig& config : configs) {
    if (config.params.azimuth_origin != reference.azimuth_origin)
      throw Error("bench: a configuration's sectors start elsewhere than the reference's (internal error)");
  }
  std::vector<std::unique_ptr<HorizonEngine>> engines;
  for (const BenchConfig& config : configs) engines.push_back(make_horizon_engine(config.method, config.params));
  std::vector<BenchResult> results(configs.size());
  std::vector<std::vector<double>> times(configs.size());
  std::vector<bool> runs(configs.size(), true);
  for (int round = 0; round < rounds; ++round) {
    for (std::size_t i = 0; i < configs.size(); ++i) {
      if (!runs[i]) continue;
      HorizonField field;
      ProgressCounter progress;
      const auto t0 = std::chrono::steady_clock::now();
      try {
        engines[i]->compute(terrain, Window::whole(terrain), field, progress);
      } catch (const Error& e) {
        if (!skipped || round > 0) throw;  // a refusal comes on the first run or never
        skipped->push_back({configs[i].label(), e.what()});
        runs[i] = false;
        continue;
      }
      const SkyViewProducts products =
          sky_view_products(terrain, Window::whole(terrain), field, engines[i]->radius(), EdgeMode::open);
      times[i].push_back(seconds_since(t0));
      BenchResult& r = results[i];
      if (round == 0) {  // the errors are the same every round
        r.config = configs[i];
        r.radius = engines[i]->radius();
        r.svf = compare_to_reference(products.svf, reference.products.svf);
        r.sky_visibility = compare_to_reference(products.sky_visibility, reference.products.sky_visibility);
        if (reference.continuous) r.svf_continuous = reference.continuous->measure(products.svf).error_fine;
      }
      if (round == rounds - 1) {
        std::sort(times[i].begin(), times[i].end());
        const std::size_t n = times[i].size();  // the median: of an even count, the middle two's mean
        r.seconds = n % 2 == 1 ? times[i][n / 2] : 0.5 * (times[i][n / 2 - 1] + times[i][n / 2]);
        r.cell_dirs_per_second =
            static_cast<double>(terrain.width()) * terrain.height() * configs[i].params.directions / r.seconds;
        if (on_result) on_result(r);
      }
    }
  }
  std::vector<BenchResult> ran;
  for (std::size_t i = 0; i < configs.size(); ++i) {
    if (runs[i]) ran.push_back(std::move(results[i]));
  }
  mark_pareto_front(ran);
  return ran;
}

void mark_pareto_front(std::vector<BenchResult>& results) {
  for (auto& r : results) {
    r.pareto = std::none_of(results.begin(), results.end(), [&](const BenchResult& o) {
      return &o != &r && o.seconds <= r.seconds && o.judged_p99() <= r.judged_p99() &&
             (o.seconds < r.seconds || o.judged_p99() < r.judged_p99());
    });
  }
}

namespace {

nlohmann::json stats_json(const ErrorStats& e) {
  return {{"rmse", e.rmse},
          {"bias", e.bias},
          {"p99_abs", e.p99},
          {"max_abs", e.max_abs},
          {"share_above_0_01", e.share_above},
          {"cells", e.cells}};
}

}  // namespace

nlohmann::json bench_to_json(const std::string& raster, const BenchReference& ref, const std::vector<BenchResult>& rs) {
  nlohmann::json j;
  j["raster"] = raster;
  j["reference"] = {{"method", "raycast"}, {"directions", ref.directions}, {"seconds", ref.seconds}};
  j["azimuth_origin"] = azimuth_origin_name(ref.azimuth_origin);
  if (ref.continuous) {
    j["continuous_reference"] = {{"method", "march over every crossing (svf check)"},
                                 {"sectors", ref.continuous->fine_directions()},
                                 {"cells", ref.continuous->cells().size()},
                                 {"seconds", ref.continuous->seconds()}};
  }
  for (const auto& r : rs) {
    nlohmann::json row = {{"method", r.config.method},
                          {"label", r.config.label()},
                          {"directions", r.config.params.directions},
                          {"azimuths", azimuth_spacing_name(r.config.params.spacing)},
                          {"samples", r.config.params.samples},
                          {"radius_m", std::isinf(r.radius) ? nlohmann::json() : nlohmann::json(r.radius)},
                          {"reference_limited", ref.limits(r.config)},
                          {"seconds", r.seconds},
                          {"cell_directions_per_second", r.cell_dirs_per_second},
                          {"pareto", r.pareto},
                          {"svf", stats_json(r.svf)},
                          {"sky_visibility", stats_json(r.sky_visibility)}};
    if (ref.continuous) row["svf_continuous"] = stats_json(r.svf_continuous);
    if (r.config.method == "sweep") row["far_lines"] = r.config.params.far_lines;
    j["results"].push_back(row);
  }
  return j;
}

std::string bench_to_markdown(const std::string& raster, const BenchReference& ref,
                              const std::vector<BenchResult>& rs) {
  std::ostringstream s;
  s << "Raster `" << raster << "`; reference: raycast, " << ref.directions << " directions (" << std::fixed
    << std::setprecision(1) << ref.seconds << " s); first sector on "
    << (ref.azimuth_origin == AzimuthOrigin::grid ? "grid" : "true")
    << " north, for every row. Errors are value − reference over all valid cells.";
  if (ref.continuous) {
    s << " `cont. p99`: svf p99 against exact horizons in " << ref.continuous->fine_directions() << " sectors at "
      << ref.continuous->cells().size()
      << " random cells, near the continuous svf, sector error included; the Pareto front is judged by it.";
  }
  if (std::any_of(rs.begin(), rs.end(), [&](const BenchResult& r) { return ref.limits(r.config); }))
    s << " † marks configurations with more directions than the reference: their errors include the reference's "
         "own sector error.";
  s << "\n\n";
  const bool cont = ref.continuous != nullptr;
  s << "| method | time (s) | M cell-dirs/s | svf RMSE | svf bias | svf p99 | svf max | share >0.01 | vis p99 | "
    << (cont ? "cont. p99 | " : "") << "Pareto |\n";
  s << "|---|---:|---:|---:|---:|---:|---:|---:|---:|" << (cont ? "---:|" : "") << ":---:|\n";
  for (const auto& r : rs) {
    s << "| " << r.config.label() << (ref.limits(r.config) ? " †" : "") << " | " << std::setprecision(3) << r.seconds
      << " | " << std::setprecision(1) << r.cell_dirs_per_second / 1e6 << " | " << std::setprecision(4) << r.svf.rmse
      << " | " << r.svf.bias << " | " << r.svf.p99 << " | " << r.svf.max_abs << " | " << std::setprecision(3)
      << r.svf.share_above << " | " << std::setprecision(4) << r.sky_visibility.p99 << " | ";
    if (cont) s << r.svf_continuous.p99 << " | ";
    s << (r.pareto ? "●" : "") << " |\n";
  }
  return s.str();
}

void plot_bench(const std::string& png_path, const std::string& title, const std::vector<BenchResult>& results,
                bool overwrite) {
  // One series per method, and the sweep's far-line variants and its grid-line directions apart.
  auto series = [](const BenchConfig& c) {
    if (c.method != "sweep") return c.method;
    if (c.params.spacing == AzimuthSpacing::grid_lines) return std::string("sweep, grid lines");
    return std::string(c.params.far_lines == 1 ? "sweep, 1 far line" : "sweep, 2 far lines");
  };
  std::vector<ParetoPoint> points;
  for (const auto& r : results) points.push_back({series(r.config), r.seconds, r.judged_p99(), r.pareto});
  const bool continuous = std::any_of(results.begin(), results.end(), [](auto& r) { return r.has_continuous(); });
  plot_pareto(png_path, title, continuous ? "p99 |svf - continuous svf|" : "p99 |svf error|", points,
              {{"march", {60, 170, 60}},
               {"sampled", {40, 120, 230}},
               {"sweep, 1 far line", {200, 60, 200}},
               {"sweep, 2 far lines", {200, 60, 60}},
               {"sweep, grid lines", {20, 20, 20}}},
              overwrite);
}

}  // namespace skyview
