#include "skyview/synthetic/synthetic_district.h"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <system_error>

#include "skyview/core/error.h"
#include "skyview/core/lowercase.h"
#include "skyview/core/number_text.h"
#include "skyview/raster/raster_io.h"

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

// GDAL's last message, or a fallback where it said nothing.
std::string gdal_reason() {
  const char* m = CPLGetLastErrorMsg();
  return m && *m ? std::string(m) : std::string("unknown GDAL error");
}

// Writes the footprints layer into `ds`; throws on the first failure.
void fill_footprints(GDALDataset* ds, const SyntheticDistrict& d, OGRSpatialReference& srs) {
  OGRLayer* layer = ds->CreateLayer("footprints", &srs, wkbPolygon, nullptr);
  if (!layer) throw Error("cannot create a layer: " + gdal_reason());
  OGRFieldDefn name("name", OFTString), base("base", OFTReal), height("height", OFTReal);
  for (OGRFieldDefn* field : {&name, &base, &height}) {
    if (layer->CreateField(field) != OGRERR_NONE) throw Error("cannot create a field: " + gdal_reason());
  }
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
    if (layer->CreateFeature(&feature) != OGRERR_NONE) throw Error("cannot write a footprint: " + gdal_reason());
  }
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
  if (birds < 0) throw Error("the number of birds must not be negative");
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double spacing = 1.0 / std::sqrt(density);
  // Counted in doubles: a dense survey's count overflows an int. A LAS 1.2 header counts points
  // in 32 bits.
  const double per_side = std::floor(d.size / spacing), total = per_side * per_side + birds;
  constexpr double kMaxPoints = std::numeric_limits<std::uint32_t>::max();
  if (!(total <= kMaxPoints)) {
    throw Error("too many points: " + number_text(density) + " returns per square metre over " + number_text(d.size) +
                " x " + number_text(d.size) + " m make " + number_text(total) + "; a LAS 1.2 file holds at most " +
                number_text(kMaxPoints));
  }
  const int n = static_cast<int>(per_side);
  std::vector<LasPoint> pts;
  pts.reserve(static_cast<std::size_t>(total));
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
  check_output_writable(path, overwrite);
  const std::filesystem::path target(path);
  const std::string ext = lowercase(target.extension().string());
  const char* driver_name = ext == ".gpkg" ? "GPKG" : (ext == ".shp" ? "ESRI Shapefile" : "GeoJSON");
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(driver_name);
  if (!driver) throw Error(std::string("GDAL has no ") + driver_name + " driver");
  OGRSpatialReference srs;
  if (srs.importFromWkt(crs_wkt.c_str()) != OGRERR_NONE) throw Error("the footprints' CRS is not valid WKT");
  const std::string id = target.stem().string() + ".skyview-tmp-" + std::to_string(::getpid());

  // Built in memory first: GDAL's GeoJSON and shapefile writers do not report failed writes (a
  // full disk left a truncated file and no error), ours do.
  const std::string memory = "/vsimem/" + id + "/";
  struct MemoryCleanup {
    std::string dir;
    ~MemoryCleanup() { VSIRmdirRecursive(dir.c_str()); }
  } memory_cleanup{memory};
  std::vector<std::pair<std::string, std::string>> files;  // name, bytes
  {
    CPLErrorReset();
    GDALDataset* ds = driver->Create((memory + target.filename().string()).c_str(), 0, 0, 0, GDT_Unknown, nullptr);
    if (!ds) throw Error("cannot write '" + path + "': " + gdal_reason());
    try {
      fill_footprints(ds, d, srs);
    } catch (const Error& e) {
      GDALClose(ds);
      throw Error("cannot write '" + path + "': " + e.what());
    }
    GDALClose(ds);
    if (CPLGetLastErrorType() >= CE_Failure) throw Error("cannot write '" + path + "': " + gdal_reason());
    char** names = VSIReadDir(memory.c_str());
    for (char** n = names; n && *n; ++n) {
      vsi_l_offset size = 0;
      const GByte* bytes = VSIGetMemFileBuffer((memory + *n).c_str(), &size, FALSE);
      if (bytes) files.emplace_back(*n, std::string(reinterpret_cast<const char*>(bytes), size));
    }
    CSLDestroy(names);
  }
  if (files.empty()) throw Error("cannot write '" + path + "': GDAL wrote no file");

  // Then into a hidden folder beside `path` and moved into place: a failed write leaves an old
  // output as it was, and a shapefile's side files move together.
  std::string hidden = ".";  // appended, not "." + ...: GCC 12 warns falsely (-Wrestrict) on that
  hidden += id;
  const std::filesystem::path folder = target.parent_path() / hidden;
  std::error_code ec;
  std::filesystem::remove_all(folder, ec);
  if (!std::filesystem::create_directory(folder, ec)) {
    throw Error("cannot write '" + path + "': cannot make the temporary folder '" + folder.string() + "'");
  }
  struct FolderCleanup {
    std::filesystem::path dir;
    ~FolderCleanup() {
      std::error_code ignored;
      std::filesystem::remove_all(dir, ignored);
    }
  } folder_cleanup{folder};
  for (const auto& [name, bytes] : files) {
    std::ofstream out(folder / name, std::ios::binary | std::ios::trunc);
    out << bytes;
    out.close();
    if (!out) throw Error("cannot write '" + path + "'");
  }
  if (files.size() > 1 && std::filesystem::exists(target)) {
    // An old shapefile goes with all its side files, so no stale index or code page survives.
    if (driver->Delete(path.c_str()) != CE_None) std::filesystem::remove(target, ec);
  }
  for (const auto& file : files) {
    // The shapefile driver writes "S.SHP" as "S.shp": the output keeps the name asked for.
    const std::string name =
        lowercase(file.first) == lowercase(target.filename().string()) ? target.filename().string() : file.first;
    std::filesystem::rename(folder / file.first, target.parent_path() / name, ec);
    if (ec) throw Error("cannot move the finished output into place at '" + path + "': " + ec.message());
  }
}

}  // namespace skyview
