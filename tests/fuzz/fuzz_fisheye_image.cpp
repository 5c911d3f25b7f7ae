// libFuzzer target for fish-eye images from anywhere (skyview/fisheye/fisheye_image.h) and what
// fisheye-svf does with them first: GDAL decodes the bytes (JPEG, PNG, TIFF, ...), then the image
// circle is searched and the sky classified. Every malformed or odd image must end in a
// skyview::Error or a result; any other exception, crash, sanitizer report or hang is a finding.
// Run it with scripts/fuzz.sh.
#include <cpl_vsi.h>
#include <gdal.h>

#include <cstddef>
#include <cstdint>

#include "fuzz_gdal_setup.h"
#include "skyview/core/error.h"
#include "skyview/fisheye/fisheye_image.h"
#include "skyview/fisheye/image_circle.h"
#include "skyview/fisheye/sky_classifier.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const char* path = "/vsimem/fuzz_fisheye_image";
  VSIFCloseL(VSIFileFromMemBuffer(path, const_cast<GByte*>(data), size, FALSE));
  try {
    const skyview::FisheyeImage image = skyview::read_fisheye_image(path);
    if (image.pixels.size() <= 4096 * 4096 * 3) {
      skyview::ImageCircle circle = skyview::inscribed_circle(image.width, image.height);
      try {
        circle = skyview::find_image_circle(image);
      } catch (const skyview::Error&) {
      }
      const auto sky = skyview::classify_sky(
          image, circle, image.channels == 1 ? skyview::SkyThreshold::mask : skyview::SkyThreshold::otsu);
      volatile std::size_t n = sky.sky.size();
      (void)n;
    }
  } catch (const skyview::Error&) {
    // The documented way to reject a bad image.
  }
  VSIUnlink(path);
  return 0;
}
