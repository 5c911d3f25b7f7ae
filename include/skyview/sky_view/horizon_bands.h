#pragma once
// What `skyview horizon` writes, per direction and per cell, besides the angles themselves: each
// band's azimuth and sector width, and which cells it leaves as nodata. The command line and the
// Python module (skyview.horizon) share these, so that both name and blank the same bands.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "skyview/raster/terrain.h"
#include "skyview/sky_view/horizon_request.h"

namespace skyview {

struct DirectionBand {
  std::string azimuth_deg;  // centre azimuth in [0, 360), ten significant digits ("11.25"): the band's name
  double width_deg = 0;     // the share of the circle it stands for
};

// The run's direction bands in order: 360 k / N plus the set's rotation where the sectors are
// uniform, the grid lines' own azimuths otherwise.
std::vector<DirectionBand> direction_bands(const HorizonSetup& setup);

// Cells of `window` (row by row) the horizon bands leave as nodata (1): nodata cells, and with
// --edge nodata those whose search circle leaves the raster. `edge_cells` receives how many valid
// cells' circles leave it. The circle's radius is the engine's, or `radius` where given (a tiled
// run's far field searches without limit).
std::vector<unsigned char> horizon_blank_cells(const HorizonSetup& setup, const Terrain& terrain, const Window& window,
                                               std::int64_t& edge_cells, std::optional<double> radius = std::nullopt);

}  // namespace skyview
