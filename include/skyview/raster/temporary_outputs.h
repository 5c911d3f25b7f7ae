#pragma once
// Outputs are written under a temporary name next to the final one and renamed into place when
// finished. A run stopped by a signal (Ctrl-C, a batch scheduler's SIGTERM at its time limit) would
// leave that hidden, possibly gigabyte-sized, file behind; the files registered here are removed
// by the signal handler that remove_temporary_outputs_on_signals installs.
#include <string>

namespace skyview {

// The temporary name for `path` (".name.skyview-tmp-PID.ext" in the same folder), registered for
// removal, with the side files GDAL may add (.aux.xml, .msk, ENVI's .hdr), until forget_temporary.
std::string temporary_output_name(const std::string& path);
void forget_temporary(const std::string& temporary);

// Text a driver wrote into the file (ENVI's header description, netCDF's history) names the
// temporary file it created: every `temporary` in `text` becomes `final_path`.
void name_final_output(std::string& text, const std::string& temporary, const std::string& final_path);

// Installs handlers for SIGINT, SIGTERM and SIGHUP that remove every registered temporary file and
// then end the process as the signal would have. For executables; a library does not take over
// its host's signals.
void remove_temporary_outputs_on_signals();

}  // namespace skyview
