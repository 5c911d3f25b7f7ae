// How far `skyview exposure`'s isotropic reflected band (albedo x unobstructed global horizontal x
// (1 - svf of the tilted surface), docs/exposure.md) is from a one-bounce ray-cast estimate, on the
// Gothenburg DSM (issue 33). A measurement, not a timing: it prints a table and is not a Google
// Benchmark. For a sample of cells (roofs, streets, wall feet: by DSM - DEM and Horn's slope),
// cosine-weighted rays leave the cell's tilted surface (Horn's normal); a ray that hits the DSM's
// mesh (the ray cast's triangles over cell centres, load_scene) sees the hit surface as Lambertian
// with radiance albedo x E / pi, E the exposure run's `total - reflected` (direct + diffuse, so one
// bounce) of the cell under the hit point; a ray that meets nothing sees sky (no reflected light).
// With cosine-weighted rays the reflected irradiance is albedo x mean(E over rays, 0 for sky).
//
// Run: skyview exposure DSM_KRbig.tif exposure.tif --from ... --to ... (docs/exposure.md has the
// command), then build/reflected_check DSM_KRbig.tif DEM_KRbig.tif exposure.tif [rays] [per_class]
#include <gdal_priv.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "skyview/raster/raster_read.h"
#include "skyview/scene/ray_scene.h"
#include "skyview/scene/scene.h"

