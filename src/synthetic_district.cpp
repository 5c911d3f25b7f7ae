#include "skyview/synthetic_district.h"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "skyview/error.h"
#include "skyview/raster_io.h"

namespace skyview {
namespace {

bool inside(const std::vector<std::array<double, 2>>& ring, double x, double y) {
  bool in = false;  // even-odd rule, enough for the axis-aligned rings made here
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    const auto& a = ring[i];
    const auto& b = ring[j];
    if ((a[1] > y) != (b[1] > y) && x < (b[0] - a[0]) * (y - a[1]) / (b[1] - a[1]) + a[0]) in = !in;
  }
  return in;
}

std::vector<std::array<double, 2>> box(double x0, double y0, double x1, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

}  // namespace

double SyntheticDistrict::ground(double x, double y) const {
  (void)y;
  return ground_at_origin + slope_x * (x - x0);
}

double SyntheticDistrict::surface(double x, double y, int* lidar_class) const {
  for (const DistrictBuilding& b : buildings) {
    if (inside(b.outer, x, y) && (b.courtyard.empty() || !inside(b.courtyard, x, y))) {
      if (lidar_class) *lidar_class = 6;
      return b.base + b.height;
    }
  }
  // Two round tree crowns over the street, 12 m high, radius 4 m.
  for (const auto& [tx, ty] : {std::array<double, 2>{x0 + 0.5 * size, y0 + 0.1 * size},
                               std::array<double, 2>{x0 + 0.1 * size, y0 + 0.5 * size}}) {
    const double r = std::hypot(x - tx, y - ty);
    if (r < 4.0) {
      if (lidar_class) *lidar_class = 5;
      return ground(x, y) + 12.0 - 0.5 * r;
    }
  }
  if (lidar_class) *lidar_class = 2;
  return ground(x, y);
}

SyntheticDistrict synthetic_district(double x0, double y0, double size, std::uint64_t seed) {
  if (!(size >= 40.0)) throw Error("the synthetic district needs a side of at least 40 m");
  SyntheticDistrict d;
  d.x0 = x0, d.y0 = y0, d.size = size;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  // Three by three blocks with streets of a fifth of the pitch: the middle one a courtyard
  // block, the north-east one without a height attribute.
  const double pitch = size / 3.0, street = 0.2 * pitch;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const double bx0 = x0 + i * pitch + 0.5 * street, by0 = y0 + j * pitch + 0.5 * street;
      const double bx1 = bx0 + pitch - street, by1 = by0 + pitch - street;
      DistrictBuilding b;
      b.outer = box(bx0, by0, bx1, by1);
      if (i == 1 && j == 1) {
        const double m = 0.3 * (bx1 - bx0);
        b.courtyard = box(bx0 + m, by0 + m, bx1 - m, by1 - m);
      }
      b.base = d.ground(bx0, by0);  // the lowest corner: the ground rises to the east
      b.height = std::round(8.0 + 32.0 * u(rng));
      b.height_known = !(i == 2 && j == 2);
      d.buildings.push_back(b);
    }
  }
  return d;
}

std::vector<LasPoint> district_lidar(const SyntheticDistrict& d, double density, int birds, std::uint64_t seed) {
  if (!(density > 0)) throw Error("the survey density must be positive");
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double spacing = 1.0 / std::sqrt(density);
  const int n = static_cast<int>(d.size / spacing);
  std::vector<LasPoint> pts;
  pts.reserve(static_cast<std::size_t>(n) * n + birds);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double x = d.x0 + (i + u(rng)) * spacing, y = d.y0 + (j + u(rng)) * spacing;
      int cls = 2;
      const double z = d.surface(x, y, &cls) + 0.02 * (u(rng) - 0.5);  // 2 cm ranging noise
      pts.push_back({x, y, z, static_cast<std::uint16_t>(100 + 50 * u(rng)), 1, 1, static_cast<std::uint8_t>(cls)});
    }
  }
  for (int b = 0; b < birds; ++b) {
    const double x = d.x0 + d.size * u(rng), y = d.y0 + d.size * u(rng);
    pts.push_back({x, y, d.surface(x, y) + 40.0 + 40.0 * u(rng), 20, 1, 1, 1});
  }
  return pts;
}

void write_district_footprints(const std::string& path, const SyntheticDistrict& d, const std::string& crs_wkt,
                               bool overwrite) {
  init_gdal();
  if (std::filesystem::exists(path)) {
    if (!overwrite) throw Error("'" + path + "' exists; give --overwrite to replace it");
    std::filesystem::remove(path);
  }
  const std::string ext = std::filesystem::path(path).extension().string();
  const char* driver_name = ext == ".gpkg" ? "GPKG" : (ext == ".shp" ? "ESRI Shapefile" : "GeoJSON");
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(driver_name);
  if (!driver) throw Error(std::string("GDAL has no ") + driver_name + " driver");
  GDALDatasetUniquePtr ds(driver->Create(path.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
  if (!ds) throw Error("cannot create '" + path + "'");
  OGRSpatialReference srs;
  if (srs.importFromWkt(crs_wkt.c_str()) != OGRERR_NONE) throw Error("the footprints' CRS is not valid WKT");
  OGRLayer* layer = ds->CreateLayer("footprints", &srs, wkbPolygon, nullptr);
  if (!layer) throw Error("cannot create a layer in '" + path + "'");
  OGRFieldDefn name("name", OFTString), base("base", OFTReal), height("height", OFTReal);
  layer->CreateField(&name);
  layer->CreateField(&base);
  layer->CreateField(&height);
  for (std::size_t i = 0; i < d.buildings.size(); ++i) {
    const DistrictBuilding& b = d.buildings[i];
    OGRFeature feature(layer->GetLayerDefn());
    feature.SetField("name", ("block " + std::to_string(i + 1)).c_str());
    feature.SetField("base", b.base);
    if (b.height_known) {
      feature.SetField("height", b.height);
    } else {
      feature.SetFieldNull(feature.GetFieldIndex("height"));
    }
    OGRPolygon polygon;
    for (const auto* ring : {&b.outer, &b.courtyard}) {
      if (ring->empty()) continue;
      OGRLinearRing r;
      for (const auto& p : *ring) r.addPoint(p[0], p[1]);
      r.closeRings();
      polygon.addRing(&r);
    }
    feature.SetGeometry(&polygon);
    if (layer->CreateFeature(&feature) != OGRERR_NONE) throw Error("cannot write a footprint to '" + path + "'");
  }
}

}  // namespace skyview
