#pragma once
// True ground geometry of a raster: for any cell, the 2x2 Jacobian that turns a step in
// pixel space into metres east and north on the ellipsoid. With it, distances and
// azimuths are the same whether the terrain is stored in UTM, in US feet or in degrees.
#include <memory>
#include <string>
#include <vector>

#include "skyview/raster/georeference.h"

namespace skyview {

struct Jacobian {
  // east = a*dcol + b*drow; north = c*dcol + d*drow  (metres per pixel)
  double a = 1, b = 0, c = 0, d = -1;

  // The pixel step (dcol, drow) that moves one metre along the true azimuth (radians,
  // clockwise from north).
  void pixel_step_for_azimuth(double azimuth, double& dcol, double& drow) const;
  // The same for the azimuth whose sine and cosine are `east` and `north`.
  void pixel_step(double east, double north, double& dcol, double& drow) const;
  // Ground distance in metres of a pixel offset.
  double metres(double dcol, double drow) const;
  // Smallest ground size of a pixel step along either axis, metres.
  double min_cell_size() const;
};

class GroundFrame {
 public:
  // Samples the Jacobian on a coarse lattice (every `lattice_step` cells) and interpolates
  // between; a projected CRS in metres without distortion collapses to one constant.
  // Throws skyview::Error when the CRS cannot be turned into geographic coordinates.
  GroundFrame(const GeoReference& georef, int width, int height, int lattice_step = 64);

  // A frame with square cells of `cell_size` metres, north up (synthetic rasters, tests).
  static GroundFrame uniform(double cell_size);

  Jacobian at(double col, double row) const;
  bool is_geographic() const { return geographic_; }
  bool is_constant() const { return lattice_.size() == 1; }
  // Human-readable description for metadata ("projected, metre", "geographic (ellipsoid ...)").
  const std::string& description() const { return description_; }
  // Radius of the ellipsoid's mean sphere, for the curvature correction.
  double earth_radius() const { return earth_radius_; }

 private:
  GroundFrame() = default;
  int lattice_cols_ = 1, lattice_rows_ = 1, step_ = 64;
  std::vector<Jacobian> lattice_;
  bool geographic_ = false;
  std::string description_;
  double earth_radius_ = 6371008.8;
};

}  // namespace skyview
