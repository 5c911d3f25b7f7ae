#pragma once
// The points a camera sees as a georeferenced point cloud: one LAS 1.4 point (format 6) per pixel
// that sees the scene, at its hit position in the scene's projected CRS (OGC WKT VLR), with the
// view's bands as float32 extra bytes (PDAL, QGIS and CloudCompare show them by name) and one band
// in [0, 1] scaled to 0..65535 into the standard intensity field for viewers that read no extra
// bytes.
#include <string>
#include <vector>

#include "skyview/render/view_buffers.h"
#include "skyview/scene/scene.h"

namespace skyview {

struct ViewPointAttribute {
  std::string name, description;  // up to 31 characters each
  const float* values = nullptr;  // one per pixel, row-major
};

struct ViewPointsOptions {
  std::vector<ViewPointAttribute> attributes;  // as extra bytes, in this order
  const float* intensity = nullptr;            // one per pixel, in [0, 1] (clamped), scaled into intensity
  double scale = 0.001;                        // metres per coordinate step
};

// Writes the visible points of `view` (row by row, left to right) to `path` under a temporary
// name renamed into place; returns their count. Throws skyview::Error where the file cannot be
// written or the coordinates do not fit the scale.
std::size_t write_view_points(const std::string& path, const ViewBuffers& view, const Scene& scene,
                              const ViewPointsOptions& options);

}  // namespace skyview
