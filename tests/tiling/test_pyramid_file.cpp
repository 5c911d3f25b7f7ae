// The far field's pyramid on disk (skyview/tiling/pyramid_file.h): it comes back bit for bit, a
// damaged or foreign file is a one-line error, and a --tiles-dir run keeps it beside its tiles so
// that a rerun reads it instead of the raster (and builds it again where it is damaged).
#include <filesystem>
#include <fstream>
#include <iterator>

#include <nlohmann/json.hpp>

#include "skyview/core/error.h"
#include "skyview/raster/output_files.h"
#include "skyview/tiling/far_field.h"
#include "skyview/tiling/pyramid_file.h"
#include "tiling/tiling_test_support.h"

using namespace skyview;
using namespace skyview::test;

namespace {

// A pyramid with nodata over a city (6 x 6 NaN cells: a level-1 cell, whose block grown by one
// cell they cover), its relief and range not trivial.
OverviewPyramid city_pyramid(bool minima = false) {
  Terrain t = rasterize(synthetic_city(5), 67, 53, local_grid(67, 53, 1.0));
  for (int r = 10; r < 16; ++r)
    for (int c = 40; c < 46; ++c) t.heights(c, r) = std::numeric_limits<float>::quiet_NaN();
  return OverviewPyramid(t, 1, minima);
}

std::string bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The message of the Error decoding `bytes` throws ("" where none is thrown).
std::string refusal(const std::string& bytes) {
  try {
    decode_pyramid(bytes, "p.bin");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(PyramidFile, RoundTripsBitForBit) {
  const OverviewPyramid p = city_pyramid();
  ASSERT_EQ(p.first_level(), 1);
  ASSERT_EQ(p.last_level(), 7);  // 34 x 27 cells, then halved to one cell
  const std::string bytes = encode_pyramid(p.levels(), "the city");
  std::string source;
  const OverviewPyramid q(decode_pyramid(bytes, "p.bin", &source));
  EXPECT_EQ(source, "the city");
  ASSERT_EQ(q.first_level(), p.first_level());
  ASSERT_EQ(q.last_level(), p.last_level());
  EXPECT_EQ(q.lowest(), p.lowest());
  EXPECT_EQ(q.highest(), p.highest());
  EXPECT_EQ(q.levels().width, 67);
  EXPECT_EQ(q.levels().height, 53);
  int nodata = 0;
  for (int l = p.first_level(); l <= p.last_level(); ++l) {
    EXPECT_EQ(q.relief(l), p.relief(l));
    const Grid<float>&a = p.level(l), &b = q.level(l);
    ASSERT_EQ(b.width(), a.width());
    ASSERT_EQ(b.height(), a.height());
    for (std::size_t i = 0; i < a.size(); ++i) {
      nodata += std::isnan(a.data()[i]);
      ASSERT_EQ(std::memcmp(&a.data()[i], &b.data()[i], sizeof(float)), 0) << "level " << l << " cell " << i;
    }
  }
  EXPECT_GT(nodata, 0);  // the NaN block's cells of level 1 came back as NaN
  // Through a file, and what a manifest records of it: the checksum the file ends with.
  const std::string path = temp_dir("pyramid-file") + "/p.bin";
  write_output_file(path, bytes, false);
  EXPECT_EQ(encode_pyramid(OverviewPyramid(read_pyramid_file(path)).levels(), "the city"), bytes);
  char tail[17];
  std::uint64_t sum = 0;
  std::memcpy(&sum, bytes.data() + bytes.size() - 8, 8);
  std::snprintf(tail, sizeof tail, "%016llx", static_cast<unsigned long long>(sum));
  EXPECT_EQ(pyramid_checksum(bytes), tail);
}

// The minima (kept for negative openness) come back too, after the maxima, and a file without them
// has none.
TEST(PyramidFile, MinimaRoundTripWhereKept) {
  const OverviewPyramid p = city_pyramid(true);
  ASSERT_TRUE(p.has_minima());
  const std::string bytes = encode_pyramid(p.levels(), "the city");
  EXPECT_GT(bytes.size(), encode_pyramid(city_pyramid().levels(), "the city").size());
  const OverviewPyramid q(decode_pyramid(bytes, "p.bin"));
  ASSERT_TRUE(q.has_minima());
  int below = 0;
  for (int l = p.first_level(); l <= p.last_level(); ++l) {
    const Grid<float>&a = p.minima(l), &b = q.minima(l);
    ASSERT_EQ(b.width(), a.width());
    ASSERT_EQ(b.height(), a.height());
    for (std::size_t i = 0; i < a.size(); ++i) {
      ASSERT_EQ(std::memcmp(&a.data()[i], &b.data()[i], sizeof(float)), 0) << "level " << l << " cell " << i;
      below += a.data()[i] < p.level(l).data()[i];
    }
  }
  EXPECT_GT(below, 0);  // minima, not a second copy of the maxima
  EXPECT_FALSE(OverviewPyramid(decode_pyramid(encode_pyramid(city_pyramid().levels(), ""), "p.bin")).has_minima());
  // A flag this version does not know (bytes 28..31, after the level count).
  std::string unknown = bytes;
  unknown[28] = 4;
  EXPECT_NE(refusal(unknown).find("checksum"), std::string::npos);  // damaged: the checksum says so first
}

TEST(PyramidFile, DamagedTruncatedAndForeignFilesAreOneLineErrors) {
  const std::string good = encode_pyramid(city_pyramid().levels(), "the city");
  ASSERT_EQ(refusal(good), "");
  std::string flipped = good;
  flipped[good.size() / 2] ^= 0x10;  // a bit of a level's height
  EXPECT_EQ(refusal(flipped),
            "'p.bin' is not a skyview overview pyramid (its checksum does not match: the file is damaged or "
            "incomplete)");
  EXPECT_NE(refusal(good.substr(0, good.size() - 100)).find("checksum does not match"), std::string::npos);
  EXPECT_NE(refusal(good.substr(0, 5)).find("it ends before its magic"), std::string::npos);
  EXPECT_NE(refusal("GIF89a this is no pyramid at all").find("does not start with SKYVPYRM"), std::string::npos);
  std::string future = good;
  future[8] = 3;  // version 3
  EXPECT_NE(refusal(future).find("format version 3, this skyview reads 2"), std::string::npos);
  EXPECT_NE(refusal("").find("ends before"), std::string::npos);
  // A checksum made right over sizes that are wrong: the sizes are checked too.
  PyramidLevels lying = city_pyramid().levels();
  lying.width = 200;
  EXPECT_NE(refusal(encode_pyramid(lying, "")).find("levels where its sizes make"), std::string::npos);
  lying = city_pyramid().levels();
  lying.max.back() = Grid<float>(2, 1);
  EXPECT_NE(refusal(encode_pyramid(lying, "")).find("bytes of levels and checksum"), std::string::npos);
  try {
    read_pyramid_file("/nonexistent/far_field_pyramid.bin");
    ADD_FAILURE() << "no error for a missing file";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "cannot read the overview pyramid '/nonexistent/far_field_pyramid.bin'");
  }
}

// A tiled run at unlimited radius into a tiles folder: the pyramid is kept there with its record in
// the manifest, a rerun reads it (the raster is not read whole again) and one damaged is built again
// with a warning; the results never change.
TEST(PyramidFile, TilesDirKeepsThePyramidAndARerunReusesIt) {
  const std::string dir = temp_dir("pyramid-tiles-dir");
  const std::string dsm = write_small_city(dir, 240, 200);
  const std::string tiles = dir + "/tiles", vrt = dir + "/out.vrt", pyramid = tiles + "/far_field_pyramid.bin";
  const std::string run =
      "svf " + dsm + " " + vrt + " --directions 8 --tile-size 64 --far-field-error 0.3 --tiles-dir " + tiles;
  RunResult r = run_skyview(run, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_TRUE(std::filesystem::exists(pyramid));
  EXPECT_EQ(metadata_item(vrt, "FAR_FIELD_PYRAMID_REUSED"), "");
  const std::string bytes = bytes_of(pyramid);
  std::string source;
  const OverviewPyramid kept(read_pyramid_file(pyramid, &source));
  EXPECT_NE(source.find(dsm), std::string::npos);  // the input it was built from
  EXPECT_EQ(std::to_string(kept.bytes()), metadata_item(vrt, "FAR_FIELD_PYRAMID_BYTES"));
  {
    std::ifstream in(tiles + "/manifest.json");
    const nlohmann::json manifest = nlohmann::json::parse(in);
    const nlohmann::json& record = manifest.at("files").at("far_field_pyramid");
    EXPECT_EQ(record.at("file"), "far_field_pyramid.bin");
    EXPECT_EQ(record.at("checksum"), pyramid_checksum(bytes));
  }
  std::filesystem::copy_file(vrt, dir + "/first.vrt");
  const auto kept_time = std::filesystem::last_write_time(pyramid);

  // A lost tile and no mosaic: the rerun reads the pyramid, not the raster, and gives the same bits.
  std::filesystem::remove(tiles + "/tile_1_1.tif");
  std::filesystem::remove(vrt);
  r = run_skyview(run, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(metadata_item(vrt, "FAR_FIELD_PYRAMID_REUSED"), pyramid);
  EXPECT_EQ(metadata_item(vrt, "TILES_REUSED"), "15");  // of 4 x 4
  EXPECT_EQ(std::filesystem::last_write_time(pyramid), kept_time);
  EXPECT_TRUE(same_bands(vrt, dir + "/first.vrt"));

  // A damaged pyramid: built again with a warning, the same bits again.
  {
    std::fstream damaged(pyramid, std::ios::in | std::ios::out | std::ios::binary);
    damaged.seekp(static_cast<std::streamoff>(bytes.size() / 2));
    damaged.write("damage", 6);
  }
  std::filesystem::remove(tiles + "/tile_2_2.tif");
  std::filesystem::remove(vrt);
  r = run_skyview(run, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("Warning: '" + pyramid +
                       "' is not a skyview overview pyramid (its checksum does not match: the file is damaged or "
                       "incomplete); building it again from the raster"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(metadata_item(vrt, "FAR_FIELD_PYRAMID_REUSED"), "");
  EXPECT_EQ(bytes_of(pyramid), bytes);  // written again, whole
  EXPECT_TRUE(same_bands(vrt, dir + "/first.vrt"));
}

}  // namespace
