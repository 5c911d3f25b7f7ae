#include "skyview/render/camera.h"

#include <cmath>
#include <cstdlib>
#include <numbers>
#include <sstream>

#include "skyview/core/error.h"

namespace skyview {
namespace {

Vec3d sub(const Vec3d& a, const Vec3d& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const Vec3d& a, const Vec3d& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double norm(const Vec3d& a) { return std::sqrt(dot(a, a)); }
Vec3d scaled(const Vec3d& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }

bool finite3(const Vec3d& v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

}  // namespace

Camera::Camera(const CameraSpec& spec, const Vec3d& scene_origin) : spec_(spec) {
  if (!finite3(spec.position)) throw UsageError("--camera must be three finite numbers");
  if (!finite3(spec.look_at)) throw UsageError("--look-at must be three finite numbers");
  if (spec.width < 1 || spec.height < 1 || spec.width > 16384 || spec.height > 16384) {
    throw UsageError("--size must be WIDTHxHEIGHT with each from 1 to 16384 pixels, not " + std::to_string(spec.width) +
                     "x" + std::to_string(spec.height));
  }
  if (spec.orthographic_width < 0 || !std::isfinite(spec.orthographic_width)) {
    throw UsageError("--orthographic must be a positive width in metres");
  }
  if (spec.orthographic_width == 0 && !(spec.fov_deg > 0 && spec.fov_deg < 180)) {
    throw UsageError("--fov must be above 0 and below 180 degrees");
  }
  const Vec3d view = sub(spec.look_at, spec.position);
  const double length = norm(view);
  if (!(length > 1e-6)) throw UsageError("--look-at must differ from --camera (the view has no direction)");
  forward_ = scaled(view, 1.0 / length);
  const double up_length = norm(spec.up);
  if (!(up_length > 0) || !finite3(spec.up)) throw UsageError("--up must be a non-zero vector");
  Vec3d r = cross(forward_, scaled(spec.up, 1.0 / up_length));
  const double r_length = norm(r);
  if (r_length < 1e-6) throw UsageError("--up must not point along the view (--look-at minus --camera)");
  right_ = scaled(r, 1.0 / r_length);
  image_up_ = cross(right_, forward_);
  eye_ = sub(spec.position, scene_origin);
  const double aspect = double(spec.width) / spec.height;
  if (orthographic()) {
    half_w_ = spec.orthographic_width / 2;
    half_h_ = half_w_ / aspect;
  } else {
    half_h_ = std::tan(spec.fov_deg * std::numbers::pi / 360.0);
    half_w_ = half_h_ * aspect;
  }
}

CameraRay Camera::ray(double col, double row) const {
  const double u = (2.0 * col / spec_.width - 1.0) * half_w_;
  const double v = (1.0 - 2.0 * row / spec_.height) * half_h_;
  CameraRay r;
  if (orthographic()) {
    for (int k = 0; k < 3; ++k) {
      r.origin[k] = float(eye_[k] + u * right_[k] + v * image_up_[k]);
      r.direction[k] = float(forward_[k]);
    }
  } else {
    Vec3d d{};
    for (int k = 0; k < 3; ++k) d[k] = forward_[k] + u * right_[k] + v * image_up_[k];
    const double n = norm(d);
    for (int k = 0; k < 3; ++k) {
      r.origin[k] = float(eye_[k]);
      r.direction[k] = float(d[k] / n);
    }
  }
  return r;
}

void Camera::project(const Vec3d& p, double& col, double& row, double& depth) const {
  const Vec3d d = sub(p, eye_);
  depth = dot(d, forward_);
  double u = dot(d, right_), v = dot(d, image_up_);
  if (!orthographic()) {
    if (depth <= 0) {
      col = row = -1;
      return;
    }
    u /= depth;
    v /= depth;
  }
  col = (u / half_w_ + 1.0) * spec_.width / 2.0;
  row = (1.0 - v / half_h_) * spec_.height / 2.0;
}

double Camera::pixels_per_metre(double depth) const {
  const double per_unit = spec_.height / (2.0 * half_h_);
  return orthographic() ? per_unit : per_unit / std::max(depth, 1e-6);
}

Vec3d parse_vec3(const std::string& text, const std::string& option) {
  Vec3d v{};
  const char* p = text.c_str();
  for (int k = 0; k < 3; ++k) {
    char* end = nullptr;
    v[k] = std::strtod(p, &end);
    if (end == p || !std::isfinite(v[k]))
      throw UsageError(option + " must be X,Y,Z (three numbers), not '" + text + "'");
    p = end;
    if (k < 2) {
      if (*p != ',') throw UsageError(option + " must be X,Y,Z (three numbers), not '" + text + "'");
      ++p;
    }
  }
  if (*p != '\0') throw UsageError(option + " must be X,Y,Z (three numbers), not '" + text + "'");
  return v;
}

void parse_size(const std::string& text, int& width, int& height, const std::string& option) {
  const std::size_t x = text.find_first_of("xX");
  const auto whole = [](const std::string& s, int& out) {
    if (s.empty() || s.size() > 6 || s.find_first_not_of("0123456789") != std::string::npos) return false;
    out = std::stoi(s);
    return true;
  };
  if (x == std::string::npos || !whole(text.substr(0, x), width) || !whole(text.substr(x + 1), height) || width < 1 ||
      height < 1 || width > 16384 || height > 16384) {
    throw UsageError(option + " must be WIDTHxHEIGHT in pixels, each from 1 to 16384, not '" + text + "'");
  }
}

}  // namespace skyview
