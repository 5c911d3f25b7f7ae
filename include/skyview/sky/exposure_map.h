#pragma once
// The directional exposure map (Sections 4.2 and 6 of "Solar exposure of complex cities"): sky
// and sun radiance integrated over a period into a map of the upper hemisphere, so that the
// exposure of any surface is the map integrated with a cosine weight over the sky it sees.
//
// Parametrisation (Blinn–Newell longitude/latitude, as in the paper): a width × height raster,
// row 0 at the top. Column x covers azimuth [x, x+1)·2π/width, clockwise from north, so north is
// at the left (and right) edge, east at width/4, south in the middle, west at 3·width/4. Row y
// covers zenith angle [y, y+1)·(π/2)/height: the zenith is the top edge, the horizon the bottom
// edge ("north up" is the left edge: looking up at the sky from below, north at the top of an
// azimuth-ordered strip). Cell (x, y) spans a solid angle (cos θ_y − cos θ_{y+1})·2π/width.
//
// Values are radiant exposure per unit solid angle, Wh m⁻² sr⁻¹: the time integral of radiance.
// Band `direct` holds the sun, splatted over its disc; band `diffuse` the sky without the sun.
#include <array>
#include <span>
#include <vector>

#include "skyview/sky/sky_model.h"

namespace skyview {

enum class ExposureBand { direct, diffuse, global };

// A unit direction in the local ground frame: east, north, up.
using Direction = std::array<double, 3>;

// One time step: the sky's conditions at the step's representative instant, and its length.
struct ExposureStep {
  SkyConditions conditions;
  double hours = 0.5;
};

struct ExposureOptions {
  int width = 512;
  int height = 512;
  // Samples of the sky's γ profile per row (in sin(γ/2), which is even near the sun), each step.
  int gamma_samples = 256;
  // The sun disc is splatted with rings × sectors equal-area samples weighted by its radiance.
  int disc_rings = 3;
  int disc_sectors = 8;
};

class ExposureMap {
 public:
  ExposureMap(int width, int height);  // all zero; throws skyview::Error for sizes < 1

  int width() const { return width_; }
  int height() const { return height_; }
  std::vector<float>& band(ExposureBand b);  // direct or diffuse, row-major
  const std::vector<float>& band(ExposureBand b) const;
  // The value of a cell in a band (global = direct + diffuse).
  double value(ExposureBand b, int x, int y) const;

  double azimuth_of_column(double x) const;  // x + 0.5 = column centre; radians clockwise from north
  double zenith_of_row(double y) const;      // y + 0.5 = row centre; radians
  double cell_solid_angle(int y) const;      // sr
  Direction direction(int x, int y) const;   // cell centre

  // ∫ map · max(0, n·ω) dΩ (Wh/m²): the exposure of a surface with unit normal n (east, north,
  // up). With `horizon` (elevation angles in radians of n equal sectors, sector k centred on
  // azimuth 2πk/n clockwise from north: horizons from a set started on grid north, which
  // HorizonField::sector_rotation records, must be turned back first), cells whose centre lies
  // below the horizon are left out.
  double irradiation(ExposureBand b, const Direction& normal, std::span<const float> horizon = {}) const;

 private:
  int width_, height_;
  std::vector<float> direct_, diffuse_;
  std::vector<double> solid_angle_;
};

// Integrates `sky` over the steps (parallel, oneTBB). Steps whose sun is below the horizon and
// whose sky is dark cost nothing. Throws skyview::Error for bad options or conditions.
ExposureMap integrate_exposure(const SkyModel& sky, std::span<const ExposureStep> steps,
                               const ExposureOptions& options = {});

// Index of the horizon sector containing `azimuth` for `sectors` sectors centred on 2πk/sectors.
int horizon_sector(double azimuth, int sectors);

}  // namespace skyview
