// Point tables in through OGR: CSV with coordinate columns, or any point layer.
#include "skyview/points/point_table.h"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_vsi.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>

#include "points/ogr_dataset.h"
#include "skyview/core/error.h"
#include "skyview/core/lowercase.h"
#include "skyview/raster/raster_io.h"

namespace skyview {
namespace {

using detail::DatasetPtr;
using detail::last_gdal_error;

std::string extension_of(const std::string& path) { return lowercase_extension(path); }

// A number in a CSV cell: the whole text (spaces around allowed), finite.
bool parse_number(const std::string& text, double& out) {
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  out = std::strtod(begin, &end);
  if (end == begin) return false;
  while (*end == ' ' || *end == '\t' || *end == '\r') ++end;
  return *end == '\0' && errno != ERANGE && std::isfinite(out);
}

int find_column(const std::vector<std::string>& columns, const std::string& name) {
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (lowercase(columns[i]) == lowercase(name)) return static_cast<int>(i);
  }
  return -1;
}

std::string wkt_of(const OGRSpatialReference& srs) {
  char* wkt = nullptr;
  srs.exportToWkt(&wkt);
  std::string s = wkt ? wkt : "";
  CPLFree(wkt);
  return s;
}

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const std::string& x : v) s += (s.empty() ? "" : ", ") + x;
  return s.empty() ? "none" : s;
}

}  // namespace

