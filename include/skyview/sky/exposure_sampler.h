#pragma once
// The per-surface exposure sampler of Section 6 of "Solar exposure of complex cities" (Eqs. 7–10):
// the exposure a surface receives through the parts of the sky it sees, read from the mip-mapped
// exposure map (ExposurePyramid) with a few samples per direction instead of every map cell.
//
// The sky around a point is cut into N slices of azimuth (one per visibility direction θ, rotated
// as the caller's direction set is). In each slice the point sees the sky between the horizon
// angle h(θ) below and the opening angle h'(θ) above (π/2 where nothing overhangs). That interval
// is covered from h' down by square samples as wide as the slice in map cells (Eq. 7:
// n_s = max(2 (h' − h) t_height N / (π t_width), 1)); the last one takes what remains down to h.
// Each sample reads the pyramid at the level of its height p_height = 2 (h_sup − h_inf) t_height / π
// (Eqs. 8–9: b = max(0, log2 p_height)) and weighs that per-cell average by the n_p = p_height²
// cells it covers (Eq. 10; p_height × slice width for the short last sample).
//
// How a sample is read (SamplerOptions::reads):
// - `mipmap`, the paper's: the pyramid's per-cell average at the sample's centre, bilinear within
//   the two levels nearest b and linear between them (a GPU's trilinear read), times n_p. Its
//   filter reaches up to a block beyond the sample on every side, into the neighbouring slices and
//   below the horizon, and a level-b block is as wide as the slice.
// - `area` (default): the exact integral of the map over the sample's rectangle from a summed-area
//   table of the pyramid's level 0, at the same cost (four reads). The paper set summed-area tables
//   aside because the cosine cannot be summed in advance; the moments below can.
// Either way a sample's cosine comes from the pyramid's first moments Σ value·Ω·ω: n·moment is
// the cosine-weighted exposure of every part of the sky in front of the surface, exact where the
// value times the cosine at the sample's centre is not. Where the surface's own plane crosses a
// slice (a steep roof, a wall foot) a sample is cut into parts at most SamplerOptions::cut_rows map
// rows high, each keeping the azimuths in front of the surface at its own central elevation (the
// plane's trace across a part taken as straight, which the midpoint rule integrates exactly);
// slices wholly behind the surface cost nothing (the paper's discarding of directions facing away).
//
// Nothing here knows rasters: the camera views (skyview render) use it as skyview exposure does.
// A sampler caches, per slice, the samples of an interval open to the zenith for one rotation of the
// direction set; other rotations (a per-cell random turn) and opening angles below π/2 are sampled
// on the fly, with the same result. With `area` reads and cut_rows = 1 the result is the map's
// exact integral over the visible sky (each map row cut by the surface's plane at its own
// elevation), which skyview exposure --method exact uses for the diffuse sky.
#include <span>
#include <vector>

#include "skyview/sky/exposure_pyramid.h"

namespace skyview {

// Radiant exposure received by a surface (Wh/m²), split as the map's bands are.
struct SkyExposure {
  double direct = 0.0, diffuse = 0.0;
  double total() const { return direct + diffuse; }
  SkyExposure& operator+=(const SkyExposure& o) {
    direct += o.direct;
    diffuse += o.diffuse;
    return *this;
  }
};

enum class SamplerReads { mipmap, area };

struct SamplerOptions {
  SamplerReads reads = SamplerReads::area;
  // Tallest sample in map rows; 0: as tall as a slice is wide (Eq. 7's square samples).
  int max_sample_rows = 0;
  // Samples that the surface's own plane crosses are cut into parts at most this high (map rows),
  // each keeping the azimuths in front of the surface at its own elevation.
  int cut_rows = 8;
  // add_gap: parts of each gap between two directions, each under the horizon interpolated at its
  // middle (area reads only).
  int gap_parts = 4;
};

class ExposureSampler {
 public:
  // `directions` slices of equal width 2π/directions, slice k centred on azimuth rotation + 2πk/N
  // (radians, clockwise from north, as ExposureMap's columns). Throws skyview::Error for fewer than
  // one direction or more slices than the map has columns.
  ExposureSampler(const ExposurePyramid& pyramid, int directions, double rotation = 0.0,
                  const SamplerOptions& options = {});

  int directions() const { return directions_; }
  double rotation() const { return rotation_; }

  // Samples (Eq. 7) the slice of direction k takes for an interval [horizon, opening].
  int sample_count(float horizon, float opening) const;

