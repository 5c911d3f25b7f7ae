#pragma once
// A camera looking at a Scene: perspective (vertical field of view) or orthographic (view width in
// metres), in the scene's projected CRS. Rays are returned in the scene's local frame (relative to
// Scene::origin, z up), the frame RayScene takes. Pixel (0, 0) is the top-left; row 0 at the top.
#include <string>

#include "skyview/scene/scene.h"

namespace skyview {

struct CameraSpec {
  Vec3d position{0, 0, 0};  // world coordinates (the scene's CRS, metres)
  Vec3d look_at{0, 0, 0};
  Vec3d up{0, 0, 1};
  double fov_deg = 60.0;          // vertical field of view (perspective)
  double orthographic_width = 0;  // > 0: orthographic, the view's width in metres
  int width = 800, height = 600;  // pixels
};

struct CameraRay {
  Vec3f origin;     // scene-local
  Vec3f direction;  // unit
};

class Camera {
 public:
  // Throws skyview::UsageError (one line, naming the option) for a look-at equal to the position,
  // an up vector along the view, a field of view outside (0, 180) degrees, a non-positive
  // orthographic width or a size below 1x1 or above 16384x16384.
  Camera(const CameraSpec& spec, const Vec3d& scene_origin);

  const CameraSpec& spec() const { return spec_; }
  int width() const { return spec_.width; }
  int height() const { return spec_.height; }
  bool orthographic() const { return spec_.orthographic_width > 0; }
  // The ray through the centre of pixel (col + 0.5, row + 0.5); fractional pixels for subsamples.
  CameraRay ray(double col, double row) const;
  // Local-frame camera position and unit axes: forward (into the view), right, up (of the image).
  const Vec3d& eye() const { return eye_; }
  const Vec3d& forward() const { return forward_; }
  const Vec3d& right() const { return right_; }
  const Vec3d& image_up() const { return image_up_; }
  // Where a scene-local point lands in the image (pixel coordinates, col and row as ray() takes
  // them) and its depth along `forward`; depth <= 0 behind the camera.
  void project(const Vec3d& p, double& col, double& row, double& depth) const;
  // Pixels per metre at `depth` (perspective) or everywhere (orthographic).
  double pixels_per_metre(double depth) const;

 private:
  CameraSpec spec_;
  Vec3d eye_, forward_, right_, image_up_;
  double half_h_ = 0, half_w_ = 0;  // tan(fov/2)·aspect terms, or half the view in metres
};

// "X,Y,Z" -> three finite numbers; throws UsageError naming `option` otherwise.
Vec3d parse_vec3(const std::string& text, const std::string& option);
// "WxH" -> width and height; throws UsageError naming `option` otherwise.
void parse_size(const std::string& text, int& width, int& height, const std::string& option);

}  // namespace skyview
