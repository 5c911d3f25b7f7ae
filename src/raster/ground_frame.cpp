#include "skyview/raster/ground_frame.h"

#include <ogr_spatialref.h>
#include <GeographicLib/Geodesic.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

#include "skyview/core/error.h"

namespace skyview {

void Jacobian::pixel_step_for_azimuth(double azimuth, double& dcol, double& drow) const {
  pixel_step(std::sin(azimuth), std::cos(azimuth), dcol, drow);
}

void Jacobian::pixel_step(double east, double north, double& dcol, double& drow) const {
  const double det = a * d - b * c;
  dcol = (d * east - b * north) / det;
  drow = (a * north - c * east) / det;
  // cos(90°) is 6e-17, not 0: snap such residues so that rays along a row or column stay on it
  // (otherwise a ray along row 0 "leaves" the raster at once).
  const double scale = std::max(std::abs(dcol), std::abs(drow));
  if (std::abs(dcol) < 1e-12 * scale) dcol = 0.0;
  if (std::abs(drow) < 1e-12 * scale) drow = 0.0;
}

double Jacobian::metres(double dcol, double drow) const { return std::hypot(a * dcol + b * drow, c * dcol + d * drow); }

double Jacobian::min_cell_size() const { return std::min(std::hypot(a, c), std::hypot(b, d)); }

GroundFrame GroundFrame::uniform(double cell_size) {
  GroundFrame f;
  f.lattice_ = {Jacobian{cell_size, 0, 0, -cell_size}};
  f.description_ = "uniform square cells";
  return f;
}

namespace {

struct OgrTransformDeleter {
  void operator()(OGRCoordinateTransformation* t) const { OGRCoordinateTransformation::DestroyCT(t); }
};

Jacobian affine_jacobian(const GeoReference& g, double unit) {
  const auto& t = g.geotransform;
  return {t[1] * unit, t[2] * unit, t[4] * unit, t[5] * unit};
}

}  // namespace

GroundFrame::GroundFrame(const GeoReference& georef, int width, int height, int lattice_step) : step_(lattice_step) {
  if (!georef.has_geotransform) {
    lattice_ = {affine_jacobian(georef, 1.0)};
    description_ = "no georeferencing: 1 m square cells assumed, the first row to the north";
    return;
  }
  if (georef.crs_wkt.empty()) {
    lattice_ = {affine_jacobian(georef, 1.0)};
    description_ = "no CRS: coordinates assumed to be metres";
    return;
  }
  OGRSpatialReference srs;
  if (srs.importFromWkt(georef.crs_wkt.c_str()) != OGRERR_NONE) throw Error("the raster's CRS cannot be parsed");
  srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  if (!srs.IsProjected() && !srs.IsGeographic()) {
    throw Error("the raster's CRS is neither projected nor geographic (" +
                std::string(srs.GetName() ? srs.GetName() : "?") + "); reproject it first");
  }
  OGRErr err = OGRERR_NONE;
  const double a = srs.GetSemiMajor(&err);
  const double invf = srs.GetInvFlattening(&err);
  const double f = invf == 0.0 ? 0.0 : 1.0 / invf;
  earth_radius_ = a * (1.0 - f / 3.0);
  std::unique_ptr<OGRSpatialReference> geog(srs.CloneGeogCS());
  geog->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<OGRCoordinateTransformation, OgrTransformDeleter> to_geog(
      OGRCreateCoordinateTransformation(&srs, geog.get()));
  if (!to_geog) throw Error("cannot transform the raster's CRS to geographic coordinates");
  geographic_ = srs.IsGeographic();
  const GeographicLib::Geodesic geodesic(a, f);

  lattice_cols_ = std::max(2, (width + step_ - 1) / step_ + 1);
  lattice_rows_ = std::max(2, (height + step_ - 1) / step_ + 1);
  lattice_.resize(static_cast<std::size_t>(lattice_cols_) * lattice_rows_);
  for (int lr = 0; lr < lattice_rows_; ++lr) {
    for (int lc = 0; lc < lattice_cols_; ++lc) {
      // Cell-centre coordinates of the lattice point and its four half-cell neighbours.
      const double col = std::min<double>(lc * step_, width - 1), row = std::min<double>(lr * step_, height - 1);
      const double offsets[5][2] = {{0, 0}, {0.5, 0}, {-0.5, 0}, {0, 0.5}, {0, -0.5}};
      double x[5], y[5];
      for (int i = 0; i < 5; ++i) {
        x[i] = georef.x_of(col + offsets[i][0], row + offsets[i][1]);
        y[i] = georef.y_of(col + offsets[i][0], row + offsets[i][1]);
      }
      if (!to_geog->Transform(5, x, y)) {
        std::ostringstream msg;
        msg << "cell (" << col << ", " << row << ") lies outside the valid area of the raster's CRS";
        throw Error(msg.str());
      }
      for (int i = 0; i < 5; ++i) {
        if (!std::isfinite(y[i]) || std::abs(y[i]) > 90.0) {
          throw Error("the raster extends beyond the poles (latitude " + std::to_string(y[i]) +
                      "); check its geotransform");
        }
      }
      // Central differences of east/north displacement measured at the lattice point.
      double en[4][2];
      for (int i = 1; i < 5; ++i) {
        double s12 = 0, azi1 = 0, azi2 = 0;
        geodesic.Inverse(y[0], x[0], y[i], x[i], s12, azi1, azi2);
        const double az = azi1 * M_PI / 180.0;
        en[i - 1][0] = s12 * std::sin(az);
        en[i - 1][1] = s12 * std::cos(az);
      }
      Jacobian& j = lattice_[static_cast<std::size_t>(lr) * lattice_cols_ + lc];
      j.a = en[0][0] - en[1][0];
      j.c = en[0][1] - en[1][1];
      j.b = en[2][0] - en[3][0];
      j.d = en[2][1] - en[3][1];
    }
  }
  // Collapse to one Jacobian when the grid is uniform to 1e-9 (e.g. a local metric CRS).
  const Jacobian& j0 = lattice_.front();
  const double tol = 1e-9 * j0.min_cell_size();
  const bool uniform = std::all_of(lattice_.begin(), lattice_.end(), [&](const Jacobian& j) {
    return std::abs(j.a - j0.a) < tol && std::abs(j.b - j0.b) < tol && std::abs(j.c - j0.c) < tol &&
           std::abs(j.d - j0.d) < tol;
  });
  if (uniform) {
    lattice_.resize(1);
    lattice_cols_ = lattice_rows_ = 1;
  }
  std::ostringstream d;
  d << (geographic_ ? "geographic" : "projected") << " CRS '" << (srs.GetName() ? srs.GetName() : "?")
    << "'; ground distances and true azimuths on the ellipsoid a=" << a << " 1/f=" << invf << " (GeographicLib)";
  description_ = d.str();
}

Jacobian GroundFrame::at(double col, double row) const {
  if (lattice_.size() == 1) return lattice_.front();
  const double u = std::clamp(col / step_, 0.0, lattice_cols_ - 1.0);
  const double v = std::clamp(row / step_, 0.0, lattice_rows_ - 1.0);
  const int i = std::min(static_cast<int>(u), lattice_cols_ - 2), k = std::min(static_cast<int>(v), lattice_rows_ - 2);
  const double fu = u - i, fv = v - k;
  const auto& p00 = lattice_[static_cast<std::size_t>(k) * lattice_cols_ + i];
  const auto& p10 = lattice_[static_cast<std::size_t>(k) * lattice_cols_ + i + 1];
  const auto& p01 = lattice_[static_cast<std::size_t>(k + 1) * lattice_cols_ + i];
  const auto& p11 = lattice_[static_cast<std::size_t>(k + 1) * lattice_cols_ + i + 1];
  auto mix = [&](double Jacobian::*m) {
    return (1 - fu) * (1 - fv) * p00.*m + fu * (1 - fv) * p10.*m + (1 - fu) * fv * p01.*m + fu * fv * p11.*m;
  };
  return {mix(&Jacobian::a), mix(&Jacobian::b), mix(&Jacobian::c), mix(&Jacobian::d)};
}

}  // namespace skyview
