#pragma once
// The horizon of a cell, per azimuth, is the elevation angle of the highest terrain seen in
// that direction. Every method that computes it (sampled, march, sweep, raycast) sits behind
// HorizonEngine so they share products, tests and one benchmark.
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "skyview/core/large_pages.h"
#include "skyview/core/progress.h"
#include "skyview/horizon/direction_set.h"
#include "skyview/raster/terrain.h"

namespace skyview {

struct HorizonParams {
  int directions = 16;             // azimuth sectors, clockwise from the first (azimuth_origin)
  int samples = 0;                 // per direction: samples (sampled, default 16), exact near
                                   // steps before the hulls (sweep, default 64); 0 = default
  int far_lines = 1;               // sweep: lines whose hulls a cell asks beyond its near steps,
                                   // 1 (the nearer) or 2 (slopes interpolated by its offset)
  double radius = 0.0;             // search radius in metres; 0 = method default (unlimited for sweep)
  std::uint64_t seed = 0;          // per-cell rotation seed (sampled method)
  bool lower = false;              // also the lowest elevation angle per direction (negative openness)
  bool early_exit = true;          // max-height pyramid termination, results unchanged
  int rays = 256;                  // rays per cell for Monte-Carlo estimates (raycast)
  double refraction = 0.13;        // refraction coefficient k when curvature is on
  std::string curvature = "auto";  // auto | on | off
  AzimuthOrigin azimuth_origin = AzimuthOrigin::north;
  AzimuthSpacing spacing = AzimuthSpacing::uniform;  // grid_lines: 4, 8 or 16, from grid north
  // Radians added to the direction set's rotation (uniform spacing): one direction at the sun's
  // azimuth for a shadow, say.
  double azimuth_offset = 0.0;
};

// Horizons of a window of cells, one plane (window-sized, row-major) per direction: a sweep
// writes a whole direction at a time, and interleaving directions per cell made every one of its
// writes a cache-line read and write.
struct HorizonField {
  int cols = 0, rows = 0, directions = 0;
  // Huge pages where granted: a field of 16 directions at 4000 x 4000 is 1 GB, and the sweep writes
  // the plane of a direction nearer east-west down its columns (see large_pages.h).
  std::vector<float, LargePageAllocator<float>> upper;  // radians, [direction][cell]; NaN on nodata cells
  std::vector<float, LargePageAllocator<float>> lower;  // radians, lowest angle seen; empty unless requested
  double sector_rotation = 0;   // azimuth of sector 0's centre (radians; HorizonParams::azimuth_origin)
  DirectionSet sectors;         // the sectors' azimuths from sector_rotation, and their weights
  std::vector<float> rotation;  // per-cell azimuth offset of the direction set (radians); empty = 0
  // Monte-Carlo estimates some methods (raycast) give directly; empty otherwise.
  std::vector<float> svf_direct;
  std::vector<float> svf_stderr;

