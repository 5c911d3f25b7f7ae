// GDAL 3.6 names the variables of a netCDF file it creates band by band Band1, Band2 ..., gives
// them long_name "GDAL Band Number N" and refuses to set another (SetMetadataItem fails). Readers
// of netCDF (xarray, CDO, ncview, Panoply) go by variable names, so a file of five products would
// come out as five anonymous bands. The finished file is renamed in place with libnetcdf (the
// library GDAL's driver itself uses) before it is moved to its final name; the global `history`
// GDAL writes names the temporary file it created, so that name becomes the final one.
#include "raster/netcdf_names.h"

#include <netcdf.h>

#include <cctype>

#include "skyview/core/error.h"
#include "skyview/raster/temporary_outputs.h"

namespace skyview::detail {
namespace {

void check(int status, const std::string& path, const char* what) {
  if (status != NC_NOERR)
    throw Error("cannot name the variables of '" + path + "' (" + what + "): " + nc_strerror(status));
}

// The variable name for a band description: characters outside letters, digits, '_', '.' and
// '-' become '_', and a name that does not start with a letter or '_' gets a leading '_'.
std::string netcdf_variable_name(const std::string& description) {
  const bool starts_well =
      !description.empty() && (std::isalpha(static_cast<unsigned char>(description[0])) || description[0] == '_');
  std::string name = starts_well ? "" : "_";
  for (const char c : description) {
    const bool kept = std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '-';
    name += kept ? c : '_';
  }
  return name;
}

}  // namespace

void name_netcdf_variables(const std::string& path, const std::string& final_path,
                           const std::vector<std::string>& names) {
  int nc = 0;
  check(nc_open(path.c_str(), NC_WRITE, &nc), path, "open");
  struct Closer {  // closes the file if a step below throws
    int id;
    ~Closer() {
      if (id >= 0) nc_close(id);
    }
  } closer{nc};
  check(nc_redef(nc), path, "define mode");
  for (std::size_t b = 0; b < names.size(); ++b) {
    if (names[b].empty()) continue;
    int var = 0;
    if (nc_inq_varid(nc, ("Band" + std::to_string(b + 1)).c_str(), &var) != NC_NOERR) continue;  // not GDAL's name
    check(nc_put_att_text(nc, var, "long_name", names[b].size(), names[b].c_str()), path, "long_name");
    const std::string name = netcdf_variable_name(names[b]);
    int other = 0;
    if (nc_inq_varid(nc, name.c_str(), &other) == NC_NOERR) continue;  // taken: keep GDAL's name
    check(nc_rename_var(nc, var, name.c_str()), path, "rename");
  }
  std::size_t length = 0;
  if (nc_inq_attlen(nc, NC_GLOBAL, "history", &length) == NC_NOERR && length > 0) {
    std::string history(length, '\0');
    if (nc_get_att_text(nc, NC_GLOBAL, "history", history.data()) == NC_NOERR) {
      name_final_output(history, path, final_path);
      check(nc_put_att_text(nc, NC_GLOBAL, "history", history.size(), history.c_str()), path, "history");
    }
  }
  check(nc_enddef(nc), path, "data mode");
  closer.id = -1;
  check(nc_close(nc), path, "close");
}

}  // namespace skyview::detail
