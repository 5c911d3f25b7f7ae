// The hand-written LAS reader against every shared sample file and synthetic files of every
// point format, and against truncated and corrupt input.
#include <gtest/gtest.h>

#include <ogr_spatialref.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>

#include "core/test_support.h"
#include "skyview/core/error.h"
#include "skyview/dsm/las_file.h"
#include "skyview/dsm/point_cloud.h"
#include "temp_dir.h"

using namespace skyview;

namespace {

std::string las_sample(const std::string& name) {
  const std::string p = std::string(SKYVIEW_SHARED_DIR) + "/sample_data/las/" + name;
  return std::filesystem::exists(p) ? p : std::string();
}

std::vector<LasPoint> read_all(const LasReader& r, std::size_t chunk = 1 << 20) {
  std::vector<LasPoint> all;
  r.read_points([&](const std::vector<LasPoint>& c) { all.insert(all.end(), c.begin(), c.end()); }, chunk);
  return all;
}

struct Sample {
  const char* file;
  int minor, format;
  std::uint64_t points;
};

TEST(LasFile, EverySharedSampleOpensWithItsDocumentedCountsAndBounds) {
  const Sample samples[] = {{"simple.las", 2, 3, 1065},
                            {"simple1_1.las", 1, 1, 1065},
                            {"simple1_3.las", 3, 4, 999},
                            {"simple1_4.las", 4, 7, 22600},
                            {"test1_4.las", 4, 6, 1000},
                            {"1_4_w_evlr.las", 4, 6, 1000},
                            {"extrabytes.las", 4, 3, 1065},
                            {"unregistered_extra_bytes.las", 4, 6, 4},
                            {"autzen_geo_proj.las", 2, 1, 106},
                            {"vegetation_1_3.las", 3, 1, 10683},
                            {"file_with_both_wkt_and_geotiff_vlrs.las", 4, 6, 25408}};
  if (las_sample("simple.las").empty()) GTEST_SKIP() << "../shared/sample_data is absent";
  for (const Sample& s : samples) {
    const LasReader r = LasReader::open_file(las_sample(s.file));
    EXPECT_EQ(r.header().version_minor, s.minor) << s.file;
    EXPECT_EQ(r.header().point_format, s.format) << s.file;
    EXPECT_EQ(r.header().point_count, s.points) << s.file;
    EXPECT_EQ(r.header().records_beyond_count, 0u) << s.file << ": waveforms and EVLRs are not points";
    const auto pts = read_all(r, 333);
    ASSERT_EQ(pts.size(), s.points) << s.file;
    // laspy's simple1_3.las stores header bounds that disagree with its points (its "unusual
    // scale/offset" case); the reader never trusts header bounds, so only the others are checked.
    if (std::string(s.file) == "simple1_3.las") continue;
    for (const LasPoint& p : pts) {
      const double v[3] = {p.x, p.y, p.z};
      for (int k = 0; k < 3; ++k) {
        ASSERT_GE(v[k], r.header().min[k] - r.header().scale[k]) << s.file;
        ASSERT_LE(v[k], r.header().max[k] + r.header().scale[k]) << s.file;
      }
    }
  }
}

// A header that counts fewer points than follow is read as it says, and the records past its
// count are reported (until Dec 5, "10 of 10 points used" with 1055 more in the file, unsaid).
TEST(LasFile, RecordsBeyondTheHeadersCountAreReported) {
  const std::string path = test::temp_dir("lascount") + "/under.las";
  write_las(path, {{0, 0, 1, 0, 1, 1, 2}, {1, 1, 2, 0, 1, 1, 2}, {2, 2, 3, 0, 1, 1, 2}}, {});
  {
    std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
    const std::uint32_t one = 1;
    f.seekp(107);
    f.write(reinterpret_cast<const char*>(&one), 4);
  }
  const LasReader r = LasReader::open_file(path);
  EXPECT_EQ(r.header().point_count, 1u);
  EXPECT_EQ(r.header().records_beyond_count, 2u);
  const auto cloud = open_point_cloud(path);
  ASSERT_EQ(cloud->warnings().size(), 1u);
  EXPECT_NE(cloud->warnings()[0].find("holds 2 more point records"), std::string::npos) << cloud->warnings()[0];
}

TEST(LasFile, TheSameReturnsInLas11AndLas12ReadIdentically) {
  if (las_sample("simple.las").empty()) GTEST_SKIP() << "../shared/sample_data is absent";
  const auto a = read_all(LasReader::open_file(las_sample("simple.las")));
  const auto b = read_all(LasReader::open_file(las_sample("simple1_1.las")));
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_DOUBLE_EQ(a[i].x, b[i].x);
    EXPECT_DOUBLE_EQ(a[i].z, b[i].z);
    EXPECT_EQ(a[i].classification, b[i].classification);
  }
}

