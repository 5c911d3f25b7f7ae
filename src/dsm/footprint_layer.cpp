#include "dsm/footprint_layer.h"

#include <cpl_error.h>

#include <cmath>

#include "skyview/core/error.h"
#include "skyview/core/number_text.h"
#include "skyview/raster/height_unit.h"
#include "skyview/raster/raster_io.h"

namespace skyview {
namespace {

// While alive, GDAL's messages on this thread (GEOS's notices reach GDAL as warnings) are counted
// into `counts` instead of printed.
class GeosNoticeCounter {
 public:
  explicit GeosNoticeCounter(FootprintCounts& counts) : counts_(counts) { CPLPushErrorHandlerEx(&note, this); }
  ~GeosNoticeCounter() { CPLPopErrorHandler(); }
  GeosNoticeCounter(const GeosNoticeCounter&) = delete;
  GeosNoticeCounter& operator=(const GeosNoticeCounter&) = delete;

 private:
  static void CPL_STDCALL note(CPLErr level, CPLErrorNum, const char* message) {
    if (level == CE_Debug) return;
    auto* self = static_cast<GeosNoticeCounter*>(CPLGetErrorHandlerUserData());
    if (++self->counts_.geos_notices == 1) self->counts_.first_geos_notice = message ? message : "";
  }
  FootprintCounts& counts_;
};

}  // namespace

std::string geos_notices_warning(const FootprintCounts& counts, const std::string& path) {
  if (counts.geos_notices == 0) return "";
  return std::to_string(counts.geos_notices) + (counts.geos_notices == 1 ? " note" : " notes") +
         " from GEOS while checking the footprints of '" + path + "' (the first: " + counts.first_geos_notice +
         "); invalid ones were mended or skipped, as counted";
}

FootprintLayer::FootprintLayer(const std::string& path, const FootprintFields& fields) : path_(path), fields_(fields) {
  init_gdal();
  dataset_.reset(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
  if (!dataset_ || dataset_->GetLayerCount() == 0) throw Error("cannot open '" + path + "' as a vector layer");
  layer_ = dataset_->GetLayer(0);
  const OGRwkbGeometryType g = wkbFlatten(layer_->GetGeomType());
  if (g != wkbPolygon && g != wkbMultiPolygon && g != wkbUnknown) {
    throw Error("'" + path + "' holds no polygons (its first layer is " + OGRGeometryTypeToName(g) + ")");
  }
  // A text field (building names, say) would read as height 0 everywhere.
  for (const std::string& field : {fields.height_field, fields.base_field}) {
    if (field.empty()) continue;
    const int index = layer_->GetLayerDefn()->GetFieldIndex(field.c_str());
    if (index < 0) throw Error("'" + path + "' has no field '" + field + "'");
    const OGRFieldType type = layer_->GetLayerDefn()->GetFieldDefn(index)->GetType();
    if (type != OFTInteger && type != OFTInteger64 && type != OFTReal) {
      throw Error("field '" + field + "' of '" + path + "' holds " + OGRFieldDefn::GetFieldTypeName(type) +
                  ", not numbers");
    }
  }
  // Only height fields have a unit to find (footprints that take their heights from returns do not).
  if (!fields.height_field.empty() || !fields.base_field.empty()) {
    const HeightUnit unit = fields.z_scale > 0.0
                                ? HeightUnit{fields.z_scale, "--footprint-z-scale"}
                                : unstated_height_unit(layer_->GetSpatialRef(), path, "--footprint-z-scale");
    metres_per_unit_ = unit.metres;
    height_unit_ = unit.source;
  }
}

void FootprintLayer::read(OGRCoordinateTransformation* to_output, const std::function<void(Footprint&)>& use,
                          FootprintCounts& counts) {
  layer_->ResetReading();
  for (auto& feature : *layer_) {
    OGRGeometry* g = feature->GetGeometryRef();
    const OGRwkbGeometryType type = g ? wkbFlatten(g->getGeometryType()) : wkbUnknown;
    std::unique_ptr<OGRGeometry> geom;
    if (type == wkbPolygon || type == wkbMultiPolygon) {
      geom.reset(g->clone());
    } else if (type == wkbGeometryCollection) {  // its polygons are the footprint
      auto parts = std::make_unique<OGRMultiPolygon>();
      for (const OGRGeometry* part : *g->toGeometryCollection()) {
        const OGRwkbGeometryType pt = wkbFlatten(part->getGeometryType());
        if (pt == wkbPolygon) parts->addGeometry(part);
        if (pt == wkbMultiPolygon) {
          for (const OGRPolygon* p : *part->toMultiPolygon()) parts->addGeometry(p);
        }
      }
      if (!parts->IsEmpty()) geom = std::move(parts);
    }
    if (!geom) {  // a point, a line, no geometry: not a building's outline
      ++counts.not_polygons;
      continue;
    }
    ++counts.polygons;
    bool beyond_repair = false;
    {
      const GeosNoticeCounter quiet(counts);
      if (!geom->IsValid()) {
        std::unique_ptr<OGRGeometry> fixed(geom->MakeValid());
        beyond_repair = !fixed || !fixed->IsValid();
        if (!beyond_repair) {
          geom = std::move(fixed);
          ++counts.repaired;
        }
      }
    }
    if (beyond_repair) {
      ++counts.skipped;
      continue;
    }
    if (to_output && geom->transform(to_output) != OGRERR_NONE) {
      ++counts.skipped;
      continue;
    }
    // A ring on a line (or a sliver that MakeValid collapsed) covers no cell centre.
    if (!(OGR_G_Area(OGRGeometry::ToHandle(geom.get())) > 0.0)) {
      ++counts.skipped;
      continue;
    }
    // Heights beyond any building's are a wrong field or unit (a sum, millimetres), not data.
    auto read_field = [&](const std::string& field, double lo, double hi) {
      const int index = field.empty() ? -1 : feature->GetFieldIndex(field.c_str());
      if (index < 0 || !feature->IsFieldSetAndNotNull(index)) return std::numeric_limits<double>::quiet_NaN();
      const double v = feature->GetFieldAsDouble(index) * metres_per_unit_;
      if (!(v >= lo && v <= hi)) {
        throw Error("footprint " + std::to_string(feature->GetFID()) + " of '" + path_ + "' has " + field + " = " +
                    number_text(v) + " m, outside " + number_text(lo) + " to " + number_text(hi) +
                    " m; check the field and its unit");
      }
      return v;
    };
    Footprint f;
    f.height = fields_.absolute_heights ? read_field(fields_.height_field, -500.0, 9000.0)
                                        : read_field(fields_.height_field, -100.0, 1000.0);
    f.base = read_field(fields_.base_field, -500.0, 9000.0);
    f.fid = feature->GetFID();
    f.polygons = std::move(geom);
    use(f);
  }
}

double footprint_top(double height, double base, bool absolute_heights, double ground) {
  if (std::isnan(height)) return std::numeric_limits<double>::quiet_NaN();
  if (!std::isnan(base)) return base + height;
  if (absolute_heights) return height;
  return std::isfinite(ground) ? ground + height : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace skyview
