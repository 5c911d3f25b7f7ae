#pragma once
// Points to query, from a CSV file (coordinates in named columns) or any OGR point layer (its
// geometries, in its own CRS), and the same rows written back with result columns, as CSV or
// GeoPackage through OGR. Every input column is kept, as text. A row whose point cannot be read
// keeps its place with a problem, so the others are still computed and the output lines up with
// the input.
#include <map>
#include <string>
#include <vector>

namespace skyview {

struct PointTableOptions {
  // CSV: the columns holding the coordinates; empty: the first pair found of x/y, easting/northing,
  // lon/lat, longitude/latitude, lng/lat (any case).
  std::string x_column, y_column;
  // CSV: the CRS of those coordinates (anything OGRSpatialReference::SetFromUserInput reads); empty:
  // EPSG:4326 for lon/lat columns, otherwise the raster's. Refused for layers that state their own.
  std::string crs;
  std::string layer;  // OGR layer name; empty: the first
};

struct PointRow {
  std::string where;                // "line 5" (CSV) or "feature 3" (other layers), for messages
  std::vector<std::string> values;  // one per PointTable::columns
  double x = 0, y = 0;              // in the table's CRS
  std::string problem;              // empty, or why the row has no usable point
};

struct PointTable {
  std::vector<std::string> columns;
  std::vector<PointRow> rows;
  std::string crs_wkt;  // of x, y (empty: the raster's, no CRS known)
  std::string source;   // "columns lon, lat" or "the layer's point geometries"
  bool from_csv = false;
};

// Throws skyview::Error for a file OGR cannot open, a missing layer, CSV coordinate columns that
// are not there (naming the columns it has), or a CRS that cannot be read; bad rows get a problem.
PointTable read_point_table(const std::string& path, const PointTableOptions& options,
                            const std::string& raster_crs_wkt);

// Moves the table's points into `to_wkt` (empty: left as they are), in place; rows that cannot be
// transformed get a problem. Throws for CRSs that cannot be related.
void transform_points(PointTable& table, const std::string& to_wkt);

// A result column: a name and one value per row (NaN: empty) or one text per row.
struct ResultColumn {
  std::string name;
  std::vector<double> numbers;     // real column when non-empty
  std::vector<std::string> texts;  // text column otherwise
};

// Writes the table's columns and `results` to `path`: CSV (".csv") or GeoPackage (".gpkg"), chosen
// by the extension (anything else is refused), under a temporary name renamed into place. The
// GeoPackage gets the rows' points in the table's CRS as geometry; a CSV from a layer without
// coordinate columns gets columns x and y; `metadata` goes into the GeoPackage layer's metadata
// (a CSV has no place for it). Throws skyview::Error if `path` exists and !overwrite.
void write_point_table(const std::string& path, const PointTable& table, const std::vector<ResultColumn>& results,
                       const std::string& layer_name, const std::map<std::string, std::string>& metadata,
                       bool overwrite);

// Refuses, before any work, an output path whose extension is neither .csv nor .gpkg.
void check_point_output(const std::string& path);

}  // namespace skyview
