#pragma once
// Variable names for netCDF outputs (see netcdf_names.cpp).
#include <string>
#include <vector>

namespace skyview::detail {

// Renames the variables GDAL wrote for bands 1..N of the netCDF file at `path` (Band1, Band2 ...)
// after `names` (the bands' descriptions) and gives each its name as long_name. Throws Error when
// the file cannot be changed; a name that would clash with a variable already there (x, y, the
// grid mapping) keeps GDAL's. `path` in the global history attribute becomes `final_path`, the
// name the file is about to be moved to.
void name_netcdf_variables(const std::string& path, const std::string& final_path,
                           const std::vector<std::string>& names);

}  // namespace skyview::detail
