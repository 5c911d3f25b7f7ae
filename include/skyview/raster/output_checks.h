#pragma once
// Checks made on outputs before any computation, so that a run never fails, rounds or loses bands
// only at its end.
#include <string>
#include <vector>

namespace skyview {

// Refuses early (before any computation) when an output exists and !overwrite, or exists and is
// not a regular file (a device or a folder is never replaced).
void check_output_writable(const std::string& path, bool overwrite);

// Refuses, before any computation, writing `path` in a GDAL format that cannot write `bands`
// float32 bands with these creation options (unknown, writes no file, rounds floats, refuses the
// band count, as AAIGrid does for more than one, or keeps fewer, as XYZ does): the run would
// otherwise fail, round or lose bands only at the end. Also refuses a `path` that does not end in
// an extension the format names (`out.png` written as a GeoTIFF, `svf.nc` without -of netCDF).
void check_output_format(const std::string& path, const std::string& format, int bands,
                         const std::vector<std::string>& creation_options);

// Refuses, before any computation, an output that is also an input or another output (by the
// file it names: "./a.tif", a link to it and "a.tif" are one). Empty paths are left out.
void check_outputs_apart(const std::vector<std::string>& outputs, const std::vector<std::string>& inputs);

}  // namespace skyview
