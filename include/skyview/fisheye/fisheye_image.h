#pragma once
// Fish-eye photographs and masks read through GDAL (JPEG, PNG, TIFF, ...): the project keeps
// OpenCV's image codecs out of its runs (src/preview/opencv_png.h says why).
#include <cstdint>
#include <string>
#include <vector>

namespace skyview {

struct FisheyeImage {
  int width = 0, height = 0;
  int channels = 0;                  // 1 (grey or mask) or 3 (RGB); an alpha band is dropped
  std::vector<std::uint8_t> pixels;  // interleaved, rows top to bottom; 16-bit images scaled to 8 bits
};

// Throws skyview::Error, naming the file, for what GDAL cannot open as a raster image, images of
// 2 bands or more than 4, images below 16 x 16 or above 40000 x 40000 pixels, or a failed read.
FisheyeImage read_fisheye_image(const std::string& path);

}  // namespace skyview
