#pragma once
// The sky models skyview offers, built by name-free factory functions (each model lives in its
// own src/sky/*.cpp). See docs/sky.md for formulas, units, ranges and citations.
#include <memory>

#include "skyview/sky/sky_model.h"

namespace skyview {

// Preetham, Shirley & Smits 1999 clear sky for turbidity T ∈ [1.7, 10]: luminance converted to
// broadband radiance with a fixed luminous efficacy; the sun from Preetham's Rayleigh and Ångström
// aerosol transmittances applied to a 5778 K solar spectrum.
std::unique_ptr<SkyModel> make_preetham_sky(double turbidity, double luminous_efficacy_lm_per_w = 125.0);

// Hošek & Wilkie 2012 sky with their 2013 solar-radiance function, spectral 320–720 nm integrated
// to W/m² (trapezoid over the eleven 40 nm bands). T ∈ [1, 10], ground albedo ∈ [0, 1].
std::unique_ptr<SkyModel> make_hosek_wilkie_sky(double turbidity, double albedo);

// Perez, Seals & Michalsky 1993 all-weather sky driven by the measured diffuse horizontal and
// direct normal irradiance in SkyConditions: the diffuse distribution is normalised to the
// measured DHI, the sun carries the measured DNI.
std::unique_ptr<SkyModel> make_perez_all_weather_sky();

// A uniform sky. With `energy` it spreads that model's diffuse horizontal irradiance evenly and
// keeps its sun; without, it uses the measured DHI and DNI in SkyConditions.
std::unique_ptr<SkyModel> make_isotropic_sky(std::shared_ptr<const SkyModel> energy = nullptr);

}  // namespace skyview
