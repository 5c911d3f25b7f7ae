#pragma once
// The azimuths a horizon field holds and how much each weighs in sums over azimuth (svf, sky
// visibility, openness). Uniform sectors are the default. Along grid lines the directions follow
// the raster's digital lines: its columns, rows, diagonals and, with 16 directions, the lines of
// slope 1/2 (pixel steps such as (1, 2)). There every cell lies on a line through cell centres, so
// the sweep finds each horizon exactly when it pushes the cell, with no near field and no search
// (docs/sky_view.md). Those directions are unevenly spaced (on square cells 26.57° apart around
// an axis, 18.43° around a diagonal), so each has its own weight: the shares that integrate the
// low harmonics of azimuth exactly (src/horizon/direction_set.cpp). Where a set starts is its origin.
#include <string_view>
#include <vector>

#include "skyview/raster/ground_frame.h"

namespace skyview {

// Where the direction set's first sector points. `north`: true north, so sector k is centred on
// azimuth 360 k / N. `grid`: up the raster's columns at its centre (grid north; a UTM raster's is
// off true north by the meridian convergence), so that the sectors at multiples of 45° run along
// its columns, rows and (square cells) diagonals, where the sweep's lines pass through cell
// centres and it finds the horizons exactly and about 2.8 times faster (docs/benchmarks.md). Products summed over
// azimuth (svf, sky visibility, openness) do not depend on the choice beyond the sectors' own error.
enum class AzimuthOrigin { north, grid };
// "north" or "grid", as --azimuth-origin and the outputs' metadata spell it; the parser throws
// skyview::Error for any other name.
const char* azimuth_origin_name(AzimuthOrigin origin);
AzimuthOrigin azimuth_origin_named(std::string_view name);

// How the directions are spread: `uniform` (2πk/N from the set's rotation) or `grid_lines`
// (4, 8 or 16 digital lines of the grid, from grid north).
enum class AzimuthSpacing { uniform, grid_lines };
// "uniform" or "grid-lines", as --azimuths and the outputs' metadata spell it; the parser throws
// skyview::Error for any other name.
const char* azimuth_spacing_name(AzimuthSpacing spacing);
AzimuthSpacing azimuth_spacing_named(std::string_view name);

// Azimuth of sector k's centre in N uniform sectors (radians, clockwise from the set's origin;
// DirectionSet::uniform).
inline double sector_azimuth(int k, int directions) { return 2.0 * 3.14159265358979323846 * k / directions; }

struct DirectionSet {
  // Sector k's azimuth from the set's rotation (radians, clockwise), rising from 0 below 2π.
  std::vector<double> offset;
  // Its weight in sums over azimuth, the share of the circle it stands for: 1/N for uniform
  // sectors; for grid lines those that sum cos jφ and sin jφ (j up to N/2) as exactly as the
  // directions allow. The shares add up to one.
  std::vector<double> share;

  int size() const { return static_cast<int>(offset.size()); }
  bool is_uniform() const;  // every share equal (to 1e-12)

  static DirectionSet uniform(int n);
  // The 4, 8 or 16 digital lines of a grid whose pixel steps map to the ground by `j`, from the
  // direction of a step up the columns (grid north); throws skyview::Error for other counts.
  static DirectionSet grid_lines(int n, const Jacobian& j);
};

// Throws skyview::Error unless AzimuthSpacing::grid_lines supports `directions` (4, 8 or 16).
void check_grid_lines_count(int directions);

}  // namespace skyview
