#include "skyview/sky_view/horizon_bands.h"

#include <cmath>

#include "skyview/core/number_text.h"

namespace skyview {

std::vector<DirectionBand> direction_bands(const HorizonSetup& setup) {
  const int n = setup.engine->params().directions;
  const double rotation = setup.sector_rotation * 180.0 / M_PI;
  const bool uniform = setup.sectors.is_uniform();  // named by 360 k / N, as before grid lines
  std::vector<DirectionBand> bands;
  for (int k = 0; k < n; ++k) {
    const auto i = static_cast<std::size_t>(k);
    // In [0, 360) to ten significant digits: a set turned by -0.0001° starts at 359.9998961, and
    // a residue that rounds to 360 reads 0.
    const double offset = uniform ? 360.0 * k / n : setup.sectors.offset[i] * 180.0 / M_PI;
    double azimuth = std::fmod(offset + rotation, 360.0);
    if (azimuth < 0.0) azimuth += 360.0;
    const std::string text = number_text(azimuth);
    DirectionBand band;
    band.azimuth_deg = std::stod(text) >= 360.0 ? std::string(1, '0') : text;
    band.width_deg = uniform ? 360.0 / n : 360.0 * setup.sectors.share[i];
    bands.push_back(std::move(band));
  }
  return bands;
}

std::vector<unsigned char> horizon_blank_cells(const HorizonSetup& setup, const Terrain& terrain, const Window& window,
                                               std::int64_t& edge_cells, std::optional<double> radius) {
  const double searched = radius.value_or(setup.engine->radius());
  std::vector<unsigned char> blank(static_cast<std::size_t>(window.cells()));
  edge_cells = 0;
  for (int r = 0; r < window.rows; ++r) {
    for (int c = 0; c < window.cols; ++c) {
      const int tc = window.col0 + c, tr = window.row0 + r;
      const bool valid = terrain.valid(tc, tr);
      const bool leaves = valid && search_circle_leaves_raster(terrain, tc, tr, searched);
      edge_cells += leaves;
      blank[static_cast<std::size_t>(r) * window.cols + c] = !valid || (setup.edge == EdgeMode::nodata && leaves);
    }
  }
  return blank;
}

}  // namespace skyview
