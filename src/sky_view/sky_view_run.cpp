// Sky-view products from a method without keeping every direction's horizons: they cost 4 bytes
// per cell and direction (8 with the lowest angles that openness_negative needs), 2 GB for 64 directions
// over 2000 x 2000 cells, where the products themselves are 20 bytes per cell.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "skyview/sky_view/sky_view.h"

namespace skyview {
namespace {

// Rows [r0, r0 + rows) of `to` (a window-sized grid) from the block-sized `from`.
void copy_rows(const Grid<float>& from, Grid<float>& to, int r0) {
  std::memcpy(to.data() + to.index(0, r0), from.data(), sizeof(float) * from.size());
}

// Every direction of `field` (over `window`) raised by the far field, if any.
void raise_all(const FarHorizons* far, const Terrain& terrain, const Window& window, HorizonField& field) {
  if (!far) return;
  for (int k = 0; k < field.directions; ++k) {
    far->raise(terrain, window, field, k, field.upper_plane(k));
    if (!field.lower.empty()) far->lower(terrain, window, field, k, field.lower_plane(k));
  }
}

// Methods that find all of a cell's directions together go by blocks of whole rows, each turned
// into products before the next (compute_by_row_blocks).
SkyViewProducts by_row_blocks(const HorizonEngine& engine, const Terrain& terrain, const Window& window, EdgeMode edge,
                              ProgressCounter& progress, std::size_t horizon_bytes, ProductSet keep,
                              const FarHorizons* far) {
  SkyViewProducts out;
  const double radius = far ? INFINITY : engine.radius();
  compute_by_row_blocks(
      engine, terrain, window, progress, horizon_bytes, 1, [&](const Window& block, HorizonField& field) {
        raise_all(far, terrain, block, field);
        SkyViewProducts part = sky_view_products(terrain, block, field, radius, edge);
        if (block.rows == window.rows) {  // one block: nothing to copy
          out = std::move(part);
          if (!field.svf_direct.empty()) {
            out.svf_montecarlo = Grid<float>(window.cols, window.rows, std::move(field.svf_direct));
            out.svf_montecarlo_stderr = Grid<float>(window.cols, window.rows, std::move(field.svf_stderr));
          }
          return;
        }
        const int r0 = block.row0 - window.row0;
        for (const auto& [product, grid] : kProductGrids) {
          if (!keep.has(product)) continue;
          if (r0 == 0) out.*grid = Grid<float>(window.cols, window.rows);
          copy_rows(part.*grid, out.*grid, r0);
        }
        if (r0 == 0 && !field.svf_direct.empty())
          out.svf_montecarlo = out.svf_montecarlo_stderr = Grid<float>(window.cols, window.rows);
        out.edge_cells += part.edge_cells;
        if (!field.svf_direct.empty()) {
          std::memcpy(out.svf_montecarlo.data() + out.svf_montecarlo.index(0, r0), field.svf_direct.data(),
                      sizeof(float) * field.svf_direct.size());
          std::memcpy(out.svf_montecarlo_stderr.data() + out.svf_montecarlo_stderr.index(0, r0),
                      field.svf_stderr.data(), sizeof(float) * field.svf_stderr.size());
        }
      });
  return out;
}

}  // namespace

SkyViewProducts compute_sky_view(const HorizonEngine& engine, const Terrain& terrain, const Window& window,
                                 EdgeMode edge, ProgressCounter& progress, std::size_t horizon_bytes, ProductSet keep,
                                 const FarHorizons* far) {
  const int n = engine.params().directions;
  if (!engine.streams_directions())
    return by_row_blocks(engine, terrain, window, edge, progress, horizon_bytes, keep, far);
  const double radius = far ? INFINITY : engine.radius();
  // A sweep walks the whole buffer for every direction whatever the window, so it never goes by
  // blocks. Its directions cost 4 bytes per cell each (8 with the lowest angles); once that is
  // twice the running sums (16 directions for all five products), they are summed as they arrive,
  // for about 10% more compute (bench_horizon) and no more wall time.
  HorizonField field;
  const double direction_bytes = engine.params().lower ? 8.0 : 4.0;
  if (direction_bytes * n < 2.0 * SkyViewSums::bytes_per_cell(keep)) {
    engine.compute(terrain, window, field, progress);
    raise_all(far, terrain, window, field);
    return sky_view_products(terrain, window, field, radius, edge);
  }
  SkyViewSums sums(terrain, window, n, keep);
  std::vector<float> raised, lowered;  // a batch's planes moved by the far field
  const DirectionBatchSink take = [&](int first, int count, const float* upper, const float* lower) {
    if (far) {
      const std::size_t cells = static_cast<std::size_t>(window.cols) * window.rows;
      raised.assign(upper, upper + cells * count);
      for (int k = 0; k < count; ++k) far->raise(terrain, window, field, first + k, raised.data() + cells * k);
      upper = raised.data();
      if (lower) {
        lowered.assign(lower, lower + cells * count);
        for (int k = 0; k < count; ++k) far->lower(terrain, window, field, first + k, lowered.data() + cells * k);
        lower = lowered.data();
      }
    }
    sums.add(first, count, upper, lower, field);
  };
  engine.compute_directions(terrain, window, field, progress, take);
  return sums.finish(radius, edge);
}

}  // namespace skyview