PointTable read_point_table(const std::string& path, const PointTableOptions& o, const std::string& raster_crs_wkt) {
  init_gdal();
  VSIStatBufL stat;  // through GDAL's file layer, so /vsimem/ and /vsizip/ paths work too
  if (VSIStatL(path.c_str(), &stat) != 0 || VSI_ISDIR(stat.st_mode))
    throw Error("cannot open points '" + path + "': no such file");
  const bool csv = extension_of(path) == ".csv";
  // CSV cells as text (no type guessing, no geometry from columns): coordinates are parsed here so
  // that a bad cell is reported by its line and the other rows still count.
  const char* csv_options[] = {"AUTODETECT_TYPE=NO", "KEEP_SOURCE_COLUMNS=YES", "HEADERS=YES", nullptr};
  CPLErrorReset();
  DatasetPtr ds(static_cast<GDALDataset*>(GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY,
                                                     csv ? std::vector<const char*>{"CSV", nullptr}.data() : nullptr,
                                                     csv ? csv_options : nullptr, nullptr)));
  if (!ds)
    throw Error("cannot read points from '" + path + "' (not a CSV file or vector layer OGR knows)" +
                last_gdal_error());
  if (ds->GetLayerCount() < 1) throw Error("'" + path + "' holds no layer of points");
  OGRLayer* layer = o.layer.empty() ? ds->GetLayer(0) : ds->GetLayerByName(o.layer.c_str());
  if (!layer) throw Error("'" + path + "' has no layer '" + o.layer + "'");
  PointTable t;
  t.from_csv = csv;
  OGRFeatureDefn* defn = layer->GetLayerDefn();
  for (int i = 0; i < defn->GetFieldCount(); ++i) t.columns.push_back(defn->GetFieldDefn(i)->GetNameRef());
  int xi = -1, yi = -1;
  bool lonlat = false;
  const bool has_geometry = !csv && defn->GetGeomFieldCount() > 0;
  if (!has_geometry) {
    if (o.x_column.empty() != o.y_column.empty()) throw Error("give both --x-column and --y-column, or neither");
    if (!o.x_column.empty()) {
      xi = find_column(t.columns, o.x_column);
      yi = find_column(t.columns, o.y_column);
      if (xi < 0 || yi < 0)
        throw Error("'" + path + "' has no column '" + (xi < 0 ? o.x_column : o.y_column) +
                    "' (its columns: " + joined(t.columns) + ")");
      lonlat = lowercase(o.x_column).starts_with("lon") || lowercase(o.x_column) == "lng";
    } else {
      const char* pairs[][2] = {
          {"x", "y"}, {"easting", "northing"}, {"lon", "lat"}, {"longitude", "latitude"}, {"lng", "lat"}};
      for (const auto& p : pairs) {
        xi = find_column(t.columns, p[0]);
        yi = find_column(t.columns, p[1]);
        if (xi >= 0 && yi >= 0) {
          lonlat = p[0][0] == 'l';
          break;
        }
      }
      if (xi < 0 || yi < 0)
        throw Error("'" + path + "' has no coordinate columns x,y, easting,northing or lon,lat (its columns: " +
                    joined(t.columns) + "); name them with --x-column and --y-column");
    }
    t.source = "columns " + t.columns[xi] + ", " + t.columns[yi];
    OGRSpatialReference srs;
    if (!o.crs.empty()) {
      if (srs.SetFromUserInput(o.crs.c_str()) != OGRERR_NONE) throw Error("cannot read the CRS '" + o.crs + "'");
      t.crs_wkt = wkt_of(srs);
    } else if (lonlat) {
      srs.importFromEPSG(4326);
      t.crs_wkt = wkt_of(srs);
    } else {
      t.crs_wkt = raster_crs_wkt;
    }
  } else {
    if (!o.x_column.empty() || !o.y_column.empty())
      throw Error("'" + path + "' has point geometries: --x-column and --y-column are for CSV files");
    if (!o.crs.empty()) throw Error("'" + path + "' states its own CRS: --points-crs is for CSV files");
    if (const OGRSpatialReference* srs = layer->GetSpatialRef())
      t.crs_wkt = wkt_of(*srs);
    else
      t.crs_wkt = raster_crs_wkt;
    t.source = "the layer's point geometries";
  }
  layer->ResetReading();
  long long n = 0;
  for (auto& feature : *layer) {
    ++n;
    PointRow row;
    row.where = csv ? "line " + std::to_string(n + 1) : "feature " + std::to_string(feature->GetFID());
    for (int i = 0; i < defn->GetFieldCount(); ++i)
      row.values.push_back(feature->IsFieldSetAndNotNull(i) ? feature->GetFieldAsString(i) : "");
    if (!has_geometry) {
      const bool ok_x = parse_number(row.values[xi], row.x), ok_y = parse_number(row.values[yi], row.y);
      if (!ok_x || !ok_y) {
        row.problem = std::string(!ok_x ? t.columns[xi] : t.columns[yi]) + " '" + row.values[!ok_x ? xi : yi] +
                      "' is not a number";
      }
    } else {
      const OGRGeometry* g = feature->GetGeometryRef();
      if (!g || g->IsEmpty()) {
        row.problem = "no point";
      } else if (wkbFlatten(g->getGeometryType()) != wkbPoint) {
        row.problem = std::string("a ") + g->getGeometryName() + ", not a point";
      } else {
        row.x = g->toPoint()->getX();
        row.y = g->toPoint()->getY();
      }
    }
    t.rows.push_back(std::move(row));
  }
  if (t.rows.empty()) throw Error("'" + path + "' holds no points");
  return t;
}

void transform_points(PointTable& table, const std::string& to_wkt) {
  if (to_wkt.empty() || table.crs_wkt.empty()) return;
  OGRSpatialReference from, to;
  from.importFromWkt(table.crs_wkt.c_str());
  to.importFromWkt(to_wkt.c_str());
  from.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  to.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  if (from.IsSame(&to)) return;
  CPLErrorReset();
  std::unique_ptr<OGRCoordinateTransformation> ct(OGRCreateCoordinateTransformation(&from, &to));
  if (!ct) throw Error("cannot transform the points into the raster's CRS" + last_gdal_error());
  for (PointRow& r : table.rows) {
    if (!r.problem.empty()) continue;
    double x = r.x, y = r.y;
    if (!ct->Transform(1, &x, &y) || !std::isfinite(x) || !std::isfinite(y)) {
      r.problem = "cannot be transformed into the raster's CRS";
      continue;
    }
    r.x = x;
    r.y = y;
  }
  table.crs_wkt = to_wkt;
}

}  // namespace skyview
