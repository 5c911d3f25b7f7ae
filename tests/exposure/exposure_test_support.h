#pragma once
// Helpers for the exposure tests: a sky over a short period, and a run of compute_exposure.
#include <gtest/gtest.h>

#include <string>

#include "skyview/exposure/exposure.h"
#include "skyview/sky/sky_request.h"
#include "skyview/synthetic/synthetic.h"

namespace skyview::test {

constexpr double kDegree = M_PI / 180.0;

// The map (size × size) and the sun steps of `request`.
inline ExposureSky make_sky(const SkyRequest& request, int size) {
  PreparedSky prepared = prepare_sky(request);
  ExposureSky sky;
  sky.map = make_exposure_map(prepared, size);
  sky.sun = sun_steps(*prepared.model, prepared.steps);
  return sky;
}

inline SkyRequest clear_sky(double lat, const std::string& from, const std::string& to, const std::string& step,
                            const std::string& model = "preetham") {
  SkyRequest r;
  r.sky = model;
  r.latitude = lat;
  r.longitude = 0.0;
  r.from = from;
  r.to = to;
  r.step = step;
  return r;
}

// A square terrain of `size` cells of `cell` metres around the origin.
inline Terrain terrain_of(const HeightFunction& f, int size, double cell) {
  return rasterize(f, size, size, local_grid(size, size, cell));
}

inline ExposureBands run_exposure(const Terrain& t, const ExposureSky& sky, ExposureMethod method, int directions,
                                  const std::string& horizon_method = "sweep") {
  HorizonParams p;
  p.directions = directions;
  p.azimuth_origin = AzimuthOrigin::grid;
  const auto engine = make_horizon_engine(horizon_method, p);
  ExposureRequest request;
  request.method = method;
  ProgressCounter progress;
  return compute_exposure(*engine, t, Window::whole(t), sky, request, progress);
}

}  // namespace skyview::test
