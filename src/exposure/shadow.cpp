// Shadows at one instant from the horizon along the sun's azimuth.
#include "skyview/exposure/shadow.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "exposure/horizon_feed.h"
#include "skyview/core/error.h"
#include "skyview/core/number_text.h"
#include "skyview/exposure/sun_horizon.h"

namespace skyview {

HorizonParams shadow_horizon_params(HorizonParams base, double sun_azimuth) {
  base.directions = 1;
  base.azimuth_origin = AzimuthOrigin::north;
  base.spacing = AzimuthSpacing::uniform;
  base.azimuth_offset = sun_azimuth;
  base.lower = false;
  return base;
}

ShadowBands compute_shadow(const HorizonEngine& engine, const Terrain& terrain, const Window& window,
                           const ShadowRequest& request, ProgressCounter& progress) {
  if (!(request.sun_elevation > 0.0)) {
    throw Error("the sun's centre is " + number_text(request.sun_elevation * 180 / std::numbers::pi) +
                " degrees below the horizon: there is no shadow to cast");
  }
  const double rotation = direction_set_rotation(engine.params(), terrain);
  if (engine.params().directions != 1 ||
      std::abs(std::remainder(rotation - request.sun_azimuth, 2 * std::numbers::pi)) > 1e-9) {
    throw Error("shadows need the horizon engine turned to the sun (shadow_horizon_params)");
  }
  const SunStep sun = sun_step(request.sun_azimuth, request.sun_elevation);
  ShadowBands out;
  out.sunlit = Grid<float>(window.cols, window.rows, std::numeric_limits<float>::quiet_NaN());
  out.incidence_cos = out.sunlit;
  // One direction: the test of sun_horizon.h with the sun on it (f = 0).
  const SunBracket at_sun = bracket_azimuth(request.sun_azimuth, 1, rotation);
  struct Consumer final : detail::HorizonConsumer {
    const Terrain& t;
    Window block;
    int row0;
    const ShadowRequest& r;
    const SunStep& sun;
    const SunBracket& at_sun;
    ShadowBands& out;
    Consumer(const Terrain& terrain, const Window& b, int first_row, const ShadowRequest& request, const SunStep& s,
             const SunBracket& bracket, ShadowBands& bands)
        : t(terrain), block(b), row0(first_row), r(request), sun(s), at_sun(bracket), out(bands) {}
    void add(int, int, const float* upper, const HorizonField&) override {
      for (int wr = 0; wr < block.rows; ++wr) {
        for (int wc = 0; wc < block.cols; ++wc) {
          const float h = upper[static_cast<std::size_t>(wr) * block.cols + wc];
          if (std::isnan(h)) continue;
          const double horizon = horizon_towards(at_sun, h, h);
          const double d = r.sun_elevation - horizon;
          out.sunlit(wc, row0 + wr) =
              static_cast<float>(r.soft ? visible_disc_fraction(d, r.disc_radius) : (d > 0.0 ? 1.0 : 0.0));
          double slope, aspect;
          horn_slope_aspect(t, block.col0 + wc, block.row0 + wr, slope, aspect);
          const double cosine =
              std::cos(slope) * sun.direction[2] +
              std::sin(slope) * (std::sin(aspect) * sun.direction[0] + std::cos(aspect) * sun.direction[1]);
          out.incidence_cos(wc, row0 + wr) = static_cast<float>(cosine);
        }
      }
    }
    void finish() override {}
  };
  detail::feed_horizons(engine, terrain, window, progress, kHorizonBlockBytes, [&](const Window& block) {
    return std::make_unique<Consumer>(terrain, block, block.row0 - window.row0, request, sun, at_sun, out);
  });
  if (request.edge == EdgeMode::nodata && std::isfinite(engine.radius())) {
    for (int r = 0; r < window.rows; ++r) {
      for (int c = 0; c < window.cols; ++c) {
        if (!search_circle_leaves_raster(terrain, window.col0 + c, window.row0 + r, engine.radius())) continue;
        ++out.edge_cells;
        out.sunlit(c, r) = out.incidence_cos(c, r) = std::numeric_limits<float>::quiet_NaN();
      }
    }
  }
  return out;
}

}  // namespace skyview
