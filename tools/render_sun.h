#pragma once
// skyview render --time: the sun at one instant over a camera view (issue 35): where it is (SPA at
// the scene's centre), which pixels it reaches (exact rays or a shadow map, shadow_maps.h) and the
// beam each receives from a clear sky (Preetham's direct normal irradiance).
#include <CLI/CLI.hpp>

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "skyview/render/shadow_maps.h"
#include "skyview/render/view_buffers.h"
#include "skyview/scene/ray_scene.h"
#include "skyview/scene/scene.h"

namespace skyview::cli {

struct RenderSunOptions {
  std::string time, tz;
  std::optional<double> lat, lon, elevation;
  std::string shadows = "exact";
  bool soft = false;
  ShadowOptions shadow;       // --shadow-map-size, --cascades
  std::optional<int> layers;  // lvsm: ShadowOptions::layers, hsm: hsm_layers
  double turbidity = 3.0;
};

// --time, --tz, --lat, --lon, --elevation, --shadows, --soft, --shadow-map-size, --cascades,
// --layers, --turbidity.
void add_render_sun_options(CLI::App& app, RenderSunOptions& o);

// Checks before any work: without --time every sun option is refused; the method's options go
// through validate_shadow_options (UsageError naming the command-line option).
void check_render_sun_options(const CLI::App& app, RenderSunOptions& o);

// The first sun band's name: sunlit, or sun_fraction with --soft.
std::string sun_band_name(const RenderSunOptions& o);

struct RenderSunBands {
  std::vector<float> visibility;  // per pixel, 0..1; NaN where sky
  std::vector<float> direct_now;  // W/m²; NaN where sky
  std::map<std::string, std::string> metadata;
  std::string summary;  // "sun at azimuth .., elevation ..; 42.1% of pixels sunlit (exact)"
};

// Places the sun for the scene (its CRS's centre, or --lat/--lon), throws skyview::Error when it
// is below the horizon, and shades every pixel that sees the scene. `eye` is the camera's position
// (scene-local) for the cascaded methods.
RenderSunBands render_sun(const RenderSunOptions& o, const Scene& scene, const RayScene& rays, const ViewBuffers& view,
                          const Vec3d& eye);

}  // namespace skyview::cli
