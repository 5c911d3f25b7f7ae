// Point tables out through OGR: the input's columns and the results, as CSV or GeoPackage.
#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <cmath>
#include <filesystem>
#include <memory>

#include "points/ogr_dataset.h"
#include "skyview/core/error.h"
#include "skyview/core/lowercase.h"
#include "skyview/points/point_table.h"
#include "skyview/raster/raster_io.h"
#include "skyview/raster/temporary_outputs.h"

namespace skyview {
namespace {

using detail::DatasetPtr;
using detail::last_gdal_error;

std::string extension_of(const std::string& path) { return lowercase_extension(path); }

}  // namespace

void check_point_output(const std::string& path) {
  const std::string ext = extension_of(path);
  if (ext != ".csv" && ext != ".gpkg")
    throw Error("the points' output '" + path + "' must end in .csv or .gpkg (it is written as CSV or GeoPackage)");
}

void write_point_table(const std::string& path, const PointTable& table, const std::vector<ResultColumn>& results,
                       const std::string& layer_name, const std::map<std::string, std::string>& metadata,
                       bool overwrite) {
  init_gdal();
  check_point_output(path);
  check_output_writable(path, overwrite);
  const bool gpkg = extension_of(path) == ".gpkg";
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(gpkg ? "GPKG" : "CSV");
  if (!driver) throw Error(std::string("GDAL has no ") + (gpkg ? "GPKG" : "CSV") + " driver");
  const std::string temp = temporary_output_name(path);
  struct Cleanup {
    std::string path;
    bool keep = false;
    ~Cleanup() {
      if (!keep) {
        std::error_code ec;
        std::filesystem::remove(path, ec);
        forget_temporary(path);
      }
    }
  } cleanup{temp};
  {
    CPLErrorReset();
    DatasetPtr ds(driver->Create(temp.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
    if (!ds) throw Error("cannot create '" + path + "'" + last_gdal_error());
    OGRSpatialReference srs;
    const bool has_crs = !table.crs_wkt.empty() && srs.importFromWkt(table.crs_wkt.c_str()) == OGRERR_NONE;
    if (has_crs) srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    // A CSV from a layer keeps the points as x, y columns (GEOMETRY=AS_XY); one from a CSV already has them.
    const bool geometry = gpkg || !table.from_csv;
    char** lco = nullptr;
    if (!gpkg && !table.from_csv) lco = CSLSetNameValue(lco, "GEOMETRY", "AS_XY");
    if (!gpkg) lco = CSLSetNameValue(lco, "STRING_QUOTING", "IF_NEEDED");  // the input's numbers stay numbers
    OGRLayer* layer =
        ds->CreateLayer(layer_name.c_str(), has_crs && geometry ? &srs : nullptr, geometry ? wkbPoint : wkbNone, lco);
    CSLDestroy(lco);
    if (!layer) throw Error("cannot create a layer in '" + path + "'" + last_gdal_error());
    if (gpkg) {
      for (const auto& [key, value] : metadata) layer->SetMetadataItem(key.c_str(), value.c_str());
    }
    for (const std::string& c : table.columns) {
      OGRFieldDefn f(c.c_str(), OFTString);
      if (layer->CreateField(&f) != OGRERR_NONE) throw Error("cannot create column '" + c + "'" + last_gdal_error());
    }
    for (const ResultColumn& r : results) {
      OGRFieldDefn f(r.name.c_str(), r.numbers.empty() ? OFTString : OFTReal);
      if (layer->CreateField(&f) != OGRERR_NONE)
        throw Error("cannot create column '" + r.name + "'" + last_gdal_error());
    }
    const bool batch = gpkg && layer->StartTransaction() == OGRERR_NONE;
    const int first_result = static_cast<int>(table.columns.size());
    for (std::size_t i = 0; i < table.rows.size(); ++i) {
      const PointRow& row = table.rows[i];
      OGRFeature f(layer->GetLayerDefn());
      for (std::size_t c = 0; c < row.values.size(); ++c) f.SetField(static_cast<int>(c), row.values[c].c_str());
      for (std::size_t r = 0; r < results.size(); ++r) {
        const int field = first_result + static_cast<int>(r);
        if (!results[r].numbers.empty()) {
          if (!std::isnan(results[r].numbers[i])) f.SetField(field, results[r].numbers[i]);
        } else if (!results[r].texts[i].empty()) {
          f.SetField(field, results[r].texts[i].c_str());
        }
      }
      if (geometry && row.problem.empty()) f.SetGeometryDirectly(new OGRPoint(row.x, row.y));
      if (layer->CreateFeature(&f) != OGRERR_NONE) throw Error("cannot write to '" + path + "'" + last_gdal_error());
    }
    if (batch && layer->CommitTransaction() != OGRERR_NONE)
      throw Error("cannot write to '" + path + "'" + last_gdal_error());
    ds.reset();  // flushes and closes
    if (CPLGetLastErrorType() == CE_Failure) throw Error("cannot write '" + path + "'" + last_gdal_error());
  }
  std::error_code ec;
  std::filesystem::rename(temp, path, ec);
  if (ec) throw Error("cannot move the output into place at '" + path + "': " + ec.message());
  cleanup.keep = true;
  forget_temporary(temp);
}

}  // namespace skyview
