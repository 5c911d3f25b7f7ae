#include "skyview/raster/vrt_mosaic.h"

#include <cpl_vsi.h>
#include <gdal_utils.h>

#include <filesystem>

#include "raster/gdal_common.h"
#include "skyview/core/error.h"
#include "skyview/raster/output_checks.h"
#include "skyview/raster/raster_read.h"
#include "skyview/raster/temporary_outputs.h"

namespace skyview {

using namespace detail;

namespace {

// Not through the VRT driver's Delete and Rename: they act on every file of the dataset's list,
// which for a VRT holds its sources, the tiles.
void remove_vrt(const std::string& tmp) {
  forget_temporary(tmp);
  VSIUnlink(tmp.c_str());
  CPLErrorReset();
}

}  // namespace

void write_vrt_mosaic(const std::string& path, const std::vector<std::string>& tiles,
                      const std::map<std::string, std::string>& metadata, bool overwrite) {
  init_gdal();
  if (tiles.empty()) throw Error("no tiles to mosaic into '" + path + "' (internal error)");
  check_output_writable(path, overwrite);
  const DatasetPtr first(GDALDataset::Open(tiles.front().c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!first) throw Error("cannot open the tile '" + tiles.front() + "': " + last_gdal_error());
  const std::string tmp = temporary_output_name(path);
  std::vector<const char*> names;
  for (const std::string& t : tiles) names.push_back(t.c_str());
  GDALBuildVRTOptions* options = GDALBuildVRTOptionsNew(nullptr, nullptr);
  int usage_error = 0;
  CPLErrorReset();
  GDALDatasetH built =
      GDALBuildVRT(tmp.c_str(), static_cast<int>(names.size()), nullptr, names.data(), options, &usage_error);
  GDALBuildVRTOptionsFree(options);
  if (!built) {
    const std::string why = last_gdal_error();
    remove_vrt(tmp);
    throw Error("cannot write '" + path + "': " + naming_output(why, tmp, path));
  }
  auto* vrt = GDALDataset::FromHandle(built);
  for (int b = 1; b <= vrt->GetRasterCount() && b <= first->GetRasterCount(); ++b) {
    GDALRasterBand* from = first->GetRasterBand(b);
    GDALRasterBand* to = vrt->GetRasterBand(b);
    to->SetDescription(from->GetDescription());
    to->SetUnitType(from->GetUnitType());
    if (char** items = from->GetMetadata()) to->SetMetadata(items);
  }
  for (const auto& [k, v] : metadata) vrt->SetMetadataItem(k.c_str(), v.c_str());
  const std::string why = close_written(vrt);
  if (!why.empty()) {
    remove_vrt(tmp);
    throw Error("cannot write '" + path + "': " + naming_output(why, tmp, path));
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    remove_vrt(tmp);
    throw Error("cannot move the finished output into place at '" + path + "': " + ec.message());
  }
  forget_temporary(tmp);
}

}  // namespace skyview