  // Adds to out[i] the exposure of a surface with unit normal normals[i] (east, north, up) through
  // the slice of direction k between elevations `horizon` (h(θ), radians; the map has no sky below
  // 0) and `opening` (h'(θ), π/2 where nothing overhangs; an interval with opening <= horizon is
  // empty). `turn`: the cell's own rotation of the set on top of the sampler's (radians).
  // Up to eight normals share one set of samples (a tilted roof and a pyranometer on it, say).
  void add_slice(int k, float horizon, float opening, std::span<const Direction> normals, std::span<SkyExposure> out,
                 double turn = 0.0) const;

  // The refinement skyview exposure uses: the sky between direction k and the next (the gap of the
  // exact method's beam test), above the horizon interpolated linearly from h0 (at direction k) to
  // h1 (at k + 1) in SamplerOptions::gap_parts parts, each under the horizon at its middle; open to
  // the zenith. Area reads only; the gaps of all directions together cover the sky once.
  void add_gap(int k, float h0, float h1, std::span<const Direction> normals, std::span<SkyExposure> out) const;

  // Σ over all slices for one normal: `horizon` holds h(θ) of every direction, `opening` h'(θ)
  // (empty: π/2 everywhere).
  SkyExposure exposure(const Direction& normal, std::span<const float> horizon, std::span<const float> opening = {},
                       double turn = 0.0) const;

 private:
  struct Moments {
    double m[6] = {0, 0, 0, 0, 0, 0};  // direct east, north, up, then diffuse
  };
  // A mip-map level's moments per map cell (the block's divided by its cells), for `mipmap` reads.
  struct Level {
    int width = 0, height = 0, cell_side = 1;  // cell_side: map cells per block side (2^level)
    std::vector<float> texels;                 // 6 per block, row-major
  };

  // Adds the moments of the map between azimuth columns xa < xb (map cells, any turn, at most the
  // map's width apart) and rows y − height/2 .. y + height/2.
  void read(double xa, double xb, double y, double height, Moments& acc) const;
  void read_mipmap(double xa, double xb, double y, double height, Moments& acc) const;
  void bilinear(int level, double x, double y, double weight, Moments& acc) const;
  // Adds the exact moments of the map between columns xa < xb (x wrapping around) and rows y0 < y1.
  void rectangle(double xa, double xb, double y0, double y1, Moments& acc) const;
  // The moments of a column table (an arc at the sampler's rotation, area reads) from the zenith
  // down to row y.
  Moments column(const std::vector<Moments>& table, double y) const;
  // Adds the moments of the part of rows y0 .. y1 of the arc [from, from + width] in front of the
  // surface with unit normal d, whose horizontal part points to `along` (radians) and is `across`
  // long, in parts at most cut_rows high; parts wholly in front from the arc's column table where
  // one is given.
  void cut(const Direction& d, double along, double across, double from, double width, double y0, double y1,
           const std::vector<Moments>* table, Moments& acc) const;
  // Area reads: adds the exposure through the arc [from, from + width] between elevations low and
  // high for each normal (table: the arc's column table, or none).
  void add_arc(double from, double width, const std::vector<Moments>* table, double low, double high,
               std::span<const Direction> normals, std::span<SkyExposure> out) const;
  double row_of(double elevation) const;

  int directions_;
  double rotation_;
  int map_width_, map_height_;
  double slice_cells_;  // slice width in map cells, t_width / N
  double max_rows_;     // tallest sample, map rows
  double cut_rows_;     // smallest part of a sample the surface's plane crosses
  int gap_parts_;       // parts of a gap between two directions
  SamplerReads reads_;
  std::vector<Level> levels_;  // mipmap reads
  std::vector<double> table_;  // area reads: (height + 1) × (width + 1) × 6 sums from the zenith and azimuth 0
  // Per slice, Σ of its first j full samples of an interval open to the zenith (j = 0 .. all),
  // for the sampler's own rotation.
  std::vector<std::vector<Moments>> cached_;
  std::vector<double> edge_sin_, edge_cos_;        // of each slice's first azimuth at the sampler's rotation
  std::vector<std::vector<Moments>> columns_;      // area reads: per slice, rows 0 .. y summed, y = 0 .. height
  std::vector<std::vector<Moments>> gap_columns_;  // the same per part of each gap (gap k, part j at k·parts + j)
};

}  // namespace skyview
