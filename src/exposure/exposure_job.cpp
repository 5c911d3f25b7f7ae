// The sky, site checks, albedo and metadata of a skyview exposure run (exposure_job.h).
#include "skyview/exposure/exposure_job.h"

#include <cmath>
#include <cstdlib>

#include "skyview/core/error.h"
#include "skyview/core/number_text.h"
#include "skyview/raster/raster_read.h"
#include "skyview/raster/raster_site.h"
#include "skyview/raster/terrain_reader.h"

namespace skyview {
namespace {

// A map made for a site farther than this from the raster describes another sky.
constexpr double kMaxSiteDistanceDeg = 1.0;

void refuse_unused(const ExposureJobRequest& r, const std::string& option, bool used, const std::string& where) {
  if (!used && r.given.count(option) > 0) throw UsageError(option + " applies only to " + where);
}

// The site of the sky (`sky_site`, from `site_source`) and the EPW's station against the raster's centre.
void check_sites(const ExposureJobRequest& r, const GeoPoint& centre, const GeoPoint& sky_site,
                 const std::string& site_source, const std::optional<EpwFile>& weather) {
  const double apart = angular_distance_deg(sky_site, centre);
  if (apart > kMaxSiteDistanceDeg && !r.allow_site_mismatch) {
    throw Error("the sky is made for " + number_text(sky_site.latitude_deg) + ", " +
                number_text(sky_site.longitude_deg) + " (" + site_source + "), " + number_text(std::round(apart)) +
                " degrees from the raster's centre " + number_text(centre.latitude_deg) + ", " +
                number_text(centre.longitude_deg) + "; give --allow-site-mismatch if that is meant");
  }
  // The weather measured at the EPW's site is the sky's too.
  if (weather) {
    const GeoPoint station{weather->location.latitude_deg, weather->location.longitude_deg};
    const double off = angular_distance_deg(station, centre);
    if (off > kMaxSiteDistanceDeg && !r.allow_site_mismatch) {
      throw Error("the weather file was measured at " + number_text(station.latitude_deg) + ", " +
                  number_text(station.longitude_deg) + ", " + number_text(std::round(off)) +
                  " degrees from the raster's centre " + number_text(centre.latitude_deg) + ", " +
                  number_text(centre.longitude_deg) + "; give --allow-site-mismatch if that is meant");
    }
  }
}

}  // namespace

const std::vector<ExposureBandInfo>& exposure_band_info() {
  static const std::vector<ExposureBandInfo> bands{
      {"total", &ExposureBands::total, "kWh m-2", "direct + diffuse + reflected on the cell's tilted surface"},
      {"direct", &ExposureBands::direct, "kWh m-2", "the sun's beam on the cell's tilted surface (Horn normal)"},
      {"diffuse", &ExposureBands::diffuse, "kWh m-2", "the sky without the sun, through the parts the cell sees"},
      {"reflected", &ExposureBands::reflected, "kWh m-2",
       "isotropic reflection: albedo x unobstructed global horizontal x (1 - svf of the tilted surface)"},
      {"horizontal_total", &ExposureBands::horizontal_total, "kWh m-2",
       "direct + diffuse + reflected on a horizontal surface at the cell (a pyranometer)"},
      {"svf", &ExposureBands::svf, "1", "sky-view factor, 1 - mean sin^2(max(h,0)); cosine-weighted, horizontal"},
  };
  return bands;
}

ExposureAlbedo parse_exposure_albedo(const std::string& text) {
  ExposureAlbedo a;
  if (text.empty()) return a;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end && *end == '\0' && end != text.c_str()) {
    if (!(v >= 0.0 && v <= 1.0)) throw UsageError("--albedo must be within 0 .. 1 (got " + text + ")");
    a.value = v;
  } else {
    a.raster = text;
  }
  return a;
}

Grid<float> checked_albedo(Grid<float>&& cells, const std::string& what) {
  for (float v : cells.values()) {
    if (!std::isnan(v) && !(v >= 0.0f && v <= 1.0f))
      throw UsageError(what + " holds " + number_text(v) + ", outside 0 .. 1");
  }
  return std::move(cells);
}

void check_albedo_grid(const std::string& path, int width, int height, const GeoReference& albedo, int dsm_width,
                       int dsm_height, const GeoReference& dsm) {
  const auto& g = albedo.geotransform;
  const auto& d = dsm.geotransform;
  const bool same_grid =
      albedo.has_geotransform == dsm.has_geotransform &&
      (!dsm.has_geotransform ||
       (std::abs(g[0] - d[0]) < 0.5 * std::abs(d[1]) && std::abs(g[3] - d[3]) < 0.5 * std::abs(d[5]) &&
        std::abs(g[1] - d[1]) < 1e-6 * std::abs(d[1]) && std::abs(g[5] - d[5]) < 1e-6 * std::abs(d[5])));
  if (width != dsm_width || height != dsm_height || !same_grid) {
    throw UsageError("--albedo '" + path + "' is " + std::to_string(width) + "x" + std::to_string(height) +
                     " cells where the DSM is " + std::to_string(dsm_width) + "x" + std::to_string(dsm_height) +
                     (same_grid ? "" : ", or lies elsewhere") + "; resample it onto the DSM's grid");
  }
}

