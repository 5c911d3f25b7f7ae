#pragma once
// What a `skyview exposure` run settles before compute_exposure: the sky (a map written by skyview
// skymap, or the sky options at the raster's site), the checks of that sky's site and weather
// against the raster, the ground albedo (a number, a raster on the DSM's grid, the EPW's, or the
// default) and the metadata the output records. The command line and the Python module
// (skyview.exposure) call these functions, so both refuse the same things with the same words and
// compute with the same sky.
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "skyview/exposure/exposure.h"
#include "skyview/raster/georeference.h"
#include "skyview/raster/terrain.h"
#include "skyview/sky/sky_request.h"
#include "skyview/sky/skymap_file.h"

namespace skyview {

// A band of the output: its name, the grid of ExposureBands it holds, its unit and definition.
struct ExposureBandInfo {
  const char* name;
  Grid<float> ExposureBands::*grid;
  const char* unit;
  const char* definition;
};
// total, direct, diffuse, reflected, horizontal_total, svf: the output's bands in order.
const std::vector<ExposureBandInfo>& exposure_band_info();

// --albedo: one number everywhere, a raster on the DSM's grid, or cells given in memory (the
// Terrain buffer's size, all of it computed); none of them: the EPW's albedo field, else ExposureRequest's default.
struct ExposureAlbedo {
  std::optional<double> value;
  std::string raster;
  std::optional<Grid<float>> cells;
};

// A number within 0 .. 1, or else a raster's path. Throws skyview::UsageError for a number outside.
ExposureAlbedo parse_exposure_albedo(const std::string& text);

// `what` ("--albedo 'a.tif'") as given, each cell within 0 .. 1 or NaN; throws skyview::UsageError.
Grid<float> checked_albedo(Grid<float>&& cells, const std::string& what);

// Throws skyview::UsageError unless the albedo raster at `path` (width x height, `albedo`) lies on
// the DSM's grid: the same size, its first cell within half a cell of the DSM's, the same cell size.
void check_albedo_grid(const std::string& path, int width, int height, const GeoReference& albedo, int dsm_width,
                       int dsm_height, const GeoReference& dsm);

struct ExposureJobRequest {
  std::string method = "fast";  // fast | exact
  std::string reads = "area";   // fast: area | mipmap
  // The sky: a map file (`skymap`), a map already read (`skymap_data`, which `skymap` then names
  // in messages and metadata), or else the sky options and the size of the map made from them.
  std::string skymap;
  std::optional<SkymapFile> skymap_data;
  SkyRequest sky;
  int map_size = 512;
  ExposureAlbedo albedo;
  bool allow_site_mismatch = false;
  // The options typed, by the command line's long names ("--reads", "--lat"): an option the run
  // would not use is refused rather than ignored.
  std::set<std::string> given;
  bool from_map() const { return !skymap.empty() || skymap_data.has_value(); }
};

// Throws skyview::Error (the command line's message) for a method, --reads or sky option that is
// unknown or that the run would not use. Reads nothing: call it before any input.
void check_exposure_job(const ExposureJobRequest& request);

// The DSM as the sky sees it: its whole raster's size and georeference, and `terrain` holding at
// least its centre cell (a tiled run's window about it), whose height is the default elevation.
struct ExposureRaster {
  const Terrain& terrain;
  int width = 0, height = 0;
  const GeoReference& georef;
  std::string name;    // the input, in messages ("'dsm.tif' has no CRS")
  bool tiled = false;  // an albedo raster is then read a tile at a time, only its grid checked here
};

struct ExposureJob {
  ExposureSky sky;
  ExposureRequest request;         // method, reads and albedo; the caller sets edge from its horizon setup
  std::string albedo_raster;       // read by tiles where the run is tiled
  double global_horizontal = 0.0;  // Wh/m², the map's unobstructed global horizontal
  // SKY_*, SKYMAP, SITE_SOURCE, RASTER_CENTRE_LAT_LON, EXPOSURE_*, ALBEDO, ALBEDO_SOURCE,
  // GLOBAL_HORIZONTAL_UNOBSTRUCTED_KWH_M2, UNITS, PERIOD.
  std::map<std::string, std::string> metadata;
};

// Makes or reads the sky, checks its site against the raster's centre, settles the albedo.
// `warn` gets the lines a user must see even under -q (a weather file's gaps, a raster without
// a CRS), as they arise. Throws skyview::Error for a dark sky, a site or weather station more than
// 1 degree from the raster's centre (unless allowed), a raster without a CRS and no site given,
// an albedo raster or array off the DSM's grid or outside 0 .. 1.
ExposureJob prepare_exposure_job(const ExposureJobRequest& request, const ExposureRaster& raster,
                                 const std::function<void(const std::vector<std::string>&)>& warn);

}  // namespace skyview
