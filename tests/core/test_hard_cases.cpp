// The hard cases: thin walls, spikes, degenerate shapes, nodata, extreme heights and cell
// sizes, high latitudes, the antimeridian, and directions exactly along the grid.
#include <gdal_priv.h>
#include <GeographicLib/Geodesic.hpp>

#include "test_support.h"

using namespace skyview;
using namespace skyview::test;

namespace {

// "sweep2": the sweep with two far lines (test_support.h).
const char* kExactMethods[] = {"march", "sweep", "sweep2", "raycast"};

// All three read the same mesh exactly; the ray cast brackets horizons to 1e-5 rad (rays closer to
// a surface may graze it), the march and the sweep are exact to float precision.
double tol(const std::string& method) { return method == "raycast" ? 2e-5 : 1e-5; }

HorizonField horizons(const Terrain& t, const std::string& name, int directions, bool lower = false) {
  HorizonParams p;
  const std::string method = engine_method(name, p);
  p.directions = directions;
  p.lower = lower;
  p.rays = 0;
  // The sampled method spreads its samples up to the radius: keep them on these small rasters.
  if (method != "sweep") p.radius = method == "sampled" ? 50.0 : 1e5;
  HorizonField f;
  ProgressCounter progress;
  make_horizon_engine(method, p)->compute(t, Window::whole(t), f, progress);
  return f;
}

// Every valid cell gets finite angles within [-90°, 90°]; nodata cells get NaN.
void expect_sane(const Terrain& t, const HorizonField& f, const std::string& what) {
  for (int r = 0; r < t.height(); ++r) {
    for (int c = 0; c < t.width(); ++c) {
      for (int k = 0; k < f.directions; ++k) {
        const float h = f.upper_at(f.cell(c, r), k);
        if (!t.valid(c, r)) {
          ASSERT_TRUE(std::isnan(h)) << what;
        } else {
          ASSERT_TRUE(std::isfinite(h)) << what << " cell " << c << "," << r;
          ASSERT_GE(h, -M_PI / 2 - 1e-6) << what;
          ASSERT_LE(h, M_PI / 2 + 1e-6) << what;
        }
      }
    }
  }
}

TEST(HardCases, OneCellThickWallAndSpikeGiveTheirExactAngle) {
  // A wall one cell thick along a column, 10 m west of the observer: atan(H / 10) looking west.
  Terrain wall = rasterize([](double e, double) { return std::abs(e + 10.0) < 0.5 ? 25.0 : 0.0; }, 41, 41,
                           local_grid(41, 41, 1.0));
  Terrain spike =
      rasterize([](double e, double n) { return std::abs(e) < 0.5 && std::abs(n - 5.0) < 0.5 ? 30.0 : 0.0; }, 41, 41,
                local_grid(41, 41, 1.0));
  for (const char* m : kExactMethods) {
    const HorizonField fw = horizons(wall, m, 8);
    EXPECT_NEAR(fw.upper_at(fw.cell(20, 20), 6), std::atan(25.0 / 10.0), tol(m)) << m;  // west
    EXPECT_NEAR(fw.upper_at(fw.cell(20, 20), 2), 0.0, tol(m)) << m;                     // east: open
    const HorizonField fs = horizons(spike, m, 8);
    EXPECT_NEAR(fs.upper_at(fs.cell(20, 20), 0), std::atan(30.0 / 5.0), tol(m)) << m;  // north
    expect_sane(wall, fw, m);
  }
}

TEST(HardCases, SingleCellPitSeesItsNeighboursAlongAxesAndDiagonals) {
  Terrain pit = rasterize([](double e, double n) { return std::abs(e) < 0.5 && std::abs(n) < 0.5 ? -2.0 : 0.0; }, 21,
                          21, local_grid(21, 21, 1.0));
  for (const char* m : kExactMethods) {
    const HorizonField f = horizons(pit, m, 8);
    const std::size_t c = f.cell(10, 10);
    for (int k = 0; k < 8; k += 2) EXPECT_NEAR(f.upper_at(c, k), std::atan(2.0), tol(m)) << m << " axis " << k;
    for (int k = 1; k < 8; k += 2)
      EXPECT_NEAR(f.upper_at(c, k), std::atan(2.0 / std::sqrt(2.0)), tol(m)) << m << " diagonal " << k;
  }
}

TEST(HardCases, OneRowAndOneColumnRasters) {
  // A profile with a 10 m step 20 m away, stored as 1 x N and as N x 1.
  const int n = 61;
  Terrain row = rasterize([](double e, double) { return e > 19.5 ? 10.0 : 0.0; }, n, 1, local_grid(n, 1, 1.0));
  Terrain col = rasterize([](double, double nn) { return nn > 19.5 ? 10.0 : 0.0; }, 1, n, local_grid(1, n, 1.0));
  for (const char* m : {"march", "sweep", "sweep2", "raycast", "sampled"}) {
    const HorizonField fr = horizons(row, m, 4), fc = horizons(col, m, 4);
    expect_sane(row, fr, m);
    expect_sane(col, fc, m);
    if (std::string(m) == "sampled") continue;
    EXPECT_NEAR(fr.upper_at(fr.cell(30, 0), 1), std::atan(10.0 / 20.0), tol(m)) << m;  // east
    EXPECT_NEAR(fc.upper_at(fc.cell(0, 30), 0), std::atan(10.0 / 20.0), tol(m)) << m;  // north
  }
}

TEST(HardCases, NodataHolesAndBordersStayNodataAndNeverOcclude) {
  Terrain t = rasterize(synthetic_city(5), 81, 81, local_grid(81, 81, 1.0));
  for (int i = 0; i < 81; ++i) {
    t.heights(i, 0) = t.heights(0, i) = t.heights(80, i) = t.heights(i, 80) = NAN;  // border
  }
  for (int r = 30; r < 40; ++r) {
    for (int c = 30; c < 45; ++c) t.heights(c, r) = NAN;  // hole
  }
  for (const char* m : {"march", "sweep", "sweep2", "raycast", "sampled"}) expect_sane(t, horizons(t, m, 16, true), m);
}

// A fill value under GDAL's mask (a GeoTIFF's internal mask, or an alpha band, which GDAL takes for
// a mask in Byte rasters) is no height: read as nodata, it never occludes the flat ground around
// it. Until Dec 5 the mask was ignored and the fill stood as a tower.
TEST(HardCases, CellsUnderTheBandsMaskAreNodata) {
  init_gdal();
  const std::string dir = temp_dir("mask");
  for (const bool alpha : {false, true}) {
    const std::string path = dir + (alpha ? "/alpha.tif" : "/mask.tif");
    {
      GDALDriver* gtiff = GetGDALDriverManager()->GetDriverByName("GTiff");
      GDALDatasetUniquePtr ds(
          gtiff->Create(path.c_str(), 15, 15, alpha ? 2 : 1, alpha ? GDT_Byte : GDT_Float32, nullptr));
      double gt[6] = {500000, 1, 0, 5000015, 0, -1};
      ds->SetGeoTransform(gt);
      ds->SetProjection(wkt_of("EPSG:32633").c_str());
      std::vector<float> z(225, 100.0f), valid(225, 255.0f);
      for (int r = 5; r < 10; ++r) {
        for (int c = 5; c < 10; ++c) z[r * 15 + c] = 250.0f, valid[r * 15 + c] = 0.0f;
      }
      ASSERT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, 15, 15, z.data(), 15, 15, GDT_Float32, 0, 0), CE_None);
      GDALRasterBand* m = nullptr;
      if (alpha) {
        m = ds->GetRasterBand(2);
        m->SetColorInterpretation(GCI_AlphaBand);
      } else {
        ASSERT_EQ(ds->CreateMaskBand(GMF_PER_DATASET), CE_None);
        m = ds->GetRasterBand(1)->GetMaskBand();
      }
      ASSERT_EQ(m->RasterIO(GF_Write, 0, 0, 15, 15, valid.data(), 15, 15, GDT_Float32, 0, 0), CE_None);
    }
    ReadReport report;
    const Terrain t = read_terrain(path, {}, &report);
    EXPECT_EQ(report.masked_cells, 25) << path;
    EXPECT_EQ(report.nodata_cells, 25) << path;
    EXPECT_FALSE(t.valid(7, 7)) << path;
    EXPECT_TRUE(t.valid(4, 7)) << path;
    const HorizonField f = horizons(t, "sweep", 16);
    for (int k = 0; k < 16; ++k) EXPECT_EQ(f.upper_at(f.cell(4, 7), k), 0.0f) << path << " direction " << k;
    const RasterBand band = read_band(path, 1);
    EXPECT_TRUE(std::isnan(band.values(7, 7))) << path;
    EXPECT_EQ(band.values(4, 7), 100.0f) << path;
  }
}

