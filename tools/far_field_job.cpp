#include "far_field_job.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "far_field_pyramid.h"
#include "horizon_job.h"
#include "skyview/core/error.h"
#include "skyview/core/number_text.h"
#include "skyview/tiling/far_field.h"

namespace skyview::cli {

namespace {

// Memory the pyramid may take: an eighth of the run's limit, at least 64 MiB.
std::uint64_t pyramid_budget(const TilePlan& plan) {
  return std::max<std::uint64_t>(std::uint64_t{64} << 20, plan.limit / 8);
}

// The finest first level whose pyramid (maxima and minima, kept for negative openness: 8 bytes a cell,
// 4/3 of the first level's cells in all) fits the budget.
int pyramid_first_level(int width, int height, std::uint64_t budget) {
  int l = 1;
  while (l < 30 && 8.0 * 4 / 3 * std::ceil(width / std::ldexp(1.0, l)) * std::ceil(height / std::ldexp(1.0, l)) >
                       static_cast<double>(budget))
    ++l;
  return l;
}

}  // namespace

void prepare_far_field(HorizonJob& job, double max_error) {
  const TerrainReader& reader = *job.reader;
  const int w = reader.width(), h = reader.height();
  const Jacobian centre = reader.frame().at(w / 2.0, h / 2.0);
  const double diagonal = centre.metres(w, h);  // the whole raster's reach
  // Curvature as the whole run resolves it (auto: on the raster's reach, not the halo's).
  HorizonParams whole = job.engine->params();
  whole.radius = diagonal;
  const double curvature =
      make_horizon_engine(job.engine->name(), whole)->curvature_coefficient(reader.read({w / 2, h / 2, 1, 1}));
  FarFieldSettings s;
  s.cell_m = centre.min_cell_size();
  s.diagonal_m = std::max(centre.metres(1, 1), centre.metres(1, -1));
  s.curvature = curvature;
  // The lowest angles (negative openness) read the levels' minima too.
  const bool lowest = job.engine->params().lower;
  const auto pyramid = run_pyramid(job, pyramid_first_level(w, h, pyramid_budget(job.tiles)), lowest);
  // The smallest halo (in steps of 10%) whose bound meets the error asked; the whole raster's
  // reach where none does (then no far field is left).
  const double error = max_error >= 0 ? max_error : kDefaultFarFieldError;
  double halo = std::max(2 * s.cells_per_level * std::ldexp(s.cell_m, pyramid->first_level()), 4 * s.diagonal_m);
  FarFieldBound bound;
  for (;; halo *= 1.1) {
    if (halo >= diagonal) {
      halo = diagonal;
      break;
    }
    s.halo_m = halo;
    bound = far_field_bound(*pyramid, s, diagonal);
    if (bound.svf <= error) break;
  }
  s.halo_m = halo;
  if (halo >= diagonal) bound = FarFieldBound{};
  // The near field: the sweep at unlimited radius on each tile's window plus halo (linear time,
  // and it sees everything within H and more); other methods at --radius H.
  HorizonParams near = job.engine->params();
  near.radius = job.engine->name() == "sweep" ? 0.0 : halo;
  near.curvature = curvature > 0 ? "on" : "off";
  job.engine = make_horizon_engine(job.engine->name(), near);
  job.far_field = std::make_shared<FarField>(pyramid, s, centre, w, h);
  job.far_halo_m = halo;
  job.tiles.reserved = pyramid->bytes();
  job.tiles.far_field = true;
  job.tiles.halo_m = halo;
  auto& m = job.metadata;
  m["FAR_FIELD"] = halo >= diagonal
                       ? "none: the bound asked needs a halo as wide as the raster's reach, which the "
                         "tiles then hold whole (exact)"
                       : "beyond the halo of " + number_text(halo) +
                             " m: a march over a max-pooled overview pyramid of the whole raster (levels " +
                             std::to_string(far_field_first_level(s, pyramid->first_level())) + " to " +
                             std::to_string(pyramid->last_level()) +
                             ", each level's cells K = " + std::to_string(s.cells_per_level) +
                             " times finer than the distance it is read at); " +
                             "horizons are the higher of the near and far angles per direction";
  m["FAR_FIELD_HALO_M"] = number_text(halo);
  m["FAR_FIELD_BOUND_SVF"] = number_text(bound.svf);
  m["FAR_FIELD_BOUND_SKY_VISIBILITY"] = number_text(bound.sky_visibility);
  m["FAR_FIELD_BOUND_ANGLE_DEG"] = number_text(bound.angle * 180 / M_PI);
  m["FAR_FIELD_BOUND_HORIZON_DEG"] = number_text(bound.horizon * 180 / M_PI);
  if (lowest && halo < diagonal) {
    m["FAR_FIELD_OPENNESS_NEGATIVE"] =
        "the lowest angles beyond the halo from the pyramid's minima (min-pooled), never above the exact ones: "
        "openness_negative within FAR_FIELD_BOUND_HORIZON_DEG degrees";
  }
  m["FAR_FIELD_ERROR_ASKED"] = number_text(error) + (max_error >= 0 ? " (asked)" : " (default)");
  m["FAR_FIELD_PYRAMID_BYTES"] = std::to_string(pyramid->bytes());
}

void add_far_field_option(CLI::App& app, TileRequest& tiling, const std::string& asked_by) {
  tiling.far_field = true;
  app.add_option("--far-field-error", tiling.far_error,
                 "Tiled runs without --radius: the largest svf error the far field beyond each tile's halo may cause "
                 "(a proven bound, docs/tiling.md; horizon angles then err by at most FAR_FIELD_BOUND_HORIZON_DEG, "
                 "recorded in the output); the halo is made as wide as it needs (default: " +
                     asked_by + number_text(kDefaultFarFieldError) + ")")
      ->check(number_above(0.0, 1.0));
}

void check_far_field_option(const CLI::App& app, const HorizonJob& job) {
  if (app.count("--far-field-error") > 0 && !job.far_field)
    throw UsageError(
        "--far-field-error applies to tiled runs without --radius (the far field beyond each tile's halo)");
}

std::string far_field_summary(const HorizonJob& job) {
  if (!job.far_field) return "";
  if (job.metadata.at("FAR_FIELD").starts_with("none")) return ", the halo holds the whole raster: exact";
  char text[160];
  std::snprintf(text, sizeof text,
                ", far field beyond %.4g m with svf error at most %.2g and horizon angles within %.2g degrees",
                job.far_halo_m, std::stod(job.metadata.at("FAR_FIELD_BOUND_SVF")),
                std::stod(job.metadata.at("FAR_FIELD_BOUND_HORIZON_DEG")));
  return text;
}

}  // namespace skyview::cli
