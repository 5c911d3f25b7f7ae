// sun_visibility: checks the sun, the receivers and the options, then runs one method and times it.
#include "skyview/render/shadow_maps.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <cmath>
#include <numbers>

#include "render/shadow_methods.h"
#include "skyview/core/error.h"
#include "skyview/core/number_text.h"

namespace skyview {

namespace {

constexpr int kMinMapSize = 8;

std::string bytes_text(double bytes) { return number_text(std::round(bytes / (1 << 20))) + " MiB"; }

void check_count(const char* name, int value, int lo, int hi) {
  if (value < lo || value > hi) {
    throw UsageError(std::string(name) + ": " + std::to_string(value) + " is out of range; give " + std::to_string(lo) +
                     " .. " + std::to_string(hi));
  }
}

void check_share(const char* name, double value, bool open_top) {
  if (!(value >= 0.0 && (open_top ? value < 1.0 : value <= 1.0))) {
    throw UsageError(std::string(name) + ": " + number_text(value) + " is out of range; give 0 .. 1" +
                     (open_top ? " (1 excluded)" : ""));
  }
}

}  // namespace

std::string shadow_method_name(ShadowMethod method) {
  switch (method) {
    case ShadowMethod::exact:
      return "exact";
    case ShadowMethod::pcf:
      return "pcf";
    case ShadowMethod::vsm:
      return "vsm";
    case ShadowMethod::lvsm:
      return "lvsm";
    case ShadowMethod::csm:
      return "csm";
    case ShadowMethod::hsm:
      return "hsm";
  }
  return "exact";
}

ShadowMethod parse_shadow_method(const std::string& name) {
  for (ShadowMethod m : {ShadowMethod::exact, ShadowMethod::pcf, ShadowMethod::vsm, ShadowMethod::lvsm,
                         ShadowMethod::csm, ShadowMethod::hsm}) {
    if (shadow_method_name(m) == name) return m;
  }
  throw UsageError("shadows: unknown method '" + name + "'; give exact, pcf, vsm, lvsm, csm or hsm");
}

Vec3f sun_direction_of(double azimuth, double elevation) {
  return {static_cast<float>(std::sin(azimuth) * std::cos(elevation)),
          static_cast<float>(std::cos(azimuth) * std::cos(elevation)), static_cast<float>(std::sin(elevation))};
}

void validate_shadow_options(ShadowMethod method, const ShadowOptions& o) {
  const bool maps = method != ShadowMethod::exact;
  const bool cascaded = method == ShadowMethod::csm || method == ShadowMethod::hsm;
  if (method == ShadowMethod::exact) {
    if (o.soft) check_count("soft_samples", o.soft_samples, 1, 4096);
    if (!(o.ray_offset >= 0.0 && o.ray_offset < 10.0)) {
      throw UsageError("ray_offset: " + number_text(o.ray_offset) + " m is out of range; give 0 .. 10");
    }
    if (!(o.sun_angular_radius > 0.0 && o.sun_angular_radius < 0.1)) {
      throw UsageError("sun_angular_radius: " + number_text(o.sun_angular_radius) +
                       " rad is out of range; give 0 .. 0.1 (the sun's is 0.00465)");
    }
  }
  if (!maps) return;
  if (o.map_size < kMinMapSize) {
    throw UsageError("map_size: " + std::to_string(o.map_size) + " texels; a shadow map needs at least " +
                     std::to_string(kMinMapSize) + " on a side");
  }
  const int maps_held = cascaded ? std::max(o.cascades, 1) : 1;
  const double bytes = static_cast<double>(o.map_size) * o.map_size * sizeof(float) * maps_held;
  if (bytes > static_cast<double>(o.max_map_bytes)) {
    throw UsageError("map_size: " + std::to_string(o.map_size) + " x " + std::to_string(o.map_size) + " texels" +
                     (cascaded ? " x " + std::to_string(o.cascades) + " cascades" : std::string()) + " need " +
                     bytes_text(bytes) + ", more than the limit of " +
                     bytes_text(static_cast<double>(o.max_map_bytes)) + " (max_map_bytes)");
  }
  check_count("pcf_kernel", o.pcf_kernel, 1, 15);
  if (o.pcf_kernel % 2 == 0) {
    throw UsageError("pcf_kernel: " + std::to_string(o.pcf_kernel) + " is even; give an odd number of taps");
  }
  if (!(o.depth_bias >= 0.0 && o.slope_bias >= 0.0)) {
    throw UsageError("depth_bias, slope_bias: must not be negative");
  }
  if (method == ShadowMethod::vsm || method == ShadowMethod::lvsm || method == ShadowMethod::hsm) {
    if (!(o.min_variance >= 0.0)) {
      throw UsageError("min_variance: " + number_text(o.min_variance) + " must not be negative");
    }
    check_share("light_bleed_reduction", o.light_bleed_reduction, /*open_top=*/true);
  }
  if (method == ShadowMethod::lvsm) check_count("layers", o.layers, 1, 64);
  if (method == ShadowMethod::hsm) check_count("hsm_layers", o.hsm_layers, 1, 64);
  if (method == ShadowMethod::lvsm || method == ShadowMethod::hsm) check_share("layer_overlap", o.layer_overlap, false);
  if (cascaded) {
    check_count("cascades", o.cascades, 1, 16);
    check_share(method == ShadowMethod::csm ? "split_lambda" : "hsm_split_lambda",
                method == ShadowMethod::csm ? o.split_lambda : o.hsm_split_lambda, false);
    if (!o.eye) {
      throw UsageError("eye: " + shadow_method_name(method) +
                       " splits the receivers by their distance from the eye; give its position");
    }
  }
}

namespace detail {

void single_map_visibility(const RayScene& rays, const LightFrame& frame, const std::vector<LightReceiver>& receivers,
                           ShadowMethod method, const ShadowOptions& o, ShadowResult& out) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  const DepthMap map = render_depth_map(rays, frame, receivers, {}, o.map_size, filter_pad(o.pcf_kernel));
  const std::vector<double> bounds =
      method == ShadowMethod::lvsm ? layer_bounds(map, o.layers, /*logarithmic=*/false) : std::vector<double>{};
  const auto t1 = Clock::now();
  out.visibility.assign(receivers.size(), 0.0f);
  out.texel.assign(receivers.size(), static_cast<float>(map.texel));
  const double inf = std::numeric_limits<double>::infinity();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, receivers.size(), 512), [&](const auto& range) {
    for (std::size_t k = range.begin(); k != range.end(); ++k) {
      double v = 0.0;
      switch (method) {
        case ShadowMethod::pcf:
          v = pcf_lookup(map, receivers[k], o);
          break;
        case ShadowMethod::vsm:
          v = variance_lookup(map, receivers[k], o, -inf, inf);
          break;
        default:
          v = layered_lookup(map, bounds, receivers[k], o, o.layer_overlap);
          break;
      }
      out.visibility[k] = static_cast<float>(v);
    }
  });
  out.map_seconds = std::chrono::duration<double>(t1 - t0).count();
  out.lookup_seconds = std::chrono::duration<double>(Clock::now() - t1).count();
  out.map_bytes = map.bytes();
  out.maps = 1;
}

}  // namespace detail

