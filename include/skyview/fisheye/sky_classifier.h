#pragma once
// Which pixels of a fish-eye image are sky.
#include <cstdint>
#include <vector>

#include "skyview/fisheye/fisheye_image.h"
#include "skyview/fisheye/image_circle.h"

namespace skyview {

enum class SkyThreshold {
  mask,  // an existing mask: any non-zero pixel is sky
  otsu,  // Otsu's threshold on the blue channel inside the circle: clear sky and clouds are bright
         // in blue, leaves, rock and walls dark (the usual choice for canopy photographs)
  blue   // Otsu's threshold on the blue ratio B / (R + G + B): clear blue sky only, clouds count as
         // obstacles (clear-sky photographs with bright walls)
};

struct SkyClassification {
  std::vector<std::uint8_t> sky;  // width * height, 255 where sky (inside the circle), else 0
  double threshold = 0;           // the value Otsu chose (blue level 0..255, or ratio 0..1)
};

// Throws skyview::Error for a photograph method on a one-band image, or a circle without pixels.
SkyClassification classify_sky(const FisheyeImage& image, const ImageCircle& circle, SkyThreshold method);

}  // namespace skyview
