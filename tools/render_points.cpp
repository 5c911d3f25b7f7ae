#include "render_points.h"

#include "skyview/render/view_points.h"

namespace skyview::cli {

std::size_t write_render_points(const std::string& path, const ViewBuffers& view, const Scene& scene,
                                const std::vector<OutputBand>& bands) {
  ViewPointsOptions po;
  for (const OutputBand& b : bands) {
    po.attributes.push_back({b.description, b.unit == "1" ? "unitless" : b.unit, b.values});
    if (b.description == "svf") po.intensity = b.values;
  }
  return write_view_points(path, view, scene, po);
}

}  // namespace skyview::cli
