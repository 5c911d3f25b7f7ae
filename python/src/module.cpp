// skyview._skyview: the library's functions on NumPy arrays (docs/python.md). The package
// python/skyview/ re-exports them and adds the xarray and Dask front ends.
#include "bindings.h"
#include "skyview/core/error.h"
#include "skyview/core/version.h"
#include "skyview/raster/raster_read.h"

PYBIND11_MODULE(_skyview, m) {
  m.doc() = "skyview's library on NumPy arrays: svf, horizon, exposure, sun_position, skymap, read_las";
  // One exception for every failure the command line reports in one line, a ValueError: the
  // caller's values (options, heights, files) are what is wrong.
  static pybind11::exception<skyview::Error> error(m, "Error", PyExc_ValueError);
  pybind11::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const skyview::Error& e) {
      PyErr_SetString(error.ptr(), e.what());
    }
  });
  skyview::init_gdal();
  m.attr("__version__") = skyview::version();
  skyview::python::bind_horizon_functions(m);
  skyview::python::bind_solar_functions(m);
  skyview::python::bind_sky_functions(m);
  skyview::python::bind_las_functions(m);
  skyview::python::bind_exposure_functions(m);
}
