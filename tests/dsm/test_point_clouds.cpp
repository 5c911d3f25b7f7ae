// Point clouds other than LAS (text, PLY, PCD), IDW gridding, and the PCL filters: every format
// gives the same grid for the same points; IDW, denoising and the ground filter give known cells.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "core/test_support.h"
#include "skyview/dsm/dsm_builder.h"
#include "skyview/core/error.h"
#include "skyview/dsm/las_file.h"
#include "skyview/dsm/point_cloud.h"
#include "skyview/dsm/point_gridder.h"

using namespace skyview;

namespace {

void write_text(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

DsmOptions grid_10m(const std::string& cloud) {
  DsmOptions d;
  d.points = {cloud};
  d.s_srs = "EPSG:32633";
  d.res = 1.0;
  d.te = std::array<double, 4>{500000, 6400000, 500010, 6400010};
  return d;
}

}  // namespace

TEST(PointClouds, TextPlyAndPcdGiveTheSameCellsAsLas) {
  const std::string dir = test::temp_dir("clouds");
  // Cell (2, 1) holds 10, 13 and 16 (classes 6, 6, 2); cell (0, 0) holds 5.
  const std::vector<LasPoint> pts = {{500002.5, 6400008.5, 10.0, 0, 1, 1, 6},
                                     {500002.2, 6400008.7, 13.0, 0, 1, 1, 6},
                                     {500002.9, 6400008.1, 16.0, 0, 1, 1, 2},
                                     {500000.5, 6400009.5, 5.0, 0, 1, 1, 2}};
  LasWriteOptions lo;
  lo.offset[0] = 500000, lo.offset[1] = 6400000;
  write_las(dir + "/p.las", pts, lo);
  write_text(
      dir + "/p.csv",
      "# exported by a scanner\nx,y,z,intensity\n500002.5,6400008.5,10,7\n# a comment\n500002.2,6400008.7,13,7\n\n"
      "500002.9;6400008.1;16\n500000.5 6400009.5\t5\n");
  write_text(dir + "/p.ply",
             "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\n"
             "property uchar classification\nend_header\n500002.5 6400008.5 10 6\n500002.2 6400008.7 13 6\n"
             "500002.9 6400008.1 16 2\n500000.5 6400009.5 5 2\n");
  // PCD in float, so coordinates are local (a float UTM northing would lose half a metre).
  write_text(dir + "/p.pcd",
             "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z label\nSIZE 4 4 4 4\nTYPE F F F U\nCOUNT 1 1 1 1\n"
             "WIDTH 4\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 4\nDATA ascii\n2.5 8.5 10 6\n2.2 8.7 13 6\n"
             "2.9 8.1 16 2\n0.5 9.5 5 2\n");
  for (const std::string name : {"p.las", "p.csv", "p.ply", "p.pcd"}) {
    DsmOptions d = grid_10m(dir + "/" + name);
    if (name == "p.pcd") d.te = std::array<double, 4>{0, 0, 10, 10};
    for (const auto& [stat, expected] :
         std::vector<std::pair<std::string, float>>{{"max", 16}, {"mean", 13}, {"min", 10}}) {
      d.stat = stat;
      const DsmResult r = build_dsm(d);
      EXPECT_FLOAT_EQ(r.dsm(2, 1), expected) << name << " " << stat;
      EXPECT_FLOAT_EQ(r.dsm(0, 0), 5.0f) << name << " " << stat;
      EXPECT_TRUE(std::isnan(r.dsm(5, 5))) << name;
    }
    // Classes survive where the format has them; text clouds are unclassified.
    d.stat = "max";
    d.classes = {6};
    if (name == "p.csv") {
      EXPECT_THROW(build_dsm(d), Error);
    } else {
      EXPECT_FLOAT_EQ(build_dsm(d).dsm(2, 1), 13.0f) << name;
    }
  }
  EXPECT_EQ(open_point_cloud(dir + "/p.csv")->point_count(), 4u);
  const auto ply = open_point_cloud(dir + "/p.ply");
  const double* b = ply->bounds();
  EXPECT_DOUBLE_EQ(b[0], 500000.5);
  EXPECT_DOUBLE_EQ(b[3], 6400009.5);
}

TEST(PointClouds, BadCloudsGiveOneLineErrors) {
  const std::string dir = test::temp_dir("badclouds");
  auto open_error = [&](const std::string& name, const std::string& text) {
    write_text(dir + "/" + name, text);
    try {
      open_point_cloud(dir + "/" + name);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  EXPECT_NE(open_error("bad.xyz", "1 2 3\n4 five 6\n").find("line 2"), std::string::npos);
  // A first line of two numbers is short data, not a header.
  EXPECT_NE(open_error("short.xyz", "1 2\n3 4 5\n").find("line 1: expected x y z"), std::string::npos);
  write_text(dir + "/empty.xyz", "x y z\n");
  EXPECT_THROW(build_dsm(grid_10m(dir + "/empty.xyz")), Error);
  write_text(dir + "/cloud.e57", "nothing");
  EXPECT_THROW(open_point_cloud(dir + "/cloud.e57"), Error);
  write_text(dir + "/broken.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header\n1\n");
  EXPECT_THROW(open_point_cloud(dir + "/broken.ply"), Error);
  EXPECT_THROW(open_point_cloud(dir + "/missing.pcd"), Error);
  // PCL 1.13's reader crashes on these (until Dec 5 the run ended with a segfault): refused first.
  for (const auto& [name, text] : {std::pair{"empty.pcd", ""}, std::pair{"garbage.pcd", "garbage\n"},
                                   std::pair{"cut.pcd", "# .PCD v0.7\nVERSION 0.7\nFIE"},
                                   std::pair{"nofields.pcd", "VERSION 0.7\nWIDTH 1\nPOINTS 1\nDATA ascii\n1 2 3\n"}}) {
    const std::string message = open_error(name, text);
    EXPECT_NE(message.find("is not a readable PCD point cloud"), std::string::npos) << name << ": " << message;
  }
  EXPECT_THROW(parse_grid_statistic("median"), Error);
  // Coordinates that do not fit the CRS given for them: UTM metres declared as degrees.
  write_text(dir + "/utm.xyz", "500010 6400010 5\n500020 6400020 6\n");
  DsmOptions wrong = grid_10m(dir + "/utm.xyz");
  wrong.s_srs = "EPSG:4326";
  wrong.t_srs = "EPSG:32633";
  wrong.te.reset();
  try {
    build_dsm(wrong);
    FAIL() << "a cloud in the wrong CRS was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("utm.xyz"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("CRS"), std::string::npos) << e.what();
  }
}

// PLY and PCD points without finite coordinates (PCD's mark of a missing return) are left out,
// counted and said (until Dec 5 they vanished: "2 of 2 points used" from a file of 4).
TEST(PointClouds, NonFinitePlyAndPcdPointsAreCounted) {
  const std::string dir = test::temp_dir("nanclouds");
  write_text(dir + "/nan.ply",
             "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\n"
             "end_header\n500001 6400001 5\nnan 6400002 6\n500003 6400003 nan\n500004 6400004 8\n");
  write_text(dir + "/nan.pcd",
             "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 8 8 8\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 4\nHEIGHT 1\n"
             "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 4\nDATA ascii\n500001 6400001 5\nnan nan nan\n500003 6400003 7\n"
             "500004 6400004 nan\n");
  for (const char* name : {"nan.ply", "nan.pcd"}) {
    const auto cloud = open_point_cloud(dir + "/" + name);
    EXPECT_EQ(cloud->point_count(), 2u) << name;
    ASSERT_EQ(cloud->warnings().size(), 1u) << name;
    EXPECT_NE(cloud->warnings()[0].find("2 of the 4 points"), std::string::npos) << cloud->warnings()[0];
  }
}

// --te is the grid's extent, as gdalwarp -te keeps it: its corner is the grid's corner, not
// snapped to whole multiples of the resolution (until Dec 5, 500000.25 became 500000).
TEST(PointClouds, TeIsKeptExactly) {
  const std::string dir = test::temp_dir("te");
  write_text(dir + "/c.xyz", "500001 6400001 5\n500004 6400004 8\n");
  DsmOptions d = grid_10m(dir + "/c.xyz");
  d.te = std::array<double, 4>{500000.25, 6400000.25, 500010.25, 6400010.25};
  const DsmResult r = build_dsm(d);
  EXPECT_EQ(r.georef.geotransform[0], 500000.25);
  EXPECT_EQ(r.georef.geotransform[3], 6400010.25);
  EXPECT_EQ(r.dsm.width(), 10);
  EXPECT_EQ(r.dsm.height(), 10);
}

// A single return, or a row of them, has a place but no area: it still makes a grid of one cell,
// or one row (until Dec 5: "the inputs cover no area (empty point cloud ...)" for a cloud that is not).
TEST(PointClouds, ASingleReturnOrARowOfThemMakesAGrid) {
  const std::string dir = test::temp_dir("onepoint");
  write_text(dir + "/one.xyz", "500000.5 6400000.5 10\n");
  write_text(dir + "/row.xyz", "500000.5 6400000.5 10\n500005.5 6400000.5 12\n");
  DsmOptions one;
  one.points = {dir + "/one.xyz"};
  one.s_srs = "EPSG:32633";
  const DsmResult a = build_dsm(one);
  ASSERT_EQ(a.dsm.width(), 1);
  ASSERT_EQ(a.dsm.height(), 1);
  EXPECT_FLOAT_EQ(a.dsm(0, 0), 10.0f);
  DsmOptions row = one;
  row.points = {dir + "/row.xyz"};
  const DsmResult b = build_dsm(row);
  EXPECT_EQ(b.dsm.width(), 6);
  EXPECT_EQ(b.dsm.height(), 1);
  EXPECT_FLOAT_EQ(b.dsm(5, 0), 12.0f);
}

TEST(PointClouds, IdwWeighsReturnsByInverseSquaredDistance) {
  // A at the centre of cell (2, 2), B half a cell east of it: midway to the centre of (3, 2).
  PointGridder g({10, 10, 0.0, 10.0, 1.0}, GridStatistic::idw, 1.0, 2.0);
  g.add(2.5, 7.5, 10.0f);
  g.add(3.0, 7.5, 20.0f);
  std::int64_t cells = 0;
  const Grid<float> r = g.finish(&cells);
  // (2, 2): A at the clamped 1e-3 cell (weight 1e6), B at 0.5 (weight 4).
  EXPECT_NEAR(r(2, 2), (1e6 * 10 + 4 * 20) / (1e6 + 4), 1e-4);
  // (3, 2): A at 1 cell (weight 1), B at 0.5 (weight 4).
  EXPECT_NEAR(r(3, 2), (10.0 + 4 * 20.0) / 5.0, 1e-5);
  // (2, 1) is 1 cell north of A and sqrt(1.25) from B, beyond the radius.
  EXPECT_NEAR(r(2, 1), 10.0, 1e-5);
  EXPECT_TRUE(std::isnan(r(6, 6)));
  EXPECT_EQ(cells, 5);  // (2,2), (3,2) and A's north, south and west neighbours at exactly 1 cell
}

TEST(PointClouds, DenoiseRemovesAnIsolatedSpike) {
  const std::string dir = test::temp_dir("denoise");
  std::string text;
  for (int i = 0; i < 40; ++i) {
    for (int j = 0; j < 40; ++j) {
      text += std::to_string(500000.125 + 0.25 * i) + " " + std::to_string(6400000.125 + 0.25 * j) + " 7\n";
    }
  }
  text += "500005.1 6400005.1 87\n";  // a bird 80 m up
  write_text(dir + "/birds.xyz", text);
  DsmOptions d = grid_10m(dir + "/birds.xyz");
  EXPECT_FLOAT_EQ(build_dsm(d).dsm(5, 4), 87.0f);
  d.denoise = true;
  const DsmResult r = build_dsm(d);
  EXPECT_EQ(r.report.points_removed_as_noise, 1u);
  EXPECT_FLOAT_EQ(r.dsm(5, 4), 7.0f);
}

TEST(PointClouds, GroundOnlyFiltersAnUnclassifiedCloudMorphologically) {
  const std::string dir = test::temp_dir("pmf");
  // Ground at 5 m over 40 x 40 m (4 returns per m2), a 10 x 10 m building of 12 m at its centre.
  std::vector<LasPoint> pts;
  for (int i = 0; i < 80; ++i) {
    for (int j = 0; j < 80; ++j) {
      const double x = 500000.25 + 0.5 * i, y = 6400000.25 + 0.5 * j;
      const bool roof = x > 500015 && x < 500025 && y > 6400015 && y < 6400025;
      pts.push_back({x, y, roof ? 17.0 : 5.0, 0, 1, 1, 1});
    }
  }
  LasWriteOptions lo;
  lo.offset[0] = 500000, lo.offset[1] = 6400000;
  write_las(dir + "/u.las", pts, lo);
  DsmOptions d = grid_10m(dir + "/u.las");
  d.te = std::array<double, 4>{500000, 6400000, 500040, 6400040};
  d.ground_only = true;
  DsmResult r = build_dsm(d);
  EXPECT_EQ(r.report.ground_source, "morphological filter");
  EXPECT_TRUE(std::isnan(r.dsm(20, 20)));  // the roof is not ground
  EXPECT_FLOAT_EQ(r.dsm(5, 5), 5.0f);
  EXPECT_FLOAT_EQ(r.dsm(35, 20), 5.0f);
  int ground_cells = 0;
  for (float v : r.dsm.values()) ground_cells += v == 5.0f;
  EXPECT_EQ(ground_cells, 40 * 40 - 10 * 10);
  // With --fill the roof's cells close at ground level: the bare earth under the building.
  d.fill = true;
  r = build_dsm(d);
  EXPECT_NEAR(r.dsm(20, 20), 5.0f, 1e-4);
  // A classified cloud uses its class 2 instead.
  for (auto& p : pts) p.classification = p.z > 10 ? 6 : 2;
  write_las(dir + "/c.las", pts, lo);
  d.points = {dir + "/c.las"};
  d.fill = false;
  r = build_dsm(d);
  EXPECT_EQ(r.report.ground_source, "class 2");
  EXPECT_TRUE(std::isnan(r.dsm(20, 20)));
}