  // Sizes the planes (NaN everywhere) and clears the per-cell extras; keeps sector_rotation and
  // sectors, which HorizonEngine::compute sets before the method runs and the method reads
  // (sectors become uniform where their number is not `d`: fields filled by hand).
  void resize(int c, int r, int d, bool with_lower);
  std::size_t cell(int col, int row) const { return static_cast<std::size_t>(row) * cols + col; }
  std::size_t cells() const { return static_cast<std::size_t>(cols) * rows; }
  float* upper_plane(int k) { return upper.data() + cells() * k; }
  float* lower_plane(int k) { return lower.data() + cells() * k; }
  float& upper_at(std::size_t cell, int k) { return upper[cells() * k + cell]; }
  float upper_at(std::size_t cell, int k) const { return upper[cells() * k + cell]; }
  float& lower_at(std::size_t cell, int k) { return lower[cells() * k + cell]; }
  float lower_at(std::size_t cell, int k) const { return lower[cells() * k + cell]; }
  double azimuth(std::size_t cell, int k) const;  // centre azimuth of sector k for a cell
  // Sector k's azimuth for the whole set, before any cell's own rotation.
  double set_azimuth(int k) const { return sector_rotation + sectors.offset[static_cast<std::size_t>(k)]; }
  // The rotation of a cell's sectors from north: the field's and the cell's own.
  double cell_rotation(std::size_t cell) const { return sector_rotation + (rotation.empty() ? 0.0 : rotation[cell]); }
};

// Receives directions [first, first + count) of a window's horizons as planes laid out as in
// HorizonField (one after another; `lower` null unless lowest angles were asked for).
using DirectionBatchSink = std::function<void(int first, int count, const float* upper, const float* lower)>;

class HorizonEngine {
 public:
  virtual ~HorizonEngine() = default;
  virtual std::string_view name() const = 0;
  virtual std::string_view citation() const = 0;
  // Parameters as recorded in output metadata.
  virtual std::map<std::string, std::string> describe() const = 0;
  // Effective search radius in metres (infinity when unlimited).
  virtual double radius() const = 0;
  // The parameters it runs with, the method's defaults filled in.
  virtual const HorizonParams& params() const = 0;
  // The Earth-curvature coefficient c (a target at ground distance d drops by c d²) it applies on
  // `terrain`, with --curvature auto resolved on its reach (by default its radius); 0 where off or
  // not modelled (the ray cast).
  virtual double curvature_coefficient(const Terrain& terrain) const;
  // Fills `out` for the cells of `window`; terrain outside the window (the halo) occludes. Every
  // method reads the same surface: the buffer extended at the raster's edges
  // (extend_at_raster_edges), then its mesh over cell centres.
  void compute(const Terrain& terrain, const Window& window, HorizonField& out, ProgressCounter& progress) const;
  // The same horizons handed to `take` in batches, in order of direction, for products that need
  // not keep them all (SkyViewSums). `out` gets what the method gives besides the planes (rotation,
  // Monte-Carlo svf) and its size; by default compute() fills all of it and `take` gets one batch.
  // Methods that find one direction at a time (the sweep) keep only the directions in progress.
  void compute_directions(const Terrain& terrain, const Window& window, HorizonField& out, ProgressCounter& progress,
                          const DirectionBatchSink& take) const;
  // True where compute_directions holds only the directions in progress (otherwise summing the
  // products as they arrive saves no memory).
  virtual bool streams_directions() const { return false; }

 protected:
  // What each method does, on the extended buffer.
  virtual void compute_window(const Terrain& terrain, const Window& window, HorizonField& out,
                              ProgressCounter& progress) const = 0;
  virtual void compute_window_directions(const Terrain& terrain, const Window& window, HorizonField& out,
                                         ProgressCounter& progress, const DirectionBatchSink& take) const;
};

// Horizons held at a time, in bytes, by what goes by blocks of rows (compute_by_row_blocks).
constexpr std::size_t kHorizonBlockBytes = std::size_t{256} << 20;

// A block of whole rows of a window and its horizons (compute_by_row_blocks).
using RowBlockSink = std::function<void(const Window& block, HorizonField& field)>;

// Rows of `cols` cells whose horizons by `engine` fit in `horizon_bytes` (at least one).
int rows_in_budget(const HorizonEngine& engine, int cols, std::size_t horizon_bytes);

// Computes `window` in blocks of whole rows, each holding about `horizon_bytes` of horizons (and a
// multiple of `row_multiple` rows, at least one), and hands each to `take` before computing the
// next, so that memory does not grow with the number of directions. For methods that find all of
// a cell's directions together: a cell's horizons do not depend on the window it is computed in
// (the rest of the buffer is its halo), so the blocks hold the whole window's bits. (A sweep walks
// the whole buffer for any window: use compute_directions.)
void compute_by_row_blocks(const HorizonEngine& engine, const Terrain& terrain, const Window& window,
                           ProgressCounter& progress, std::size_t horizon_bytes, int row_multiple,
                           const RowBlockSink& take);

// Names accepted by --method, in the order the docs list them.
std::vector<std::string> horizon_method_names();
// Throws skyview::Error for an unknown name or invalid parameters.
std::unique_ptr<HorizonEngine> make_horizon_engine(std::string_view method, const HorizonParams& params);

// The direction set's rotation on `terrain` (radians, clockwise from north): 0 for
// AzimuthOrigin::north, the azimuth of grid north at the raster's centre for AzimuthOrigin::grid.
// The same for every tile and block of a raster.
double direction_set_rotation(AzimuthOrigin origin, const Terrain& terrain);
// The rotation and the sectors `params` ask for on `terrain`: grid lines start on grid north
// whatever the origin, and their azimuths follow the raster's centre Jacobian (shared by every
// tile and block).
AzimuthOrigin direction_set_origin(const HorizonParams& params);
double direction_set_rotation(const HorizonParams& params, const Terrain& terrain);
DirectionSet direction_set(const HorizonParams& params, const Terrain& terrain);

}  // namespace skyview