// A raster with no geotransform is an image: its first row is its top, north, as QGIS shows it.
// Until Dec 5 GDAL's stand-in geotransform (rows running north) put a wall above a cell in the
// image into its southern horizon band.
TEST(HardCases, ARasterWithoutAGeotransformIsNorthUp) {
  init_gdal();
  const std::string path = temp_dir("nogt") + "/wall.tif";
  {
    GDALDriver* gtiff = GetGDALDriverManager()->GetDriverByName("GTiff");
    GDALDatasetUniquePtr ds(gtiff->Create(path.c_str(), 41, 41, 1, GDT_Float32, nullptr));
    std::vector<float> z(41 * 41, 0.0f);
    for (int c = 0; c < 41; ++c) z[10 * 41 + c] = 50.0f;  // a wall along row 10, above (20, 20)
    ASSERT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, 41, 41, z.data(), 41, 41, GDT_Float32, 0, 0), CE_None);
  }
  const Terrain t = read_terrain(path, {});
  ASSERT_FALSE(t.georef.has_geotransform);
  const HorizonField f = horizons(t, "sweep", 4);  // north, east, south, west
  EXPECT_NEAR(f.upper_at(f.cell(20, 20), 0), std::atan2(50.0, 10.0), 1e-5);
  EXPECT_EQ(f.upper_at(f.cell(20, 20), 2), 0.0f);
}

