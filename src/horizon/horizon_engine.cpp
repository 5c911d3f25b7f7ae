#include "skyview/horizon/horizon_engine.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "earth_curvature.h"
#include "methods.h"
#include "skyview/core/error.h"

namespace skyview {

void HorizonField::resize(int c, int r, int d, bool with_lower) {
  cols = c;
  rows = r;
  directions = d;
  if (sectors.size() != d) sectors = DirectionSet::uniform(d);
  const std::size_t n = static_cast<std::size_t>(c) * r * d;
  upper.assign(n, std::numeric_limits<float>::quiet_NaN());
  lower.assign(with_lower ? n : 0, std::numeric_limits<float>::quiet_NaN());
  rotation.clear();
  svf_direct.clear();
  svf_stderr.clear();
}

double HorizonField::azimuth(std::size_t cell, int k) const {
  return sectors.offset[static_cast<std::size_t>(k)] + cell_rotation(cell);
}

double direction_set_rotation(AzimuthOrigin origin, const Terrain& terrain) {
  if (origin == AzimuthOrigin::north) return 0.0;
  // One row up (drow = -1) moves east by -b and north by -d.
  const Jacobian j = raster_centre_jacobian(terrain);
  return std::atan2(-j.b, -j.d);
}

AzimuthOrigin direction_set_origin(const HorizonParams& params) {
  return params.spacing == AzimuthSpacing::grid_lines ? AzimuthOrigin::grid : params.azimuth_origin;
}

double direction_set_rotation(const HorizonParams& params, const Terrain& terrain) {
  return direction_set_rotation(direction_set_origin(params), terrain) +
         (params.spacing == AzimuthSpacing::uniform ? params.azimuth_offset : 0.0);
}

DirectionSet direction_set(const HorizonParams& params, const Terrain& terrain) {
  if (params.spacing == AzimuthSpacing::grid_lines)
    return DirectionSet::grid_lines(params.directions, raster_centre_jacobian(terrain));
  return DirectionSet::uniform(params.directions);
}

double HorizonEngine::curvature_coefficient(const Terrain& terrain) const {
  return detail::curvature_coefficient(params(), radius(), terrain.frame.earth_radius());
}

namespace {
// The buffer every method runs on (`inner`: the window in it), and `out`'s direction set there.
Terrain prepare_field(const HorizonParams& params, const Terrain& terrain, const Window& window, Window& inner,
                      HorizonField& out) {
  Terrain extended = extend_at_raster_edges(terrain, window, inner);
  out.sector_rotation = direction_set_rotation(params, extended);
  out.sectors = direction_set(params, extended);
  return extended;
}
}  // namespace

void HorizonEngine::compute(const Terrain& terrain, const Window& window, HorizonField& out,
                            ProgressCounter& progress) const {
  Window inner;
  const Terrain extended = prepare_field(params(), terrain, window, inner, out);
  compute_window(extended, inner, out, progress);
}

void HorizonEngine::compute_directions(const Terrain& terrain, const Window& window, HorizonField& out,
                                       ProgressCounter& progress, const DirectionBatchSink& take) const {
  Window inner;
  const Terrain extended = prepare_field(params(), terrain, window, inner, out);
  compute_window_directions(extended, inner, out, progress, take);
}

void HorizonEngine::compute_window_directions(const Terrain& terrain, const Window& window, HorizonField& out,
                                              ProgressCounter& progress, const DirectionBatchSink& take) const {
  compute_window(terrain, window, out, progress);
  take(0, out.directions, out.upper.data(), out.lower.empty() ? nullptr : out.lower.data());
}

int rows_in_budget(const HorizonEngine& engine, int cols, std::size_t horizon_bytes) {
  const HorizonParams& params = engine.params();
  // Per cell: the planes, and at most a rotation and two Monte-Carlo values besides.
  const std::size_t per_cell =
      sizeof(float) * (static_cast<std::size_t>(params.directions) * (params.lower ? 2 : 1) + 3);
  const std::size_t per_row = std::max<std::size_t>(1, per_cell * static_cast<std::size_t>(std::max(1, cols)));
  return static_cast<int>(std::clamp<std::size_t>(horizon_bytes / per_row, 1, std::size_t{1} << 30));
}

void compute_by_row_blocks(const HorizonEngine& engine, const Terrain& terrain, const Window& window,
                           ProgressCounter& progress, std::size_t horizon_bytes, int row_multiple,
                           const RowBlockSink& take) {
  const std::size_t multiple = static_cast<std::size_t>(std::max(1, row_multiple));
  const std::size_t fit = static_cast<std::size_t>(rows_in_budget(engine, window.cols, horizon_bytes));
  const std::size_t rows = std::max<std::size_t>(1, fit / multiple) * multiple;
  const int block_rows = static_cast<int>(std::min<std::size_t>(rows, static_cast<std::size_t>(window.rows)));
  for (int r0 = 0; r0 < window.rows; r0 += block_rows) {
    progress.stop_if_cancelled();
    const Window block{window.col0, window.row0 + r0, window.cols, std::min(block_rows, window.rows - r0)};
    HorizonField field;
    engine.compute(terrain, block, field, progress);
    take(block, field);
  }
}

std::vector<std::string> horizon_method_names() { return {"sampled", "march", "sweep", "raycast"}; }

std::unique_ptr<HorizonEngine> make_horizon_engine(std::string_view method, const HorizonParams& params) {
  if (params.directions < 1 || params.directions > 4096) throw UsageError("--directions must be between 1 and 4096");
  if (!(params.radius >= 0.0) || std::isinf(params.radius))
    throw UsageError("--radius must be a positive number of metres");
  if (!std::isfinite(params.azimuth_offset)) throw Error("the azimuth offset of the directions must be finite");
  if (params.spacing == AzimuthSpacing::grid_lines) {
    check_grid_lines_count(params.directions);
    if (method == "sampled")
      throw UsageError(
          "--azimuths grid-lines needs fixed directions: the sampled method turns each cell's set at random");
  }
  if (method == "sampled") return detail::make_sampled_engine(params);
  if (method == "march") return detail::make_march_engine(params);
  if (method == "sweep") return detail::make_sweep_engine(params);
  if (method == "raycast") return detail::make_raycast_engine(params);
  std::string known;
  for (const auto& n : horizon_method_names()) known += (known.empty() ? "" : ", ") + n;
  throw Error("unknown method '" + std::string(method) + "' (known: " + known + ")");
}

}  // namespace skyview
