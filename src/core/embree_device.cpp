#include "core/embree_device.h"

#include "skyview/core/error.h"

namespace skyview::detail {
namespace {

void keep_first_error(void* user, RTCError code, const char* message) {
  auto* first = static_cast<std::string*>(user);
  if (first->empty())
    first->assign("Embree error " + std::to_string(static_cast<int>(code)) + ": " + (message ? message : ""));
}

}  // namespace

EmbreeDevice new_embree_device(std::string& failure, bool need_filters) {
  EmbreeDevice device(rtcNewDevice(nullptr));
  if (!device) throw Error("cannot start Embree");
  if (need_filters && !rtcGetDeviceProperty(device.get(), RTC_DEVICE_PROPERTY_FILTER_FUNCTION_SUPPORTED)) {
    throw Error("this Embree was built without filter functions, which the ray cast needs");
  }
  rtcSetDeviceErrorFunction(device.get(), keep_first_error, &failure);
  return device;
}

}  // namespace skyview::detail