// A city framed by nodata on two sides (a collar, as clipped tiles have), then also holed in the
// middle. The ray cast's rays along the grid (and steep rays that fall into the hole and under its
// skirt) can pass into the terrain through a hit lost in rounding; until Dec 3 the test of where
// their track ends bounded nothing when it ended on the collar, and they escaped: over this raster
// up to 1.64 rad off, 59° south of one cell read as -50°. With the hole, lowest angles are left
// out: past its corners the ray cast reads the half quads' open diagonals, which the march does
// not (docs/sky_view.md), and their lowest angles differ by up to 0.09 rad there.
TEST(HardCases, RayCastOverANodataCollarAndHoleMatchesTheMarch) {
  Terrain t = rasterize(synthetic_city(5), 81, 81, local_grid(81, 81, 1.0));
  for (int i = 0; i < 81; ++i) {
    for (int k = 0; k < 3; ++k) t.heights(k, i) = t.heights(i, 80 - k) = NAN;
  }
  FieldDifference d = field_difference(horizons(t, "raycast", 16, true), horizons(t, "march", 16, true));
  EXPECT_LT(d.worst, 1e-3) << "radians, collar";
  EXPECT_EQ(d.nan_mismatches, 0u);
  EXPECT_GT(d.high, 1000u);
  for (int r = 30; r < 34; ++r) {
    for (int c = 40; c < 60; ++c) t.heights(c, r) = NAN;
  }
  const HorizonField march = horizons(t, "march", 16);
  d = field_difference(horizons(t, "raycast", 16), march);
  EXPECT_LT(d.worst, 1e-3) << "radians, collar and hole";
  EXPECT_EQ(d.nan_mismatches, 0u);
}

// A radius means the same to every method: the terrain at every row and column crossing within
// it (the mesh peaks only there). A wall 90 m high stands 11 m east of the cell, on flat ground;
// within 10.3 m the last crossing is the ground at 10 m, where the mesh starts its ramp up to the
// wall. Until Dec 3 the ray cast read the ramp up to 10.3 m itself (69°). Within 0.5 m there is no
// crossing at all, even with the wall 1 m away, which the ray cast's first crossing read regardless.
TEST(HardCases, WithARadiusEveryExactMethodStopsAtTheLastCrossingWithinIt) {
  auto wall_at = [](double east) {
    return rasterize([east](double e, double) { return std::abs(e - east) < 0.5 ? 90.0 : 0.0; }, 41, 41,
                     local_grid(41, 41, 1.0));
  };
  const Terrain far = wall_at(11.0), near = wall_at(1.0);
  auto east = [](const Terrain& t, const char* method, double radius) {
    HorizonParams p;
    p.directions = 8;
    p.radius = radius;
    p.rays = 0;
    HorizonField f;
    ProgressCounter progress;
    make_horizon_engine(method, p)->compute(t, Window{20, 20, 1, 1}, f, progress);
    return f.upper_at(0, 2);
  };
  for (const char* m : {"march", "sweep", "raycast"}) {
    EXPECT_NEAR(east(far, m, 10.3), 0.0, tol(m)) << m;
    EXPECT_NEAR(east(far, m, 11.0), std::atan(90.0 / 11.0), tol(m)) << m;
    EXPECT_NEAR(east(near, m, 0.5), 0.0, tol(m)) << m << ": no crossing within the radius";
  }
}