ShadowResult sun_visibility(const RayScene& rays, const Scene& scene, Vec3f sun_direction,
                            const ShadowReceivers& receivers, ShadowMethod method, const ShadowOptions& options) {
  (void)scene;  // the hierarchy holds the geometry; the scene is the caller's promise that they match
  const double len =
      std::sqrt(double(sun_direction[0]) * sun_direction[0] + double(sun_direction[1]) * sun_direction[1] +
                double(sun_direction[2]) * sun_direction[2]);
  if (!(len > 0.0) || !std::isfinite(len)) throw Error("the sun's direction is zero or not a number");
  const double elevation = std::asin(std::clamp(sun_direction[2] / len, -1.0, 1.0)) * 180.0 / std::numbers::pi;
  if (!(elevation > 0.0)) {
    throw Error("the sun's centre is at " + number_text(std::round(elevation * 100) / 100) +
                " degrees elevation, not above the horizon: there are no sun shadows to cast");
  }
  if (!receivers.normals.empty() && receivers.normals.size() != receivers.points.size()) {
    throw UsageError("receivers: " + std::to_string(receivers.normals.size()) + " normals for " +
                     std::to_string(receivers.points.size()) + " points; give one per point or none");
  }
  validate_shadow_options(method, options);
  ShadowResult out;
  if (receivers.points.empty()) return out;
  const detail::Vec3 sun{sun_direction[0] / len, sun_direction[1] / len, sun_direction[2] / len};
  if (method == ShadowMethod::exact) {
    const auto t0 = std::chrono::steady_clock::now();
    out.visibility = detail::exact_visibility(rays, sun, receivers, options);
    out.texel.assign(receivers.points.size(), 0.0f);
    out.lookup_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return out;
  }
  const detail::LightFrame frame(sun, rays.bounds());
  const std::vector<detail::LightReceiver> light = detail::light_receivers(frame, receivers);
  if (method == ShadowMethod::csm || method == ShadowMethod::hsm) {
    detail::cascaded_visibility(rays, frame, light, receivers.points, method, options, out);
  } else {
    detail::single_map_visibility(rays, frame, light, method, options, out);
  }
  return out;
}

}  // namespace skyview
