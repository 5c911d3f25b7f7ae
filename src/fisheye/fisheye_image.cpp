#include "skyview/fisheye/fisheye_image.h"

#include <cpl_error.h>
#include <gdal_priv.h>

#include <algorithm>
#include <memory>

#include "skyview/core/error.h"
#include "skyview/raster/raster_io.h"

namespace skyview {

FisheyeImage read_fisheye_image(const std::string& path) {
  init_gdal();
  CPLErrorReset();
  std::unique_ptr<GDALDataset> ds(static_cast<GDALDataset*>(
      GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
  if (!ds) throw Error("cannot read '" + path + "' as an image (JPEG, PNG, TIFF or another format GDAL reads)");
  FisheyeImage im;
  im.width = ds->GetRasterXSize();
  im.height = ds->GetRasterYSize();
  const int bands = ds->GetRasterCount();
  if (bands != 1 && bands != 3 && bands != 4)
    throw Error("'" + path + "' has " + std::to_string(bands) + " bands; a photograph has 3 (RGB) or 4, a mask 1");
  if (im.width < 16 || im.height < 16 || im.width > 40000 || im.height > 40000)
    throw Error("'" + path + "' is " + std::to_string(im.width) + " x " + std::to_string(im.height) +
                " pixels; an image between 16 and 40000 pixels a side is needed");
  im.channels = bands == 1 ? 1 : 3;
  const std::size_t n = static_cast<std::size_t>(im.width) * im.height;
  im.pixels.resize(n * im.channels);
  // 16-bit images (TIFF from a raw converter) are scaled to 8 bits rather than clipped.
  const GDALDataType type = ds->GetRasterBand(1)->GetRasterDataType();
  const bool wide = type == GDT_UInt16 || type == GDT_Int16;
  if (type != GDT_Byte && !wide)  // a DEM or a result raster, not a picture
    throw Error("'" + path + "' holds " + GDALGetDataTypeName(type) +
                " values: a photograph or mask has 8- or 16-bit pixels");
  std::vector<std::uint16_t> wide_pixels(wide ? n : 0);
  int band_map[3] = {1, 2, 3};
  for (int c = 0; c < im.channels; ++c) {
    CPLErr err;
    if (wide) {
      err =
          ds->GetRasterBand(band_map[c])
              ->RasterIO(GF_Read, 0, 0, im.width, im.height, wide_pixels.data(), im.width, im.height, GDT_UInt16, 0, 0);
      for (std::size_t i = 0; i < n; ++i)
        im.pixels[i * im.channels + c] = static_cast<std::uint8_t>(wide_pixels[i] / 257);
    } else {
      err = ds->GetRasterBand(band_map[c])
                ->RasterIO(GF_Read, 0, 0, im.width, im.height, im.pixels.data() + c, im.width, im.height, GDT_Byte,
                           im.channels, static_cast<GSpacing>(im.channels) * im.width);
    }
    if (err != CE_None) {
      const char* m = CPLGetLastErrorMsg();
      throw Error("cannot read the pixels of '" + path + "'" + (m && *m ? std::string(": ") + m : ""));
    }
  }
  return im;
}

}  // namespace skyview