// A ray exactly along a hole's rim, or along the open diagonal of a quad with one nodata corner,
// runs along mesh edges that only one triangle holds, where Embree's watertight test can drop hits.
// Without the skirt the ray cast hangs on such edges it saw nothing east along the rim (0 against
// 0.62 rad); along the diagonal rounding put its rays on the triangles' side either way (both
// sides tried), and the skirt is there for the same reason. Row 2 and the cells just above the
// main diagonal are nodata; a spike 5 m high stands on row 3 and on the diagonal, nothing else rises.
TEST(HardCases, RaysAlongAHolesRimAndAHalfQuadsDiagonalMeetTheSpikeThere) {
  Terrain t = rasterize([](double, double) { return 0.0; }, 21, 21, local_grid(21, 21, 1.0));
  for (int i = 0; i < 21; ++i) {
    t.heights(i, 2) = NAN;
    if (i >= 5 && i + 1 < 21) t.heights(i + 1, i) = NAN;
  }
  t.heights(15, 3) = 5.0f;
  t.heights(14, 14) = 5.0f;
  for (const char* m : kExactMethods) {
    const HorizonField f = horizons(t, m, 8);
    EXPECT_NEAR(f.upper_at(f.cell(8, 3), 2), std::atan(5.0 / 7.0), tol(m)) << m << " east along the rim";
    EXPECT_NEAR(f.upper_at(f.cell(8, 8), 3), std::atan(5.0 / (6.0 * std::sqrt(2.0))), tol(m))
        << m << " south-east along the half quads' diagonals";
  }
}

TEST(HardCases, MillimetreReliefAtTheDeadSeaAndOnEverest) {
  for (double base : {-420.0, 8848.0}) {
    const std::string dir = temp_dir("mm" + std::to_string(static_cast<int>(base)));
    // A 1 mm step 5 cm (one cell) east of the observer, stored in a float32 GeoTIFF.
    Terrain t =
        rasterize([](double e, double) { return e > 0.025 ? 0.001 : 0.0; }, 41, 41, local_grid(41, 41, 0.05), base);
    write_terrain(dir + "/step.tif", t, {});
    const Terrain back = read_terrain(dir + "/step.tif", {});
    for (const char* m : kExactMethods) {
      const HorizonField f = horizons(back, m, 4);
      // float32 resolves about 0.5 mm at 8848 m, so the step is stored to within that.
      const double tol = base > 1000 ? std::atan(0.0005 / 0.05) : 2e-4;
      EXPECT_NEAR(f.upper_at(f.cell(20, 20), 1), std::atan(0.001 / 0.05), tol) << m << " base " << base;
      EXPECT_NEAR(f.upper_at(f.cell(20, 20), 3), 0.0, 1e-4) << m << " base " << base;
    }
  }
}

TEST(HardCases, TinyAndHugeCellsGiveTheSameScaledAnswer) {
  // A pit of 20 cells radius and depth, at 0.05 m and at 90 m cells: the same svf.
  for (double cell : {0.05, 90.0}) {
    const int n = 51;
    const Terrain t = rasterize(circular_pit(20 * cell, 20 * cell), n, n, local_grid(n, n, cell));
    HorizonParams p;
    p.directions = 64;
    p.radius = 30 * cell;
    for (const char* m : kExactMethods) {
      const CellResult r = run_cell(t, 25, 25, m, p);
      EXPECT_NEAR(r.svf, 0.5, 0.02) << m << " cell " << cell;
    }
  }
}

GeoReference degrees_grid(int n, double lat, double lon, double cell) {
  const GeographicLib::Geodesic& wgs = GeographicLib::Geodesic::WGS84();
  double lat2, lon2;
  wgs.Direct(lat, lon, 0.0, cell, lat2, lon2);
  const double dlat = lat2 - lat;
  wgs.Direct(lat, lon, 90.0, cell, lat2, lon2);
  const double dlon = lon2 - lon;
  GeoReference g;
  g.has_geotransform = true;
  g.geotransform = {lon - 0.5 * n * dlon, dlon, 0, lat + 0.5 * n * dlat, 0, -dlat};
  g.crs_wkt = wkt_of("EPSG:4326");
  return g;
}

