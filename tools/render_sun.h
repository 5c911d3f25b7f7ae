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
#include "skyview/render/two_scale_visibility.h"
#include "skyview/render/view_buffers.h"
#include "skyview/scene/ray_scene.h"
#include "skyview/scene/scene.h"
#include "skyview/sky/exposure_pyramid.h"
#include "skyview/sky/exposure_sampler.h"
#include "skyview/sky/sky_model.h"
#include "skyview/solar/solar_position.h"

namespace skyview::cli {

struct RenderSunOptions {
  std::string time, tz;
  std::optional<double> lat, lon, elevation;
  std::string shadows = "exact";
  bool soft = false;
  ShadowOptions shadow;       // --shadow-map-size, --cascades
  std::optional<int> layers;  // lvsm: ShadowOptions::layers, hsm: hsm_layers
  double turbidity = 3.0;
  std::string colour_out;   // --colour-out: the view in colour (colour_view.h)
  std::string shadow_diff;  // --shadow-diff: the map method against exact rays
};

// --time, --tz, --lat, --lon, --elevation, --shadows, --soft, --shadow-map-size, --cascades,
// --layers, --turbidity, --colour-out, --shadow-diff.
void add_render_sun_options(CLI::App& app, RenderSunOptions& o);

// Checks before any work: without --time every sun option is refused; the method's options go
// through validate_shadow_options (UsageError naming the command-line option).
void check_render_sun_options(const CLI::App& app, RenderSunOptions& o);

// The first sun band's name: sunlit, or sun_fraction with --soft.
std::string sun_band_name(const RenderSunOptions& o);

// The sun at --time for the scene: its CRS's centre, or --lat/--lon.
struct SunInstant {
  double unix_utc = 0;
  Site site;
  std::string site_source;
  SunPosition position;
  double grid_azimuth = 0;   // radians clockwise from the scene's +y (grid north)
  Vec3f direction{0, 0, 1};  // unit, towards the sun, in the scene's frame
  // For the sky models, in the view's frame: the sun's azimuth on the grid.
  SkyConditions conditions;
  double direct_normal = 0;  // W/m², the Preetham sun at --turbidity
};

// Throws skyview::Error naming the sun's elevation when it is below the horizon.
SunInstant place_sun(const RenderSunOptions& o, const Scene& scene);

// The diffuse sky at the instant as an exposure map of one hour of its radiance (so the map's
// Wh m-2 sr-1 are W m-2 sr-1 and what the sampler integrates is irradiance, W/m²), read by the same
// sampler render's exposure bands use: diffuse_now is the two-scale visibility's exposure_diffuse
// with this sampler, never a second integrator.
class InstantSky {
 public:
  InstantSky(const RenderSunOptions& o, const SunInstant& sun, int directions);
  const ExposureSampler& sampler() const { return sampler_; }
  double diffuse_horizontal() const { return diffuse_horizontal_; }  // the model's own, W/m²
  int map_width() const { return width_; }
  int map_height() const { return height_; }

 private:
  int width_, height_;
  double diffuse_horizontal_;
  ExposurePyramid pyramid_;
  ExposureSampler sampler_;
};

// W/m² per pixel from the exposure bands of a two_scale_visibility run with InstantSky's sampler.
std::vector<float> diffuse_now_of(const TwoScaleBands& bands);

struct RenderSunBands {
  std::vector<float> visibility;   // per pixel, 0..1; NaN where sky
  std::vector<float> direct_now;   // W/m²; NaN where sky
  std::vector<float> diffuse_now;  // W/m²; NaN where sky
  std::vector<float> global_now;   // direct_now + diffuse_now
  std::vector<float> exact;        // with a map method: the exact rays' visibility per pixel, else empty
  std::map<std::string, std::string> metadata;
  std::string summary;  // "sun at azimuth .., elevation ..; 42.1% of pixels sunlit (exact)"
};

// Shades every pixel that sees the scene. `eye` is the camera's position (scene-local) for the
// cascaded methods; `diffuse_now` from diffuse_now_of. With a shadow-map method the exact rays are
// traced too and the method's error against them (shadow_error.h) goes into the metadata.
RenderSunBands render_sun(const RenderSunOptions& o, const SunInstant& sun, const InstantSky& sky, const Scene& scene,
                          const RayScene& rays, const ViewBuffers& view, const Vec3d& eye,
                          std::vector<float> diffuse_now);

// Writes --colour-out and --shadow-diff where asked.
void write_render_sun_pictures(const RenderSunOptions& o, const SunInstant& sun, const RenderSunBands& bands,
                               const Camera& camera, const ViewBuffers& view, bool overwrite);

}  // namespace skyview::cli
