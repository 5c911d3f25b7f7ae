#pragma once
// Fish-eye projections and the image frame of an upward-looking hemisphere. A projection maps the
// zenith angle θ of a direction to its distance from the image centre, here as a fraction r of the
// radius at θ = 90°:
//   equidistant    r = θ / (π/2)                 (equiangular; most fish-eye converters, FC-E8/E9)
//   equisolid      r = √2 sin(θ/2)               (equal-area)
//   orthographic   r = sin θ                     (the cosine-weighted svf is the sky's share of the disc)
//   stereographic  r = tan(θ/2)                  (conformal)
// Orientation: as an upward-looking camera sees the sky, north at the top and east on the LEFT
// (azimuth φ clockwise from north seen from above turns anticlockwise in the image); `mirror` puts
// east on the right, as a map of the sky seen from above.
#include <string>
#include <string_view>

namespace skyview {

enum class Projection { equidistant, equisolid, orthographic, stereographic };

// "equidistant", ... as --projection spells them; the parser throws skyview::Error for others.
const char* projection_name(Projection p);
Projection projection_named(std::string_view name);

// r(θ) as a fraction of the 90° radius (θ in radians, 0..π/2 and, for wide lenses, beyond: the
// orthographic projection only to π/2).
double projection_radius(Projection p, double zenith);
// θ(r), the inverse; NaN where no direction maps (orthographic beyond r = 1).
double projection_zenith(Projection p, double r);

// An image of the hemisphere: its centre (pixels, x right, y down, pixel centres at whole numbers)
// and the radius (pixels) at which θ = 90°.
struct FisheyeFrame {
  double cx = 0, cy = 0, radius = 1;
  Projection projection = Projection::equidistant;
  bool mirror = false;

  // The direction seen at pixel position (x, y): false outside θ ≤ 90°.
  bool direction(double x, double y, double& zenith, double& azimuth) const;
  // Where the direction (zenith, azimuth) appears.
  void pixel(double zenith, double azimuth, double& x, double& y) const;
};

}  // namespace skyview