TEST(HardCases, GeographicRasterAtLatitude85AndAcrossTheAntimeridian) {
  const int n = 101;
  const double expected = std::pow(std::cos(std::atan(10.0 / 20.0)), 2);
  for (double lon : {25.0, 180.0}) {  // 180: the raster spans 179.99.. to 180.01..
    const Terrain t = rasterize(circular_pit(20.0, 10.0), n, n, degrees_grid(n, 85.0, lon, 0.5));
    HorizonParams p;
    p.directions = 64;
    p.radius = 24.0;
    for (const char* m : kExactMethods) {
      const CellResult r = run_cell(t, n / 2, n / 2, m, p);
      EXPECT_NEAR(r.svf, expected, 0.01) << m << " lon " << lon;
    }
  }
}

TEST(HardCases, DirectionsExactlyAlongRowsColumnsAndDiagonals) {
  // A square courtyard 20 m wide with 10 m walls, 8 directions: the axes see the wall 10 m away,
  // the diagonals see the corner 10*sqrt(2) m away.
  const Terrain t = rasterize([](double e, double n) { return std::max(std::abs(e), std::abs(n)) > 9.5 ? 10.0 : 0.0; },
                              41, 41, local_grid(41, 41, 1.0));
  for (const char* m : kExactMethods) {
    const HorizonField f = horizons(t, m, 8);
    const std::size_t c = f.cell(20, 20);
    for (int k = 0; k < 8; k += 2) EXPECT_NEAR(f.upper_at(c, k), std::atan(10.0 / 10.0), tol(m)) << m << " " << k;
    for (int k = 1; k < 8; k += 2)
      EXPECT_NEAR(f.upper_at(c, k), std::atan(10.0 / (10.0 * std::sqrt(2.0))), tol(m)) << m << " " << k;
  }
}

// The ray cast's eye sits on its own vertex and its rays ignore the triangles around it. Far from
// the mesh's origin, where floats are coarse, that keeps the near horizons of rough terrain: the
// eye lifted by 64 float steps of the extent (7.6 mm at 1 km) lowered them by up to 0.4 degrees.
TEST(HardCases, RayCastMatchesTheMarchOnRoughTerrainFarFromTheMeshOrigin) {
  const int w = 1001, h = 5;
  const Terrain t = rasterize(
      [](double e, double n) {
        return 0.4 * std::sin(1.7 * e) * std::cos(2.3 * n) + 0.3 * std::sin(5.1 * e + 3.3 * n);
      },
      w, h, local_grid(w, h, 1.0));
  HorizonParams p;
  p.directions = 16;
  p.rays = 0;
  p.radius = 1e5;
  const Window far_end{w - 60, 0, 60, 5};  // the last column and the outer rows too
  HorizonField ray, march;
  ProgressCounter progress;
  make_horizon_engine("raycast", p)->compute(t, far_end, ray, progress);
  make_horizon_engine("march", p)->compute(t, far_end, march, progress);
  double worst = 0;
  for (std::size_t i = 0; i < ray.upper.size(); ++i)
    worst = std::max(worst, double(std::abs(ray.upper[i] - march.upper[i])));
  // Rays due west along the outer rows graze the edge ring, which continues the rough boundary's
  // slope outward: the rounding of a float ray a hair off its row then reads that slope, up to
  // 6.8e-5 rad (the bound was 2e-5 while the ring copied the boundary). The eye lift this guards
  // against was 7e-3.
  EXPECT_LT(worst, 1e-4);
}

