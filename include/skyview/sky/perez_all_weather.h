#pragma once
// Perez, Seals & Michalsky 1993 all-weather sky luminance distribution (Solar Energy 50(3)
// 235–245, Table 1 with the 1993 erratum), with the sky clearness ε and brightness Δ of Perez et
// al. 1990 (Solar Energy 44(5) 271–289). Angles in radians.

namespace skyview::perez {

struct Parameters {
  double a, b, c, d, e;
  int bin;  // 1..8, by sky clearness
};

// Sky clearness ε and brightness Δ from diffuse horizontal and direct normal irradiance (W/m²),
// sun zenith, and extraterrestrial normal irradiance. Δ uses the Kasten–Young air mass.
double clearness(double diffuse_horizontal, double direct_normal, double sun_zenith);
double brightness(double diffuse_horizontal, double sun_zenith, double extraterrestrial_normal);

// The five distribution parameters, with Radiance's guards (Δ ≥ 0.01, ε ≤ 11.9, Δ ≥ 0.2 for
// 1.065 < ε < 2.8) so the fitted polynomials stay in range.
Parameters parameters(double clearness, double brightness, double sun_zenith);

// Relative radiance lv(ζ, γ) = gradation(ζ) · indicatrix(γ), with gradation 1 + a·exp(b / cos ζ)
// and indicatrix 1 + c·exp(d·γ) + e·cos²γ; cos ζ is held at its 5°-elevation value below that,
// where the fit has no data and b > 0 would diverge. Each factor is held at 0 or above: under an
// overcast sky with a low sun (clearness bin 1, brightness Δ above about 0.7) the fitted gradation
// turns negative over the lower sky, and radiance cannot.
double gradation(const Parameters& p, double zeta);
double indicatrix(const Parameters& p, double gamma);
double relative_radiance(const Parameters& p, double zeta, double gamma);

}  // namespace skyview::perez