void check_exposure_job(const ExposureJobRequest& r) {
  if (r.method != "fast" && r.method != "exact")
    throw UsageError("--method must be fast or exact (got '" + r.method + "')");
  const bool exact = r.method == "exact";
  refuse_unused(r, "--max-error", false, "skyview svf (skyview bench --exposure measures exposure's error)");
  refuse_unused(r, "--reads", !exact, "--method fast");
  if (r.reads != "area" && r.reads != "mipmap")
    throw UsageError("--reads must be area or mipmap (got '" + r.reads + "')");
  if (r.from_map()) {
    for (const std::string& name : sky_option_names())
      refuse_unused(r, name, false, "runs without --skymap (the map file holds its sky, site and period)");
    refuse_unused(r, "--map-size", false, "runs without --skymap (the map file has its size)");
  } else {
    check_sky_request(r.sky);
    check_sky_options_used(r.sky, r.given);
    if (r.map_size < 16 || r.map_size > 8192) throw UsageError("--map-size must be within 16 .. 8192");
  }
}

ExposureJob prepare_exposure_job(const ExposureJobRequest& r, const ExposureRaster& raster,
                                 const std::function<void(const std::vector<std::string>&)>& warn) {
  const bool exact = r.method == "exact";
  const Terrain& t = raster.terrain;
  const int width = raster.width, height = raster.height;
  const std::optional<GeoPoint> centre = raster_centre_geographic(raster.georef, width, height);
  const ExposureAlbedo& albedo = r.albedo;
  const bool albedo_given = albedo.value || !albedo.raster.empty() || albedo.cells;
  ExposureJob job;
  auto& meta = job.metadata;

  // The sky: from the map, or made here for the raster's site.
  ExposureSky& sky = job.sky;
  std::optional<PreparedSky> prepared;
  std::map<std::string, std::string> sky_meta;
  std::string site_source;
  std::optional<EpwFile> weather;
  if (r.from_map()) {
    SkymapFile file = r.skymap_data ? *r.skymap_data : read_skymap(r.skymap);
    sky.map = std::move(file.map);
    sky_meta = file.metadata;
    site_source = "the sky map '" + r.skymap + "'";
    if (exact) {
      // The beam of every step: the map's own period and sky again.
      try {
        prepared = prepare_sky(file.request);
      } catch (const Error& e) {
        throw UsageError("--method exact rebuilds the time steps of '" + r.skymap +
                         "' from its metadata, which failed: " + e.what());
      }
      weather = prepared->weather;
    } else if (!file.request.epw.empty() && !albedo_given) {
      try {
        weather = read_epw(file.request.epw);
      } catch (const Error&) {
        // Only the albedo was wanted from it: the default stands.
      }
    }
  } else {
    if (t.origin_col > width / 2 || t.origin_row > height / 2 || t.origin_col + t.width() <= width / 2 ||
        t.origin_row + t.height() <= height / 2) {
      throw Error("a sky for a tile of a raster needs the raster's centre cell: make it once and give the map");
    }
    if (!centre && !r.sky.latitude && r.sky.epw.empty()) {
      throw Error(raster.name + " has no CRS to place the sun: give --lat and --lon");
    }
    std::optional<Site> default_site;
    if (centre) {
      Site s;
      s.latitude_deg = centre->latitude_deg;
      s.longitude_deg = centre->longitude_deg;
      const double mid = t.heights(width / 2 - t.origin_col, height / 2 - t.origin_row);
      s.elevation_m = t.base_height + (std::isnan(mid) ? 0.0 : mid);
      default_site = s;
    }
    // Hošek–Wilkie's sky depends on the ground albedo: the one given, where it is a number.
    SkyRequest sky_request = r.sky;
    if (albedo.value) sky_request.albedo = *albedo.value;
    prepared = prepare_sky(sky_request, default_site);
    weather = prepared->weather;
    site_source = r.sky.latitude ? "--lat/--lon" : centre ? "the raster's centre" : "the EPW file";
  }
  if (prepared) {
    warn(prepared->warnings);
    prepared->warnings.clear();
  }
  if (!r.from_map()) {
    sky.map = make_exposure_map(*prepared, r.map_size);
    warn(prepared->warnings);
    sky_meta = prepared->metadata;
  }
  const double global_horizontal = sky.map.irradiation(ExposureBand::global, Direction{0, 0, 1});
  job.global_horizontal = global_horizontal;
  if (!(global_horizontal > 0.0)) {
    const std::string period =
        sky_meta.count("FROM_UTC") ? " from " + sky_meta["FROM_UTC"] + " to " + sky_meta["TO_UTC"] : "";
    throw Error("no daylight at " + sky_meta["LATITUDE"] + ", " + sky_meta["LONGITUDE"] + period +
                ": the sun stays below the horizon and the sky is dark");
  }
  if (exact) sky.sun = sun_steps(*prepared->model, prepared->steps);
  // The site of the sky against the raster's.
  const GeoPoint sky_site{std::strtod(sky_meta["LATITUDE"].c_str(), nullptr),
                          std::strtod(sky_meta["LONGITUDE"].c_str(), nullptr)};
  if (centre) {
    check_sites(r, *centre, sky_site, site_source, weather);
    meta["RASTER_CENTRE_LAT_LON"] = number_text(centre->latitude_deg) + ", " + number_text(centre->longitude_deg);
  } else if (r.from_map()) {
    warn({raster.name + " has no CRS: the sky map's site (" + number_text(sky_site.latitude_deg) + ", " +
          number_text(sky_site.longitude_deg) + ") cannot be checked against it"});
  }

  ExposureRequest& request = job.request;
  request.method = exact ? ExposureMethod::exact : ExposureMethod::fast;
  request.sampler.reads = r.reads == "mipmap" ? SamplerReads::mipmap : SamplerReads::area;
  std::string albedo_source;
  if (albedo.value) {
    request.albedo = *albedo.value;
    albedo_source = "--albedo";
  } else if (albedo.cells) {
    if (albedo.cells->width() != t.width() || albedo.cells->height() != t.height()) {
      throw UsageError("the albedo array is " + std::to_string(albedo.cells->height()) + " x " +
                       std::to_string(albedo.cells->width()) + " cells (rows x columns) where the heights are " +
                       std::to_string(t.height()) + " x " + std::to_string(t.width()));
    }
    request.albedo_grid = checked_albedo(Grid<float>(*albedo.cells), "the albedo array");
    albedo_source = "an array";
  } else if (!albedo.raster.empty()) {
    if (raster.tiled) {  // each tile reads its window of it
      const RasterSize size = raster_size(albedo.raster, 1);
      check_albedo_grid(albedo.raster, size.width, size.height, read_band(albedo.raster, 1, {0, 0, 1, 1}).georef, width,
                        height, raster.georef);
    } else {
      RasterBand band = read_band(albedo.raster, 1);
      check_albedo_grid(albedo.raster, band.values.width(), band.values.height(), band.georef, width, height, t.georef);
      request.albedo_grid = checked_albedo(std::move(band.values), "--albedo '" + albedo.raster + "'");
    }
    job.albedo_raster = albedo.raster;
    albedo_source = "the raster '" + albedo.raster + "'";
  } else if (std::optional<double> a = weather ? mean_albedo(*weather) : std::nullopt) {
    request.albedo = *a;
    albedo_source = "the EPW's albedo field, weighted by global horizontal irradiance";
  } else {
    albedo_source = "default";
  }

  for (const auto& [key, value] : sky_meta) {
    if (key.rfind("SKYVIEW_", 0) == 0) continue;  // the map file's own command and version
    meta["SKY_" + key] = value;
  }
  if (r.from_map()) meta["SKYMAP"] = r.skymap;
  meta["SITE_SOURCE"] = site_source;
  meta["EXPOSURE_METHOD"] = r.method;
  meta["EXPOSURE_CITATION"] =
      exact ? "beam of every time step against the horizon interpolated at the sun's azimuth; sky radiance summed over "
              "the period integrated over the visible sky at the map's resolution with the exact cosine"
            : "Section 6 of Munoz-Pandiella et al., Solar exposure of complex cities (exposure map sampled per "
              "horizon direction, Eqs. 7-10)";
  if (!exact) meta["EXPOSURE_SAMPLER_READS"] = r.reads;
  meta["EXPOSURE_MAP_SIZE"] = std::to_string(sky.map.width()) + "x" + std::to_string(sky.map.height());
  meta["ALBEDO"] = albedo.raster.empty() && !albedo.cells ? number_text(request.albedo) : "per cell";
  meta["ALBEDO_SOURCE"] = albedo_source;
  meta["GLOBAL_HORIZONTAL_UNOBSTRUCTED_KWH_M2"] = number_text(global_horizontal / 1000);
  meta["UNITS"] = "kWh m-2 over the period (svf: 1)";
  meta["PERIOD"] = sky_meta.count("FROM_UTC") ? sky_meta["FROM_UTC"] + " to " + sky_meta["TO_UTC"] + " (excluded)"
                                              : "the EPW file's hours (" + sky_meta["EPW"] + ")";
  return job;
}

}  // namespace skyview
