#pragma once
// Building footprints as `skyview dsm` burns them and `skyview scene` extrudes them: the first layer
// of any OGR vector source, each feature's polygons made valid and brought into the output CRS, its
// heights read from numeric fields in metres (or the unit given), with the rule that puts a
// building's top over its ground. One reader, so that both commands see the same buildings.
#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <functional>
#include <limits>
#include <memory>
#include <string>

namespace skyview {

struct FootprintFields {
  std::string height_field;       // building height attribute; empty: none
  std::string base_field;         // absolute base height attribute; empty: none
  bool absolute_heights = false;  // height_field is absolute, not above the ground
  // Metres per unit of both fields; 0: metres, refused where the layer's CRS is in another unit
  // (attributes carry no unit, and such layers often give feet).
  double z_scale = 0.0;
};

struct Footprint {
  std::unique_ptr<OGRGeometry> polygons;  // a Polygon or MultiPolygon, valid, of positive area, in the output CRS
  double height = std::numeric_limits<double>::quiet_NaN();  // metres; NaN where the field is absent or null
  double base = std::numeric_limits<double>::quiet_NaN();
  GIntBig fid = 0;
};

// What reading left out or mended.
struct FootprintCounts {
  int polygons = 0;      // features with polygons
  int repaired = 0;      // invalid polygons OGR's MakeValid mended
  int skipped = 0;       // beyond repair, not transformable, or of no area
  int not_polygons = 0;  // points, lines, no geometry: not a building's outline
  // GEOS's notes while checking and mending polygons ("Ring Self-intersection at or near point
  // ..."): counted here and said once by the command, not a line each on the terminal.
  int geos_notices = 0;
  std::string first_geos_notice;
};

// One line for a command's warnings: "N notes from GEOS while checking the footprints of 'F'
// (the first: ...)"; empty without any.
std::string geos_notices_warning(const FootprintCounts& counts, const std::string& path);

class FootprintLayer {
 public:
  // Opens `path` and checks its first layer holds polygons and that the fields exist and hold
  // numbers. Throws skyview::Error (one line, naming the file or field).
  FootprintLayer(const std::string& path, const FootprintFields& fields);

  const std::string& path() const { return path_; }
  // GDAL's short name of the format ("GPKG", "ESRI Shapefile").
  std::string driver_name() const { return dataset_->GetDriverName(); }
  OGRLayer& layer() { return *layer_; }
  const OGRSpatialReference* crs() const { return layer_->GetSpatialRef(); }
  // What gave the fields their unit ("metres (...)", "--footprint-z-scale"); empty without fields.
  const std::string& height_unit() const { return height_unit_; }

  // Calls `use` for each feature with polygons, made valid and transformed by `to_output` (null:
  // kept in the layer's CRS); counts what it left out. Throws skyview::Error for a height beyond any
  // building's (a wrong field or unit, not data).
  void read(OGRCoordinateTransformation* to_output, const std::function<void(Footprint&)>& use,
            FootprintCounts& counts);

 private:
  std::string path_;
  FootprintFields fields_;
  GDALDatasetUniquePtr dataset_;
  OGRLayer* layer_ = nullptr;
  double metres_per_unit_ = 1.0;
  std::string height_unit_;
};

// The height of a building's flat top from its fields (Footprint::height and base): base + height
// where the base is known, the height itself where it is absolute, else `ground` (the lowest ground
// under the building, as OpenStreetMap's height=* is measured from the lowest point of its
// perimeter) + height; NaN where the height is unknown or there is no finite ground to add it to.
double footprint_top(double height, double base, bool absolute_heights, double ground);

}  // namespace skyview
