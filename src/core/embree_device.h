#pragma once
// Embree's device and scene handles, owned, and a device whose errors are collected rather than
// lost: Embree reports them through a C callback that must not throw, so the first one is kept in
// a string the caller turns into a skyview::Error once the call that caused it returns.
#include <embree3/rtcore.h>

#include <memory>
#include <string>

namespace skyview::detail {

struct EmbreeDeviceDeleter {
  void operator()(RTCDeviceTy* d) const { rtcReleaseDevice(d); }
};
struct EmbreeSceneDeleter {
  void operator()(RTCSceneTy* s) const { rtcReleaseScene(s); }
};
using EmbreeDevice = std::unique_ptr<RTCDeviceTy, EmbreeDeviceDeleter>;
using EmbreeScene = std::unique_ptr<RTCSceneTy, EmbreeSceneDeleter>;

// A new device whose first error lands in `failure` (which must outlive it). With
// `need_filters`, refuses an Embree built without filter functions. Throws skyview::Error.
EmbreeDevice new_embree_device(std::string& failure, bool need_filters);

}  // namespace skyview::detail
