#include "render_exposure_reference.h"

#include <cmath>
#include <limits>

#include "skyview/core/number_text.h"
#include "skyview/preview/raster_preview.h"

namespace skyview::cli {

std::string exposure_diff_path(const std::string& diff_preview) {
  if (diff_preview.empty()) return {};
  const std::size_t dot = diff_preview.rfind('.');
  return diff_preview.substr(0, dot) + "_exposure" + diff_preview.substr(dot);
}

void add_exposure_reference_bands(std::vector<OutputBand>& out, const ExposureReference& reference) {
  out.push_back({"exposure_reference",
                 "kWh m-2",
                 reference.exposure.values().data(),
                 {{"DEFINITION",
                   "ray-cast reference exposure: the sky map integrated over the pixel's tilted hemisphere with exact "
                   "visibility rays (cosine- and radiance-sampled, balance heuristic)"}}});
  out.push_back(
      {"exposure_reference_stderr",
       "kWh m-2",
       reference.stderr_.values().data(),
       {{"DEFINITION", "standard error of exposure_reference: the samples' standard deviation / sqrt(rays)"}}});
}

ExposureAgreement compare_exposure(const Grid<float>& exposure, const ExposureReference& reference,
                                   const std::string& preview, const std::string& output, bool overwrite) {
  Grid<float> diff(exposure.width(), exposure.height(), std::numeric_limits<float>::quiet_NaN());
  ExposureAgreement a;
  std::size_t n = 0;
  for (std::size_t i = 0; i < diff.values().size(); ++i) {
    const float e = exposure.values()[i], r = reference.exposure.values()[i];
    if (std::isnan(e) || std::isnan(r)) continue;
    diff.values()[i] = e - r;
    a.mean += e - r;
    a.mean_abs += std::abs(e - r);
    a.reference_mean += r;
    ++n;
  }
  if (n) a.mean /= n, a.mean_abs /= n, a.reference_mean /= n;
  if (!preview.empty()) {
    PreviewSpec ps;
    ps.title = "exposure - exposure_reference - " + output;
    ps.band = "exposure - exposure_reference";
    ps.unit = "kWh m-2";
    ps.ramp = ColourRamp::diverging;
    write_raster_preview(preview, diff, ps, overwrite);
  }
  return a;
}

std::string exposure_agreement_text(const ExposureAgreement& a) {
  const double share = a.reference_mean > 0 ? a.mean_abs / a.reference_mean * 100 : 0.0;
  return ", exposure - reference mean " + number_text(std::round(a.mean * 10) / 10) + " mean abs " +
         number_text(std::round(a.mean_abs * 10) / 10) + " kWh m-2 (" + number_text(std::round(share * 10) / 10) +
         " % of the reference's mean)";
}

}  // namespace skyview::cli