TEST(LasFile, CrsFromGeoTiffKeysAndFromWkt) {
  if (las_sample("simple.las").empty()) GTEST_SKIP() << "../shared/sample_data is absent";
  EXPECT_NE(LasReader::open_file(las_sample("autzen_geo_proj.las")).header().crs_wkt.find("PROJCS"), std::string::npos);
  EXPECT_FALSE(LasReader::open_file(las_sample("file_with_both_wkt_and_geotiff_vlrs.las")).header().crs_wkt.empty());
  // VerticalUnitsGeoKey where the keys give one: US survey feet, metres; none in the Autzen sample.
  EXPECT_EQ(LasReader::open_file(las_sample("file_with_both_wkt_and_geotiff_vlrs.las")).header().z_unit_metres,
            1200.0 / 3937.0);
  EXPECT_EQ(LasReader::open_file(las_sample("simple1_4.las")).header().z_unit_metres, 1.0);
  EXPECT_EQ(LasReader::open_file(las_sample("autzen_geo_proj.las")).header().z_unit_metres, 0.0);
}

// A LAS 1.2 file whose GeoTIFF keys name a vertical CRS (VerticalCSTypeGeoKey) and no unit: the
// z unit is that CRS's. Made from a written file by turning its GTRasterTypeGeoKey entry (which the
// reader ignores) into VerticalCSTypeGeoKey = 6360, NAVD88 height in US survey feet.
TEST(LasFile, AVerticalCrsInTheGeoTiffKeysGivesTheHeightsUnit) {
  const std::string dir = test::temp_dir("las-vertical");
  LasWriteOptions o;
  o.crs_wkt = test::wkt_of("EPSG:32633");
  o.offset[0] = 500000, o.offset[1] = 6400000;
  write_las(dir + "/utm.las", {{500000.5, 6400000.5, 10.0, 0, 1, 1, 2}}, o);
  std::ifstream in(dir + "/utm.las", std::ios::binary);
  std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(LasReader::open_memory(bytes.data(), bytes.size()).header().z_unit_metres, 0.0);
  const std::uint8_t raster_type[8] = {0x01, 0x04, 0, 0, 1, 0, 1, 0};  // 1025, 0, 1, 1 (little-endian)
  const auto at = std::search(bytes.begin(), bytes.end(), std::begin(raster_type), std::end(raster_type));
  ASSERT_NE(at, bytes.end());
  const std::uint8_t vertical_crs[8] = {0x00, 0x10, 0, 0, 1, 0, 0xd8, 0x18};  // 4096, 0, 1, 6360
  std::copy(std::begin(vertical_crs), std::end(vertical_crs), at);
  EXPECT_NEAR(LasReader::open_memory(bytes.data(), bytes.size()).header().z_unit_metres, 1200.0 / 3937.0, 1e-12);
}

TEST(LasFile, LazIsRefusedWithTheWayToDecompressIt) {
  if (las_sample("simple.laz").empty()) GTEST_SKIP() << "../shared/sample_data is absent";
  try {
    LasReader::open_file(las_sample("simple.laz"));
    FAIL() << "LAZ accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("laszip"), std::string::npos) << e.what();
  }
}

std::vector<LasPoint> synthetic_points() {
  std::vector<LasPoint> pts;
  for (int i = 0; i < 50; ++i) {
    pts.push_back({500000.0 + i * 0.25, 6400000.0 - i * 0.5, 100.0 + i * 0.125, static_cast<std::uint16_t>(i * 7),
                   static_cast<std::uint8_t>(1 + i % 3), 3, static_cast<std::uint8_t>(i % 2 ? 2 : 6)});
  }
  return pts;
}

TEST(LasFile, EveryPointFormatAndVersionRoundTrips) {
  const std::filesystem::path dir = skyview::test::temp_dir("las");
  const auto pts = synthetic_points();
  for (int format = 0; format <= 10; ++format) {
    for (int minor : {2, 4}) {
      if (format > 5 && minor < 4) continue;
      LasWriteOptions o;
      o.point_format = format;
      o.version_minor = minor;
      o.offset[0] = 500000;
      o.offset[1] = 6400000;
      const std::string path = (dir / ("f" + std::to_string(format) + "v" + std::to_string(minor) + ".las")).string();
      write_las(path, pts, o);
      const auto back = read_all(LasReader::open_file(path), 7);
      ASSERT_EQ(back.size(), pts.size());
      for (std::size_t i = 0; i < pts.size(); ++i) {
        ASSERT_NEAR(back[i].x, pts[i].x, 5e-4) << format;
        ASSERT_NEAR(back[i].y, pts[i].y, 5e-4) << format;
        ASSERT_NEAR(back[i].z, pts[i].z, 5e-4) << format;
        ASSERT_EQ(back[i].classification, pts[i].classification) << format;
        ASSERT_EQ(back[i].return_number, pts[i].return_number) << format;
        ASSERT_EQ(back[i].number_of_returns, pts[i].number_of_returns) << format;
        ASSERT_EQ(back[i].intensity, pts[i].intensity) << format;
      }
    }
  }
}

