#pragma once
// Each file of the module adds its functions to it.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

namespace skyview::python {

void bind_horizon_functions(pybind11::module_& m);   // svf, horizon
void bind_solar_functions(pybind11::module_& m);     // sun_position
void bind_sky_functions(pybind11::module_& m);       // skymap
void bind_las_functions(pybind11::module_& m);       // read_las
void bind_exposure_functions(pybind11::module_& m);  // exposure

}  // namespace skyview::python
