#pragma once
// Preetham, Shirley & Smits, "A Practical Analytic Model for Daylight", SIGGRAPH 1999,
// Appendix A.2: zenith values and Perez-form distribution of luminance Y and chromaticity x, y,
// plus the colour conversions used to draw the sky. Angles in radians.

namespace skyview::preetham {

struct Yxy {
  double Y = 0;  // luminance, cd/m²
  double x = 0, y = 0;
};

struct XYZ {
  double X = 0, Y = 0, Z = 0;
};

struct LinearRgb {
  double r = 0, g = 0, b = 0;
};

// Perez-form coefficients A..E of one component at turbidity T (paper's Table, linear in T).
struct PerezCoefficients {
  double A, B, C, D, E;
};
enum class Component { Y, x, y };
PerezCoefficients coefficients(Component c, double turbidity);

// F(θ, γ) = (1 + A·exp(B / cos θ)) · (1 + C·exp(D·γ) + E·cos²γ), with cos θ clamped above 0.
double perez(const PerezCoefficients& k, double theta, double gamma);

// Zenith luminance (cd/m²) and chromaticity for sun zenith angle `sun_zenith`.
Yxy zenith(double turbidity, double sun_zenith);

// Sky luminance and chromaticity in a direction: value_zenith · F(θ, γ) / F(0, sun_zenith).
Yxy sky(double turbidity, double sun_zenith, double theta, double gamma);

XYZ to_xyz(const Yxy& c);
// CIE XYZ to linear sRGB (Rec. 709 primaries, D65 white).
LinearRgb to_linear_srgb(const XYZ& c);

}  // namespace skyview::preetham
