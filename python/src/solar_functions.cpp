// skyview.sun_position: `skyview sun --csv` over an array of instants at once.
#include <pybind11/numpy.h>

#include <cmath>
#include <limits>

#include "bindings.h"
#include "skyview/core/error.h"
#include "skyview/solar/solar_position.h"

namespace skyview::python {

namespace py = pybind11;

namespace {

// The columns of `skyview sun --csv` after time_utc and time_local, by the same names.
struct Column {
  const char* name;
  double SunPosition::*value;
};
constexpr Column kColumns[] = {{"zenith_deg", &SunPosition::zenith_deg},
                               {"azimuth_deg", &SunPosition::azimuth_deg},
                               {"elevation_deg", &SunPosition::elevation_deg},
                               {"declination_deg", &SunPosition::declination_deg},
                               {"right_ascension_deg", &SunPosition::right_ascension_deg},
                               {"earth_sun_distance_au", &SunPosition::earth_sun_distance_au},
                               {"equation_of_time_min", &SunPosition::equation_of_time_min},
                               {"delta_t_s", &SunPosition::delta_t_s}};

// `unix_seconds`: UTC seconds since 1970 (NaN: not a time, giving NaN everywhere).
py::dict sun_position(const py::array_t<double, py::array::c_style | py::array::forcecast>& unix_seconds,
                      const Site& site) {
  validate_site(site);
  const py::ssize_t n = unix_seconds.size();
  constexpr std::size_t kCount = std::size(kColumns);
  std::vector<std::vector<double>> out(kCount, std::vector<double>(static_cast<std::size_t>(n)));
  const double* t = unix_seconds.data();
  {
    py::gil_scoped_release computing;
    for (py::ssize_t i = 0; i < n; ++i) {
      const auto j = static_cast<std::size_t>(i);
      if (std::isnan(t[i])) {
        for (auto& column : out) column[j] = std::numeric_limits<double>::quiet_NaN();
        continue;
      }
      const SunPosition s = solar_position(t[i], site);
      for (std::size_t c = 0; c < kCount; ++c) out[c][j] = s.*kColumns[c].value;
    }
  }
  std::vector<py::ssize_t> shape(unix_seconds.shape(), unix_seconds.shape() + unix_seconds.ndim());
  py::dict columns;
  for (std::size_t c = 0; c < kCount; ++c) {
    py::array_t<double> a(shape);
    std::copy(out[c].begin(), out[c].end(), a.mutable_data());
    columns[kColumns[c].name] = a;
  }
  return columns;
}

}  // namespace

void bind_solar_functions(py::module_& m) {
  using namespace pybind11::literals;
  // skyview/__init__.py turns datetime64 into Unix seconds and calls this.
  m.def(
      "_sun_position_unix",
      [](const py::array_t<double, py::array::c_style | py::array::forcecast>& unix_seconds, double lat, double lon,
         double elevation, std::optional<double> pressure, std::optional<double> temperature,
         std::optional<double> delta_t, double delta_ut1) {
        if (!(std::abs(lat) <= 90.0)) throw UsageError("lat " + std::to_string(lat) + " is outside -90..90 degrees");
        if (!(std::abs(lon) <= 180.0)) throw UsageError("lon " + std::to_string(lon) + " is outside -180..180 degrees");
        Site site;  // the command line's defaults
        site.latitude_deg = lat;
        site.longitude_deg = lon;
        site.elevation_m = elevation;
        if (pressure) site.pressure_mbar = *pressure;
        if (temperature) site.temperature_c = *temperature;
        if (delta_t) {
          if (!(std::abs(*delta_t) <= 1e6)) throw UsageError("delta_t is outside -1e6..1e6 s");
          site.delta_t_s = *delta_t;
        }
        site.delta_ut1_s = delta_ut1;
        return sun_position(unix_seconds, site);
      },
      "unix_seconds"_a, "lat"_a, "lon"_a, "elevation"_a, "pressure"_a, "temperature"_a, "delta_t"_a, "delta_ut1"_a);
}

}  // namespace skyview::python
