#pragma once
// skyview render --points-out: the output image's bands carried onto the visible points of a LAS file.
#include <string>
#include <vector>

#include "skyview/raster/band_writer.h"
#include "skyview/render/view_buffers.h"
#include "skyview/scene/scene.h"

namespace skyview::cli {

// Every band as a float32 extra-bytes attribute of its name (its unit as the description), svf
// also as intensity (svf · 65535). Returns the count of points written.
std::size_t write_render_points(const std::string& path, const ViewBuffers& view, const Scene& scene,
                                const std::vector<OutputBand>& bands);

}  // namespace skyview::cli
