#include "skyview/sky_view/svf_run.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>

#include "skyview/core/error.h"
#include "skyview/core/number_text.h"
#include "skyview/sky_view/svf_check.h"

namespace skyview {

namespace {

// Cells the svf check samples by default with --max-error: the p99 of 1000 cells is within about
// 20% of the raster's, and their exact horizons cost a fraction of a second on the samples.
constexpr int kDefaultCheckCells = 1000;

std::string four_digits(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4f", v);
  return text;
}

// The fewest cells whose p99 bounds the raster's with 95% confidence (299: 0.99^n must fall
// under 0.05); fewer cells give a p99 but no bound.
int cells_for_a_bound() {
  static const int cells = [] {
    int n = 1;
    while (quantile_upper_rank(n, 0.99, 0.95) == 0) ++n;
    return n;
  }();
  return cells;
}

std::string bound_text(double bound) {
  return std::isnan(bound) ? "none under " + std::to_string(cells_for_a_bound()) + " cells" : four_digits(bound);
}

int cells_to_check(const SvfRequest& r) {
  return r.check_cells >= 0 ? r.check_cells : (r.horizon.max_error >= 0.0 ? kDefaultCheckCells : 0);
}

SvfCheckOptions check_options(const HorizonSetup& s, const Terrain& terrain, int cells) {
  SvfCheckOptions c;
  c.cells = cells;
  c.directions = std::max(64, s.engine->params().directions);
  c.curvature = s.engine->curvature_coefficient(terrain);
  c.azimuth_origin = s.engine->params().azimuth_origin;
  return c;
}

void record_check(std::map<std::string, std::string>& m, const SvfCheck& check, const SvfCheckResult& r) {
  m["SVF_CHECK_CELLS"] = std::to_string(r.error.cells);
  m["SVF_CHECK_P99"] = number_text(r.error.p99);
  if (std::isnan(r.p99_upper95)) {
    m.erase("SVF_CHECK_P99_UPPER95");  // under 300 cells bound no p99
  } else {
    m["SVF_CHECK_P99_UPPER95"] = number_text(r.p99_upper95);
  }
  m["SVF_CHECK_MAX"] = number_text(r.error.max_abs);
  m["SVF_CHECK_RMSE"] = number_text(r.error.rmse);
  m["SVF_CHECK_BIAS"] = number_text(r.error.bias);
  m["SVF_CHECK_P99_FINE"] = number_text(r.error_fine.p99);
  if (std::isnan(r.fine_p99_upper95)) {
    m.erase("SVF_CHECK_P99_FINE_UPPER95");
  } else {
    m["SVF_CHECK_P99_FINE_UPPER95"] = number_text(r.fine_p99_upper95);
  }
  m["SVF_CHECK_BASIS"] =
      "svf - exact svf on " + std::string(r.exhaustive ? "every valid cell" : "random valid cells") +
      " (the march over every row and column crossing to the raster's edge, " + std::to_string(check.directions()) +
      " sectors, the run's curvature); P99_UPPER95 bounds the raster's p99 with 95% confidence; P99_FINE is against " +
      std::to_string(check.fine_directions()) +
      " sectors, near the continuous svf, and adds the sectors' own error (what --max-error is held to)";
}

}  // namespace

const std::vector<SvfProductInfo>& svf_products() {
  static const std::vector<SvfProductInfo> products = {
      {"svf", "1", "1 - mean sin^2(max(h,0)); cosine-weighted, horizontal", Product::svf},
      {"svf_surface", "1", "view factor of the tilted cell surface (Horn normal) to the unobstructed sky",
       Product::svf_surface},
      {"sky_visibility", "1", "1 - mean sin(max(h,0)); solid-angle fraction of the hemisphere",
       Product::sky_visibility},
      {"openness_positive", "degree", "mean zenith angle of the horizon (Yokoyama 2002)", Product::openness_positive},
      {"openness_negative", "degree", "mean nadir angle of the lowest terrain (Yokoyama 2002)",
       Product::openness_negative},
  };
  return products;
}

std::string default_svf_products() {
  std::string list;
  for (const SvfProductInfo& p : svf_products()) {
    if (!list.empty()) list += ',';
    list += p.name;
  }
  return list;
}

std::vector<const SvfProductInfo*> parse_svf_products(const std::string& list) {
  std::vector<const SvfProductInfo*> out;
  std::stringstream in(list);
  for (std::string name; std::getline(in, name, ',');) {
    const auto& all = svf_products();
    const auto it = std::find_if(all.begin(), all.end(), [&](const SvfProductInfo& p) { return name == p.name; });
    if (it == all.end()) throw Error("unknown product '" + name + "' (" + default_svf_products() + ")");
    if (std::find(out.begin(), out.end(), &*it) != out.end()) throw Error("'" + name + "' given twice");
    out.push_back(&*it);
  }
  if (out.empty()) throw Error("no product given");
  return out;
}

HorizonRequest default_svf_horizon_request() {
  HorizonRequest r;
  r.azimuth_origin = "grid";
  return r;
}

void check_svf_request(const SvfRequest& r) {
  parse_svf_products(r.products);
  if (r.check_cells < -1 || r.check_cells > 10000000)
    throw UsageError("--check-cells " + std::to_string(r.check_cells) + " is not in [0, 10000000]");
  const int n_check = cells_to_check(r);
  // --max-error is met by a 95% bound of the p99, which fewer cells cannot give (a raster with
  // fewer valid cells is checked whole, and needs none).
  if (r.horizon.max_error >= 0.0 && n_check > 0 && n_check < cells_for_a_bound()) {
    throw UsageError("--check-cells " + std::to_string(n_check) +
                     " cannot show that --max-error is met: a 95% bound of " + "the p99 needs " +
                     std::to_string(cells_for_a_bound()) + " cells or more (or 0: no check)");
  }
  if (n_check > 0 && r.horizon.max_error < 0.0 && r.horizon.params.directions > kSvfCheckMaxDirections) {
    throw UsageError("--check-cells measures against the run's own sectors, at most " +
                     std::to_string(kSvfCheckMaxDirections) + " (this run has --directions " +
                     std::to_string(r.horizon.params.directions) + "); use fewer directions or leave it out");
  }
}

SvfResult run_svf(const Terrain& terrain, const SvfRequest& request, HorizonSetup& setup,
                  const std::function<void(const std::function<void(ProgressCounter&)>&)>& run, const Window& asked) {
  check_svf_request(request);
  const Window window = asked.cols > 0 && asked.rows > 0 ? asked : Window::whole(terrain);
  const std::vector<const SvfProductInfo*> chosen = parse_svf_products(request.products);
  // Only the products written are summed; negative openness is the only one that needs the lowest
  // angles, a second walk.
  ProductSet keep = ProductSet::none();
  for (const SvfProductInfo* c : chosen) keep.add(c->product);
  const int n_check = cells_to_check(request);
  if (n_check > 0) keep.add(Product::svf);
  if (keep.has(Product::openness_negative) != setup.engine->params().lower) {
    HorizonParams p = setup.engine->params();
    p.lower = keep.has(Product::openness_negative);
    setup.engine = make_horizon_engine(setup.engine->name(), p);
  }
  SvfResult out;
  // Horizons are held a part at a time (compute_sky_view), so memory does not grow with the
  // number of directions.
  SkyViewProducts p;
  std::optional<SvfCheck> check;
  std::string tried;  // --max-error's runs and what the check measured
  auto& m = setup.metadata;
  for (;;) {
    run([&](ProgressCounter& progress) {
      p = compute_sky_view(*setup.engine, terrain, window, setup.edge, progress, kHorizonBlockBytes, keep,
                           request.far_field.get());
    });
    if (n_check == 0) break;
    const SvfCheckOptions co = check_options(setup, terrain, n_check);
    if (!check || check->directions() != co.directions || check->curvature() != co.curvature)
      check.emplace(terrain, co);
    const SvfCheckResult r = check->measure(p.svf);
    record_check(m, *check, r);
    char line[512];
    std::snprintf(line, sizeof line,
                  "svf check on %lld cells (%.1f s): p99 %s (95%% bound %s), max %s, bias %+.4f against exact "
                  "horizons in %d sectors; p99 %s (95%% bound %s) against %d sectors, near the continuous svf",
                  static_cast<long long>(r.error.cells), check->seconds(), four_digits(r.error.p99).c_str(),
                  bound_text(r.p99_upper95).c_str(), four_digits(r.error.max_abs).c_str(), r.error.bias,
                  check->directions(), four_digits(r.error_fine.p99).c_str(), bound_text(r.fine_p99_upper95).c_str(),
                  check->fine_directions());
    out.messages.emplace_back(line);
    if (!setup.choice) break;
    // The request is met when the raster's p99 against the near-continuous svf (the finer
    // sectors, the calibration's basis) is within it with 95% confidence: the bound, not the
    // sample's own p99, which on a 100² city read 0.0092 where all cells gave 0.0105.
    const double requested = request.horizon.max_error;
    const double bound = std::isnan(r.fine_p99_upper95) ? r.error_fine.max_abs : r.fine_p99_upper95;
    tried += (tried.empty() ? "" : "; ") + describe_choice(*setup.choice) + ": p99 " + four_digits(r.error_fine.p99) +
             ", bound " + four_digits(bound);
    m["MAX_ERROR_MEASURED_P99"] = number_text(r.error_fine.p99);
    m["MAX_ERROR_MEASURED_BOUND"] = number_text(bound);
    m["MAX_ERROR_MET"] =
        bound > requested ? "no" : (r.exhaustive ? "yes (every valid cell checked)" : "yes (with 95% confidence)");
    m["MAX_ERROR_TRIED"] = tried;
    // The parts of the error, where the check's sectors are the run's own.
    MeasuredError measured;
    measured.bound = bound;
    if (check->directions() == setup.choice->params.directions) {
      measured.method_p99 = r.error.p99;
      measured.sector_p99 = check->sector_p99();
    }
    const auto next = choose_after_measurement(requested, setup.choice->entry, measured, setup.choice->params);
    if (!next) {
      if (bound > requested) {
        out.warnings.push_back("--max-error " + number_text(requested) + " not met: the svf check bounds the p99 by " +
                               four_digits(bound) + " with " + describe_choice(*setup.choice) +
                               ", the most accurate calibrated choice");
      }
      break;
    }
    out.messages.push_back("--max-error " + number_text(requested) + ": the svf check bounds the p99 by " +
                           four_digits(bound) + " with " + describe_choice(*setup.choice) + "; running again with " +
                           describe_choice(*next));
    AccuracyChoice chosen_next = *next;
    chosen_next.params.lower = keep.has(Product::openness_negative);
    use_choice(setup, chosen_next, requested, terrain);
  }
  record_edge_cells(setup, p.edge_cells);
  for (const SvfProductInfo* c : chosen)
    out.bands.push_back({c->name, c->unit, {{"DEFINITION", c->definition}}, std::move(p.*product_grid(c->product))});
  if (!p.svf_montecarlo.values().empty()) {
    out.bands.push_back({"svf_montecarlo",
                         "1",
                         {{"DEFINITION", "fraction of stratified cosine-weighted rays that reach the sky"}},
                         std::move(p.svf_montecarlo)});
    out.bands.push_back({"svf_montecarlo_stderr",
                         "1",
                         {{"DEFINITION", "binomial standard error of svf_montecarlo (an upper bound)"}},
                         std::move(p.svf_montecarlo_stderr)});
  }
  out.metadata = setup.metadata;
  return out;
}

}  // namespace skyview
