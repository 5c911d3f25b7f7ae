#pragma once
// `skyview fisheye-svf`: the svf of a fish-eye photograph or sky mask: its image circle (found, or
// given), its sky (classified, or a mask), and the sky fractions with exact per-pixel weights and by
// the annulus method.
#include <optional>
#include <string>

#include "skyview/fisheye/fisheye_image.h"
#include "skyview/fisheye/image_circle.h"
#include "skyview/fisheye/projection.h"
#include "skyview/fisheye/sky_classifier.h"
#include "skyview/fisheye/sky_fraction.h"

namespace skyview {

struct FisheyeSvfOptions {
  Projection projection = Projection::equidistant;
  std::optional<ImageCircle> circle;            // given (--center, --radius): the image circle, not searched
  double field_of_view = 180.0;                 // degrees across the image circle (190 for a Nikon FC-E9)
  SkyThreshold threshold = SkyThreshold::otsu;  // mask: an existing mask (its circle: inscribed)
  int rings = 36;
};

struct FisheyeSvfResult {
  ImageCircle circle;  // the image circle used
  bool circle_found = false;
  FisheyeFrame frame;  // with the 90° radius
  SkyClassification classification;
  SkyFractions fractions;
};

// Throws skyview::Error for options out of range (a field of view below 180° or above 360°, rings),
// an image without a circle, a circle that lies outside the image.
FisheyeSvfResult fisheye_svf(const FisheyeImage& image, const FisheyeSvfOptions& options);

// The photograph beside its classification (sky white, the rest dark, the 90° circle red), scaled to
// at most 640 pixels high, as a PNG: what the classifier saw.
void write_classified_png(const std::string& path, const FisheyeImage& image, const FisheyeSvfResult& result,
                          bool overwrite);

}  // namespace skyview
