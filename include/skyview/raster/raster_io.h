#pragma once
// Raster I/O in one include: reading (raster_read.h), the checks on outputs made before any
// computation (output_checks.h), the band writer (band_writer.h) and the other outputs
// (output_files.h). Every output is written under a temporary name and renamed into place.
#include "skyview/raster/band_writer.h"
#include "skyview/raster/output_checks.h"
#include "skyview/raster/output_files.h"
#include "skyview/raster/raster_read.h"
