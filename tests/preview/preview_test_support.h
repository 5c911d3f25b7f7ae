#pragma once
// Reading a written preview back: its RGBA pixels, the georeference GDAL finds from its world file
// and .aux.xml, and the metadata saying what it draws.
#include <gdal_priv.h>
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "skyview/raster/raster_io.h"

namespace skyview::test {

struct PreviewPicture {
  int width = 0, height = 0, bands = 0;
  std::vector<std::uint8_t> rgba;  // four samples per pixel; alpha 255 where the file has none
  std::array<double, 6> geotransform{};
  bool has_geotransform = false;
  std::string epsg;  // the CRS's EPSG code, "" without
  std::string band, title, range, ramp;

  std::array<int, 4> at(int x, int y) const {
    const std::size_t i = (static_cast<std::size_t>(y) * width + x) * 4;
    return {rgba[i], rgba[i + 1], rgba[i + 2], rgba[i + 3]};
  }
};

inline PreviewPicture read_preview(const std::string& path) {
  init_gdal();
  PreviewPicture p;
  std::unique_ptr<GDALDataset> ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!ds) {
    ADD_FAILURE() << "cannot open " << path;
    return p;
  }
  p.width = ds->GetRasterXSize();
  p.height = ds->GetRasterYSize();
  p.bands = ds->GetRasterCount();
  p.rgba.assign(static_cast<std::size_t>(p.width) * p.height * 4, 255);
  for (int b = 0; b < std::min(p.bands, 4); ++b) {
    std::vector<std::uint8_t> plane(static_cast<std::size_t>(p.width) * p.height);
    EXPECT_EQ(ds->GetRasterBand(b + 1)->RasterIO(GF_Read, 0, 0, p.width, p.height, plane.data(), p.width, p.height,
                                                 GDT_Byte, 0, 0, nullptr),
              CE_None);
    for (std::size_t i = 0; i < plane.size(); ++i) p.rgba[i * 4 + b] = plane[i];
  }
  p.has_geotransform = ds->GetGeoTransform(p.geotransform.data()) == CE_None;
  if (const OGRSpatialReference* crs = ds->GetSpatialRef()) {
    const char* code = crs->GetAuthorityCode(nullptr);
    p.epsg = code ? code : "";
  }
  const auto item = [&](const char* key) {
    const char* v = ds->GetMetadataItem(key);
    return std::string(v ? v : "");
  };
  p.band = item("PREVIEW_BAND");
  p.title = item("PREVIEW_TITLE");
  p.range = item("PREVIEW_RANGE");
  p.ramp = item("PREVIEW_RAMP");
  return p;
}

// The picture's pixel (x, y) under ground point (gx, gy), from its geotransform (north-up).
inline std::pair<int, int> pixel_at(const PreviewPicture& p, double gx, double gy) {
  const auto& g = p.geotransform;
  return {static_cast<int>(std::floor((gx - g[0]) / g[1])), static_cast<int>(std::floor((gy - g[3]) / g[5]))};
}

}  // namespace skyview::test
