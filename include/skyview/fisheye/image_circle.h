#pragma once
// Where the hemisphere lies in a fish-eye image: the circle of a circular fish-eye lens's image
// (its vignette: black outside), or, for a sky mask, the circle inscribed in the image.
#include "skyview/fisheye/fisheye_image.h"

namespace skyview {

struct ImageCircle {
  double cx = 0, cy = 0, radius = 0;  // pixels; pixel centres at whole numbers
  double rms = 0;                     // of the edge points about the fitted circle, pixels (0 when not fitted)
  int edge_points = 0;                // used in the fit
  int sectors = 0;                    // of 12 around the circle (30° each) that hold some of them
};

// The circle a circular fish-eye lens draws: its rim found along 720 rays from the centre (the
// outermost pixel brighter than the black border around it, in a run of four), the circle through
// the most rim points with (almost) none outside it (dark content at the rim stops a ray inside the
// circle, never outside) among 3000 through three of them, refitted by least squares (Kåsa) to the
// points on it, and the rays cast again from its centre. Throws skyview::Error when the image has
// no black border (a full-frame fish-eye: give the circle) or no circle fits 60 rim points spread
// over 5 of 12 sectors.
ImageCircle find_image_circle(const FisheyeImage& image);

// The circle inscribed in the image, centred: how a circular fish-eye camera frames the sky, and how
// skyview fisheye draws its masks.
ImageCircle inscribed_circle(int width, int height);

}  // namespace skyview
