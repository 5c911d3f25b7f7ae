// Writing and reading the exposure map files of skyview skymap.
#include "skyview/sky/skymap_file.h"

#include <gdal_priv.h>

#include <cmath>
#include <cstdlib>

#include "skyview/core/error.h"

namespace skyview {
namespace {

const char* const kDefinition =
    "radiant exposure per unit solid angle; cosine-weighted integral over the sky a surface sees = its "
    "exposure (Wh/m2)";

// A number from the metadata, or NaN where it is missing or not a number.
double metadata_number(const std::map<std::string, std::string>& m, const std::string& key) {
  const auto it = m.find(key);
  if (it == m.end() || it->second.empty()) return std::nan("");
  char* end = nullptr;
  const double v = std::strtod(it->second.c_str(), &end);
  return end && *end == '\0' && std::isfinite(v) ? v : std::nan("");
}

}  // namespace

void write_skymap(const std::string& path, const ExposureMap& map, const WriteOptions& options) {
  GeoReference georef;  // x = azimuth (degrees), y = elevation (degrees); no CRS
  georef.geotransform = {0.0, 360.0 / map.width(), 0.0, 90.0, 0.0, -90.0 / map.height()};
  georef.has_geotransform = true;
  const std::string definition = kDefinition;
  write_bands(path, map.width(), map.height(), georef,
              {{"direct",
                "Wh m-2 sr-1",
                map.band(ExposureBand::direct).data(),
                {{"DEFINITION", "sun disc splatted over its disc; " + definition}}},
               {"diffuse",
                "Wh m-2 sr-1",
                map.band(ExposureBand::diffuse).data(),
                {{"DEFINITION", "sky without the sun; " + definition}}}},
              options);
}

SkymapFile read_skymap(const std::string& path) {
  init_gdal();
  GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!ds) throw Error("cannot open the sky map '" + path + "'");
  const std::string not_skymap = "'" + path + "' is not a sky map written by skyview skymap: ";
  if (ds->GetRasterCount() != 2) {
    throw Error(not_skymap + "it has " + std::to_string(ds->GetRasterCount()) + " bands, not direct and diffuse");
  }
  for (int b = 1; b <= 2; ++b) {
    const std::string want = b == 1 ? "direct" : "diffuse";
    const char* got = ds->GetRasterBand(b)->GetDescription();
    if (!got || want != got) throw Error(not_skymap + "band " + std::to_string(b) + " is not named " + want);
  }
  const int width = ds->GetRasterXSize(), height = ds->GetRasterYSize();
  double gt[6];
  if (ds->GetGeoTransform(gt) != CE_None || std::abs(gt[0]) > 1e-9 || std::abs(gt[1] * width - 360.0) > 1e-6 ||
      std::abs(gt[3] - 90.0) > 1e-9 || std::abs(gt[5] * height + 90.0) > 1e-6 || gt[2] != 0.0 || gt[4] != 0.0) {
    throw Error(not_skymap + "its cells do not span 0..360 degrees of azimuth and 90..0 of elevation");
  }
  std::map<std::string, std::string> metadata;
  if (char** items = ds->GetMetadata(); items) {
    for (char** item = items; *item; ++item) {
      const std::string text = *item;
      const auto eq = text.find('=');
      if (eq != std::string::npos) metadata[text.substr(0, eq)] = text.substr(eq + 1);
    }
  }
  ExposureMap map(width, height);
  for (int b = 1; b <= 2; ++b) {
    std::vector<float>& band = map.band(b == 1 ? ExposureBand::direct : ExposureBand::diffuse);
    if (ds->GetRasterBand(b)->RasterIO(GF_Read, 0, 0, width, height, band.data(), width, height, GDT_Float32, 0, 0) !=
        CE_None) {
      throw Error("cannot read band " + std::to_string(b) + " of '" + path + "'");
    }
  }
  return skymap_from_bands(std::move(map), std::move(metadata), path);
}

SkymapFile skymap_from_bands(ExposureMap map, std::map<std::string, std::string> metadata, const std::string& name) {
  const std::string not_skymap = "'" + name + "' is not a sky map written by skyview skymap: ";
  SkymapFile out;
  out.metadata = std::move(metadata);
  const auto& m = out.metadata;
  out.latitude_deg = metadata_number(m, "LATITUDE");
  out.longitude_deg = metadata_number(m, "LONGITUDE");
  if (m.count("SKY") == 0 || std::isnan(out.latitude_deg) || std::isnan(out.longitude_deg)) {
    throw Error(not_skymap + "its metadata lack SKY, LATITUDE or LONGITUDE");
  }
  for (int b = 1; b <= 2; ++b) {
    for (const float v : map.band(b == 1 ? ExposureBand::direct : ExposureBand::diffuse)) {
      if (!(v >= 0.0f) || std::isinf(v))
        throw Error(not_skymap + "band " + std::to_string(b) + " holds " +
                    (std::isnan(v) ? "nodata" : "values below 0 or infinite"));
    }
  }
  out.map = std::move(map);
  SkyRequest& r = out.request;
  r.sky = m.at("SKY");
  r.latitude = out.latitude_deg;
  r.longitude = out.longitude_deg;
  if (const double e = metadata_number(m, "ELEVATION"); !std::isnan(e)) r.elevation = e;
  if (const double t = metadata_number(m, "TURBIDITY"); !std::isnan(t)) r.turbidity = t;
  if (const double a = metadata_number(m, "ALBEDO"); !std::isnan(a)) r.albedo = a;
  if (const double k = metadata_number(m, "LUMINOUS_EFFICACY_LM_W"); !std::isnan(k)) r.luminous_efficacy = k;
  if (m.count("EPW")) r.epw = m.at("EPW");
  if (m.count("FROM_UTC") && m.count("TO_UTC")) {
    r.from = m.at("FROM_UTC");
    r.to = m.at("TO_UTC");
  }
  if (m.count("STEP")) r.step = m.at("STEP");
  return out;
}

}  // namespace skyview
