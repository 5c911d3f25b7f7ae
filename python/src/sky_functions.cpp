// skyview.skymap: `skyview skymap` without its files: the directional exposure map of the sky over
// a period, bands direct and diffuse (Wh m-2 sr-1), rows from the zenith down, columns clockwise
// from north (exposure_map.h).
#include "arrays.h"
#include "bindings.h"
#include "skyview/core/error.h"
#include "skyview/sky/sky_request.h"

namespace skyview::python {

namespace {

py::tuple skymap(const SkyRequest& request, std::optional<int> size_given, int threads) {
  const int size = size_given.value_or(ExposureOptions{}.width);  // the command line's --size default
  if (size < 8 || size > 8192) throw UsageError("size must be within 8 .. 8192");
  check_sky_request(request);
  make_sky_model(request);  // its options' errors before any file is read
  PreparedSky sky = prepare_sky(request);
  ExposureMap map{1, 1};
  {
    py::gil_scoped_release computing;
    const ThreadLimit limit(threads);
    map = make_exposure_map(sky, size);
  }
  warn_all(sky.warnings);
  py::dict bands;
  bands["direct"] = to_numpy(std::move(map.band(ExposureBand::direct)), {map.height(), map.width()});
  bands["diffuse"] = to_numpy(std::move(map.band(ExposureBand::diffuse)), {map.height(), map.width()});
  py::dict metadata;
  for (const auto& [key, value] : sky.metadata) metadata[py::str(key)] = value;
  return py::make_tuple(bands, metadata);
}

}  // namespace

void bind_sky_functions(py::module_& m) {
  using namespace pybind11::literals;
  // skyview/__init__.py names the period's ends from_ and to, and turns datetime64 into text.
  m.def(
      "_skymap",
      [](std::optional<std::string> from, std::optional<std::string> to, std::optional<double> lat,
         std::optional<double> lon, std::optional<double> elevation, std::optional<std::string> step,
         std::optional<std::string> tz, std::optional<std::string> sky, std::optional<double> turbidity,
         std::optional<double> albedo, std::optional<double> luminous_efficacy, std::optional<std::string> epw,
         std::optional<int> size, int threads) {
        SkyRequest r;  // the command line's defaults
        if (from) r.from = *from;
        if (to) r.to = *to;
        r.latitude = lat;
        r.longitude = lon;
        r.elevation = elevation;
        if (step) r.step = *step;
        if (tz) r.tz = *tz;
        if (sky) r.sky = *sky;
        if (turbidity) r.turbidity = *turbidity;
        if (albedo) r.albedo = *albedo;
        if (luminous_efficacy) r.luminous_efficacy = *luminous_efficacy;
        if (epw) r.epw = *epw;
        return skymap(r, size, threads);
      },
      "from_"_a, "to"_a, "lat"_a, "lon"_a, "elevation"_a, "step"_a, "tz"_a, "sky"_a, "turbidity"_a, "albedo"_a,
      "luminous_efficacy"_a, "epw"_a, "size"_a, "threads"_a);
}

}  // namespace skyview::python