// A ray along a grid line meets the mesh on its edges, where Embree can lose a hit in rounding. Just
// above a street's own slope, beside a building's wall, a ray slipped into the terrain and ran under
// it to the raster's edge (a Gothenburg street cell, 1.32 rad off): a ray that ends below the terrain
// counts as blocked. The heights are that street's, 10 x 10 cells of DSM_KRbig.tif from (220, 0).
TEST(HardCases, RayCastAlongAStreetBesideAWallStillMeetsTheBuildingAhead) {
  const float patch[10][10] = {{2.63f, 2.65f, 2.67f, 14.48f, 14.48f, 17.40f, 17.54f, 19.50f, 20.16f, 20.34f},
                               {2.65f, 2.65f, 2.66f, 2.69f, 14.48f, 17.27f, 17.52f, 19.37f, 20.13f, 20.31f},
                               {2.66f, 2.67f, 2.70f, 2.70f, 14.48f, 17.17f, 17.47f, 17.68f, 20.08f, 20.26f},
                               {2.69f, 2.66f, 2.68f, 2.70f, 14.48f, 17.24f, 17.43f, 17.64f, 19.81f, 20.21f},
                               {2.71f, 2.68f, 2.68f, 2.69f, 2.78f, 14.48f, 17.39f, 17.60f, 19.54f, 20.15f},
                               {2.70f, 2.69f, 2.69f, 2.70f, 2.75f, 14.48f, 17.35f, 17.56f, 17.70f, 20.10f},
                               {2.73f, 2.71f, 2.68f, 2.72f, 2.77f, 14.48f, 17.19f, 17.52f, 17.66f, 19.65f},
                               {2.75f, 2.73f, 2.72f, 2.75f, 2.75f, 14.48f, 14.48f, 17.48f, 17.62f, 19.38f},
                               {2.77f, 2.73f, 2.73f, 2.73f, 2.74f, 2.80f, 14.48f, 17.25f, 17.58f, 17.65f},
                               {2.79f, 2.74f, 2.73f, 2.71f, 2.76f, 2.80f, 14.48f, 17.14f, 17.54f, 17.68f}};
  // The grid of DSM_KRbig.tif too (SWEREF99 12 00, 234 x 223 cells): its centre's Jacobian puts
  // vertices off whole metres, where the rounding happens.
  GeoReference grid;
  grid.has_geotransform = true;
  grid.geotransform = {147720, 1, 0, 6398780, 0, -1};
  grid.crs_wkt = wkt_of("EPSG:3007");
  Terrain t = rasterize([](double, double) { return 2.7; }, 234, 223, grid);
  for (int r = 0; r < 10; ++r) {
    for (int c = 0; c < 10; ++c) t.heights(220 + c, r) = patch[r][c];
  }
  HorizonParams p;
  p.directions = 32;
  p.rays = 0;
  p.radius = 1e5;
  HorizonField ray, march;
  ProgressCounter progress;
  make_horizon_engine("raycast", p)->compute(t, Window{224, 6, 1, 1}, ray, progress);
  make_horizon_engine("march", p)->compute(t, Window{224, 6, 1, 1}, march, progress);
  // Within 2e-4 rad: the march turns each azimuth into pixel steps by the cell's own Jacobian, the ray
  // cast by the raster centre's, and beside a wall that shows.
  for (int k = 0; k < 32; ++k) EXPECT_NEAR(ray.upper_at(0, k), march.upper_at(0, k), 2e-4) << "direction " << k;
  EXPECT_GT(march.upper_at(0, 0), 1.3);  // the building three cells north
}

// Just east of a UTM zone's central meridian grid north is a hair west of true north, so a ray due
// east from the outer row climbs off the mesh over cell centres at once (sweep -2.2 and march 0
// degrees against 24.4 on the next row, the bundled city.tif's outer columns up to 68 degrees off
// looking north). The ring of boundary heights around the raster (extend_at_raster_edges) keeps
// such rays on the terrain: every outer cell sees the ridge as the rows inside do.
TEST(HardCases, RaysAlongTheRastersEdgeOnACentralMeridianSeeTheTerrainAhead) {
  const int w = 100, h = 6;
  GeoReference grid;
  grid.has_geotransform = true;
  grid.geotransform = {500000, 1, 0, 6400000, 0, -1};
  grid.crs_wkt = wkt_of("EPSG:32633");
  // A ridge along column 50, the same on every row.
  Terrain t = rasterize([](double, double) { return 0.0; }, w, h, grid);
  auto ridge_at = [](int c) { return 10.0 * std::exp(-(c - 50.0) * (c - 50.0) / 300.0); };
  for (int r = 0; r < h; ++r) {
    for (int c = 0; c < w; ++c) t.heights(c, r) = static_cast<float>(ridge_at(c));
  }
  // From column 30 looking east (and, by symmetry, from 70 looking west): the steepest vertex ahead.
  double ridge = -M_PI / 2;
  for (int c = 31; c < w; ++c) ridge = std::max(ridge, std::atan2(ridge_at(c) - ridge_at(30), c - 30.0));
  ASSERT_GT(ridge, 0.4);
  for (const char* m : kExactMethods) {
    const HorizonField f = horizons(t, m, 4);  // north, east, south, west
    for (int r = 0; r < h; ++r) {
      EXPECT_NEAR(f.upper_at(f.cell(30, r), 1), ridge, 1e-3) << m << " row " << r << " east";
      EXPECT_NEAR(f.upper_at(f.cell(70, r), 3), ridge, 1e-3) << m << " row " << r << " west";
    }
  }
}

}  // namespace