// The CRS as each version's readers look for it: LAS 1.2 as GeoTIFF keys (the model type and the
// projected or geographic code) and WKT; LAS 1.4 as WKT only, with the global encoding's WKT bit. A
// CRS given without its code gets the one GDAL identifies; one that has none travels as WKT alone.
// Every file reads back as the CRS written, and a LAS 1.2 file reads back from its keys alone.
TEST(LasFile, CrsIsWrittenAsEachVersionsReadersExpectIt) {
  const std::filesystem::path dir = skyview::test::temp_dir("las");
  struct Record {
    int id;
    std::size_t at;  // of the record's header in the file
    std::vector<std::uint8_t> body;
  };
  struct Written {
    std::string bytes;
    std::uint16_t global_encoding = 0;
    std::vector<Record> records;
    const Record* find(int id) const {
      for (const Record& r : records) {
        if (r.id == id) return &r;
      }
      return nullptr;
    }
  };
  auto u16 = [](const std::string& b, std::size_t at) {
    return static_cast<int>(std::uint8_t(b[at]) | std::uint8_t(b[at + 1]) << 8);
  };
  auto u32 = [&](const std::string& b, std::size_t at) {
    return static_cast<std::size_t>(u16(b, at)) | static_cast<std::size_t>(u16(b, at + 2)) << 16;
  };
  auto written = [&](const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    Written w;
    w.bytes.assign((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string& b = w.bytes;
    w.global_encoding = static_cast<std::uint16_t>(u16(b, 6));
    std::size_t at = static_cast<std::size_t>(u16(b, 94));
    for (std::size_t v = 0; v < u32(b, 100); ++v) {
      const std::size_t length = static_cast<std::size_t>(u16(b, at + 20));
      EXPECT_EQ(b.substr(at, 18), std::string("\0\0LASF_Projection\0", 18));
      w.records.push_back({u16(b, at + 18),
                           at,
                           {b.begin() + static_cast<std::ptrdiff_t>(at + 54),
                            b.begin() + static_cast<std::ptrdiff_t>(at + 54 + length)}});
      at += 54 + length;
    }
    EXPECT_EQ(at, u32(b, 96)) << "the points start after the records";
    return w;
  };
  auto same_crs = [](const std::string& a, const std::string& b) {
    OGRSpatialReference x, y;
    return x.importFromWkt(a.c_str()) == OGRERR_NONE && y.importFromWkt(b.c_str()) == OGRERR_NONE && x.IsSame(&y);
  };
  struct Case {
    const char* name;
    std::string wkt;
    int model, key, code;  // expected in the 1.2 keys; code 0: no keys
  };
  const Case cases[] = {
      {"utm", skyview::test::wkt_of("EPSG:32633"), 1, 3072, 32633},
      {"utm_from_proj", skyview::test::wkt_of("+proj=utm +zone=33 +datum=WGS84 +units=m +no_defs"), 1, 3072, 32633},
      {"degrees", skyview::test::wkt_of("EPSG:4326"), 2, 2048, 4326},
      {"custom", skyview::test::wkt_of("+proj=tmerc +lon_0=14.5 +k=0.9999 +x_0=400000 +ellps=GRS80 +units=m"), 0, 0,
       0}};
  for (const Case& c : cases) {
    for (int minor : {2, 4}) {
      LasWriteOptions o;
      o.version_minor = minor;
      o.offset[0] = 500000, o.offset[1] = 6400000;
      o.crs_wkt = c.wkt;
      const std::string path = (dir / (std::string(c.name) + "_v" + std::to_string(minor) + ".las")).string();
      write_las(path, synthetic_points(), o);
      const Written w = written(path);
      EXPECT_EQ(w.global_encoding & 0x10, minor == 4 ? 0x10 : 0) << path;
      const bool keys = minor == 2 && c.code > 0;
      ASSERT_EQ(w.records.size(), keys ? 2u : 1u) << path;
      const Record* wkt = w.find(2112);
      ASSERT_TRUE(wkt) << path;
      ASSERT_EQ(wkt->body.back(), 0) << "the WKT ends in a NUL";
      EXPECT_TRUE(same_crs(reinterpret_cast<const char*>(wkt->body.data()), c.wkt)) << path;
      EXPECT_TRUE(same_crs(LasReader::open_file(path).header().crs_wkt, c.wkt)) << path;
      if (!keys) continue;
      const Record* geokeys = w.find(34735);
      ASSERT_TRUE(geokeys) << path;
      const std::vector<std::uint16_t> expected = {1,
                                                   1,
                                                   0,
                                                   3,
                                                   1024,
                                                   0,
                                                   1,
                                                   std::uint16_t(c.model),
                                                   1025,
                                                   0,
                                                   1,
                                                   1,
                                                   std::uint16_t(c.key),
                                                   0,
                                                   1,
                                                   std::uint16_t(c.code)};
      std::vector<std::uint16_t> got(geokeys->body.size() / 2);
      std::memcpy(got.data(), geokeys->body.data(), got.size() * 2);
      EXPECT_EQ(got, expected) << path;
      // The same file without its WKT record: the reader takes the CRS from the keys.
      std::string keys_only = w.bytes.substr(0, wkt->at) + w.bytes.substr(wkt->at + 54 + wkt->body.size());
      const std::uint32_t records = 1, points_at = static_cast<std::uint32_t>(u32(w.bytes, 96) - 54 - wkt->body.size());
      std::memcpy(keys_only.data() + 100, &records, 4);
      std::memcpy(keys_only.data() + 96, &points_at, 4);
      const std::string keys_path = (dir / (std::string(c.name) + "_keys_only.las")).string();
      std::ofstream(keys_path, std::ios::binary) << keys_only;
      EXPECT_TRUE(same_crs(LasReader::open_file(keys_path).header().crs_wkt,
                           skyview::test::wkt_of(("EPSG:" + std::to_string(c.code)).c_str())))
          << keys_path;
    }
  }
}

TEST(LasFile, ScaleAndOffsetExtremes) {
  const std::filesystem::path dir = skyview::test::temp_dir("las");
  std::vector<LasPoint> pts = {{-1.0e6, 2.0e7, -420.0005, 0, 1, 1, 2}, {1.0e6, -2.0e7, 8848.123, 0, 1, 1, 2}};
  LasWriteOptions o;
  o.scale[0] = o.scale[1] = 0.01;
  o.scale[2] = 1e-4;
  o.offset[2] = 4000;
  write_las((dir / "extreme.las").string(), pts, o);
  const auto back = read_all(LasReader::open_file((dir / "extreme.las").string()));
  EXPECT_NEAR(back[0].x, -1.0e6, 0.005);
  EXPECT_NEAR(back[1].y, -2.0e7, 0.005);
  EXPECT_NEAR(back[0].z, -420.0005, 1e-4);
  EXPECT_NEAR(back[1].z, 8848.123, 1e-4);
  pts[0].x = 1e9;  // beyond 2^31 * 0.01
  EXPECT_THROW(write_las((dir / "overflow.las").string(), pts, o), Error);
}

TEST(LasFile, TruncatedAndCorruptFilesGiveClearErrors) {
  const std::filesystem::path dir = skyview::test::temp_dir("las");
  const std::string path = (dir / "good.las").string();
  LasWriteOptions o;
  o.offset[0] = 500000;
  o.offset[1] = 6400000;
  write_las(path, synthetic_points(), o);
  std::ifstream in(path, std::ios::binary);
  std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto expect_error = [&](std::vector<std::uint8_t> b, const std::string& fragment) {
    try {
      LasReader::open_memory(b.data(), b.size(), "x.las");
      FAIL() << "accepted: " << fragment;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  expect_error(std::vector<std::uint8_t>(bytes.begin(), bytes.end() - 10), "truncated");
  expect_error(std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + 100), "shorter than any LAS header");
  auto bad = bytes;
  bad[0] = 'X';
  expect_error(bad, "no LASF signature");
  bad = bytes;
  bad[104] = 11;
  expect_error(bad, "point data format 11");
  bad = bytes;
  bad[105] = 5;
  bad[106] = 0;
  expect_error(bad, "record length");
  bad = bytes;
  bad[94] = 100;
  bad[95] = 0;
  expect_error(bad, "header size");
  bad = bytes;
  bad[131] = bad[132] = bad[133] = bad[134] = bad[135] = bad[136] = bad[137] = bad[138] = 0;
  expect_error(bad, "scale");
  bad = bytes;
  bad[25] = 9;
  expect_error(bad, "version 1.9");
  EXPECT_EQ(LasReader::open_memory(bytes.data(), bytes.size()).header().point_count, 50u);
  write_las((dir / "empty.las").string(), {}, {});
  EXPECT_EQ(LasReader::open_file((dir / "empty.las").string()).header().point_count, 0u);
}

}  // namespace
