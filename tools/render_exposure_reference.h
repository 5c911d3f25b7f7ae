#pragma once
// skyview render --reference with --skymap: the exposure reference's bands, its difference image
// (beside --diff-preview's) and its agreement with the exposure band for the summary line.
#include <string>
#include <vector>

#include "skyview/raster/band_writer.h"
#include "skyview/render/exposure_reference.h"

namespace skyview::cli {

// D.png -> D_exposure.png: where --diff-preview's exposure - exposure_reference image goes.
std::string exposure_diff_path(const std::string& diff_preview);

// Appends exposure_reference and exposure_reference_stderr to `out`.
void add_exposure_reference_bands(std::vector<OutputBand>& out, const ExposureReference& reference);

struct ExposureAgreement {
  double mean = 0, mean_abs = 0, reference_mean = 0;  // kWh m-2 over the pixels on the scene
};

// exposure - exposure_reference over the pixels on the scene; with a `preview` path, also its
// PNG (diverging ramp, symmetric stretch).
ExposureAgreement compare_exposure(const Grid<float>& exposure, const ExposureReference& reference,
                                   const std::string& preview, const std::string& output, bool overwrite);

// ", exposure - reference mean M mean abs A kWh m-2 (P % of the reference's mean)"
std::string exposure_agreement_text(const ExposureAgreement& a);

}  // namespace skyview::cli