namespace {

// A band of a raster by its description, as floats (NaN for nodata).
std::vector<float> read_band(GDALDataset& ds, const std::string& description, int& cols, int& rows) {
  cols = ds.GetRasterXSize(), rows = ds.GetRasterYSize();
  for (int b = 1; b <= ds.GetRasterCount(); ++b) {
    GDALRasterBand* band = ds.GetRasterBand(b);
    if (description != band->GetDescription()) continue;
    std::vector<float> v(static_cast<std::size_t>(cols) * rows);
    if (band->RasterIO(GF_Read, 0, 0, cols, rows, v.data(), cols, rows, GDT_Float32, 0, 0) != CE_None) break;
    int has = 0;
    const double nodata = band->GetNoDataValue(&has);
    if (has) {
      for (float& x : v) x = x == static_cast<float>(nodata) ? NAN : x;
    }
    return v;
  }
  std::fprintf(stderr, "no band '%s'\n", description.c_str());
  std::exit(1);
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(std::min<double>(v.size() - 1, std::floor(p * (v.size() - 1) + 0.5)))];
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: reflected_check DSM DEM EXPOSURE [rays per cell] [cells per class]\n");
    return 2;
  }
  const std::string dsm_path = argv[1], dem_path = argv[2], exposure_path = argv[3];
  const int rays = argc > 4 ? std::atoi(argv[4]) : 1024;
  const int per_class = argc > 5 ? std::atoi(argv[5]) : 150;
  const double albedo = 0.2;  // the exposure run's default; it cancels in the relative differences
  GDALAllRegister();
  const skyview::Terrain dsm = skyview::read_terrain(dsm_path, {});
  const skyview::Terrain dem = skyview::read_terrain(dem_path, {});
  GDALDatasetUniquePtr ex(GDALDataset::Open(exposure_path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!ex) return 1;
  int cols = 0, rows = 0;
  const std::vector<float> total = read_band(*ex, "total", cols, rows);
  const std::vector<float> reflected = read_band(*ex, "reflected", cols, rows);
  if (cols != dsm.width() || rows != dsm.height() || dem.width() != cols || dem.height() != rows) {
    std::fprintf(stderr, "DSM, DEM and exposure differ in size\n");
    return 1;
  }
  const skyview::Scene scene = skyview::load_scene({dsm_path});
  const skyview::RayScene ray_scene(scene);
  const auto& gt = dsm.georef.geotransform;
  auto z_of = [&](int c, int r) { return dsm.base_height + dsm.heights(c, r); };
  auto above_ground = [&](int c, int r) { return z_of(c, r) - (dem.base_height + dem.heights(c, r)); };
  // Horn's normal (east, north, up) on 1 m-square north-up cells scaled by the geotransform.
  auto horn_normal = [&](int c, int r) {
    auto z = [&](int dc, int dr) { return z_of(c + dc, r + dr); };
    const double dzdx = ((z(1, -1) + 2 * z(1, 0) + z(1, 1)) - (z(-1, -1) + 2 * z(-1, 0) + z(-1, 1))) / (8 * gt[1]);
    const double dzdy = ((z(-1, -1) + 2 * z(0, -1) + z(1, -1)) - (z(-1, 1) + 2 * z(0, 1) + z(1, 1))) / (8 * -gt[5]);
    std::array<double, 3> n{-dzdx, -dzdy, 1.0};
    const double len = std::hypot(n[0], n[1], n[2]);
    for (double& x : n) x /= len;
    return n;
  };
  // Classes: roof (more than 3 m above the DEM, Horn slope under 10 degrees), street (under 0.5 m
  // above it, flat, nothing over 3 m within 2 cells), wall foot (under 0.5 m above it with an
  // 8-neighbour 3 m or more higher). 20 cells from the raster's sides, where rays leave early.
  enum Class { roof, street, wall_foot };
  const char* class_name[] = {"roofs", "streets", "wall feet"};
  std::vector<std::pair<int, int>> cells[3];
  const int margin = 20;
  for (int r = margin; r < rows - margin; ++r) {
    for (int c = margin; c < cols - margin; ++c) {
      if (std::isnan(total[r * cols + c]) || std::isnan(reflected[r * cols + c])) continue;
      const double h = above_ground(c, r);
      const double slope = std::acos(horn_normal(c, r)[2]);
      bool step = false, tall_near = false;
      for (int dr = -2; dr <= 2; ++dr) {
        for (int dc = -2; dc <= 2; ++dc) {
          if (std::max(std::abs(dc), std::abs(dr)) == 1 && z_of(c + dc, r + dr) - z_of(c, r) >= 3.0) step = true;
          if (above_ground(c + dc, r + dr) > 3.0) tall_near = true;
        }
      }
      if (h > 3.0 && slope < 10 * std::numbers::pi / 180)
        cells[roof].push_back({c, r});
      else if (h < 0.5 && step)
        cells[wall_foot].push_back({c, r});
      else if (h < 0.5 && !tall_near && slope < 10 * std::numbers::pi / 180)
        cells[street].push_back({c, r});
    }
  }
  std::mt19937 random(33);
  std::printf("class      cells  isotropic  ray-cast  mean rel  p50 |rel|  p95 |rel|  (kWh/m2; rel = ray/iso - 1)\n");
  for (int k = 0; k < 3; ++k) {
    std::vector<std::pair<int, int>>& pool = cells[k];
    const std::size_t found = pool.size();
    std::shuffle(pool.begin(), pool.end(), random);
    if (static_cast<int>(pool.size()) > per_class) pool.resize(per_class);
    std::vector<double> rel, abs_rel;
    double sum_iso = 0, sum_ray = 0;
    int skipped = 0;
    for (const auto& [c, r] : pool) {
      const auto n = horn_normal(c, r);
      // The surface under the cell centre, from above, and the eye 5 cm off it along the normal.
      const float x = static_cast<float>(dsm.georef.x_of(c, r) - scene.origin[0]);
      const float y = static_cast<float>(dsm.georef.y_of(c, r) - scene.origin[1]);
      const auto down = ray_scene.intersect({x, y, 10000.0f}, {0, 0, -1});
      if (!down) {
        ++skipped;
        continue;
      }
      const double ground = 10000.0 - down->t;
      const double eye[3] = {x + 0.05 * n[0], y + 0.05 * n[1], ground + 0.05 * n[2]};
      // A frame about the normal.
      std::array<double, 3> t1 = std::abs(n[2]) < 0.9 ? std::array<double, 3>{-n[1], n[0], 0.0}
                                                      : std::array<double, 3>{1.0, 0.0, -n[0] / n[2]};
      const double l1 = std::hypot(t1[0], t1[1], t1[2]);
      for (double& v : t1) v /= l1;
      const std::array<double, 3> t2{n[1] * t1[2] - n[2] * t1[1], n[2] * t1[0] - n[0] * t1[2],
                                     n[0] * t1[1] - n[1] * t1[0]};
      const int side = std::max(1, static_cast<int>(std::sqrt(rays)));
      std::uniform_real_distribution<double> u01(0.0, 1.0);
      double sum = 0;
      for (int i = 0; i < side; ++i) {
        for (int j = 0; j < side; ++j) {
          // Stratified cosine-weighted directions (Malley).
          const double u = (i + u01(random)) / side, v = (j + u01(random)) / side;
          const double s = std::sqrt(u), phi = 2 * std::numbers::pi * v, cz = std::sqrt(1 - u);
          const double a = s * std::cos(phi), b = s * std::sin(phi);
          const skyview::Vec3f d{static_cast<float>(a * t1[0] + b * t2[0] + cz * n[0]),
                                 static_cast<float>(a * t1[1] + b * t2[1] + cz * n[1]),
                                 static_cast<float>(a * t1[2] + b * t2[2] + cz * n[2])};
          const skyview::Vec3f o{static_cast<float>(eye[0]), static_cast<float>(eye[1]), static_cast<float>(eye[2])};
          const auto hit = ray_scene.intersect(o, d, 0.0f);
          if (!hit) continue;  // sky
          const double hx = eye[0] + hit->t * d[0] + scene.origin[0], hy = eye[1] + hit->t * d[1] + scene.origin[1];
          const int hc = static_cast<int>(std::floor((hx - gt[0]) / gt[1]));
          const int hr = static_cast<int>(std::floor((hy - gt[3]) / gt[5]));
          if (hc < 0 || hr < 0 || hc >= cols || hr >= rows) continue;
          const float e = total[hr * cols + hc] - reflected[hr * cols + hc];
          if (!std::isnan(e)) sum += e;
        }
      }
      const double ray_cast = albedo * sum / (side * side);
      const double iso = reflected[r * cols + c];
      sum_iso += iso, sum_ray += ray_cast;
      if (iso > 1e-3) {
        rel.push_back(ray_cast / iso - 1.0);
        abs_rel.push_back(std::abs(rel.back()));
      }
    }
    const std::size_t m = pool.size() - skipped;
    double mean_rel = 0;
    for (double x : rel) mean_rel += x;
    mean_rel = rel.empty() ? NAN : mean_rel / rel.size();
    std::printf("%-10s %5zu  %9.4f  %8.4f  %+8.3f  %9.3f  %9.3f  (%zu with isotropic > 0.001, of %zu found)\n",
                class_name[k], m, sum_iso / m, sum_ray / m, mean_rel, percentile(abs_rel, 0.5),
                percentile(abs_rel, 0.95), rel.size(), found);
  }
  return 0;
}
