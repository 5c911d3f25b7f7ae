// -of COG: a cloud-optimised GeoTIFF with overviews, staged on disk (not in memory) and copied by
// GDAL's COG driver, holding the same values as a GeoTIFF, whole or in tiles.
#include <filesystem>

#include "tiling/tiling_test_support.h"

using namespace skyview;
using namespace skyview::test;

namespace {

TEST(CogOutput, OpensAsCogWithOverviewsAndTheSameValues) {
  const std::string dir = temp_dir("cog");
  const std::string dsm = write_small_city(dir);
  const std::string common = " --radius 9 --directions 8";
  ASSERT_EQ(run_skyview("svf " + dsm + " " + dir + "/plain.tif" + common, dir).exit_code, 0);
  // Blocks of 16 cells, so that a 67 x 53 raster gets overviews (GDAL makes them down to one block).
  for (const std::string tiles : {"", " --tile-size 22"}) {
    const std::string out = dir + "/cog" + (tiles.empty() ? "" : "_tiled") + ".tif";
    const RunResult r = run_skyview("svf " + dsm + " " + out + common + tiles + " -of COG -co BLOCKSIZE=16", dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    GDALDataset* ds = GDALDataset::Open(out.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY);
    ASSERT_NE(ds, nullptr);
    const char* layout = ds->GetMetadataItem("LAYOUT", "IMAGE_STRUCTURE");
    EXPECT_STREQ(layout ? layout : "", "COG") << tiles;
    EXPECT_GE(ds->GetRasterBand(1)->GetOverviewCount(), 2) << tiles;
    const char* source = ds->GetMetadataItem("SOURCE");
    EXPECT_STREQ(source ? source : "", dsm.c_str());
    GDALClose(ds);
    EXPECT_TRUE(same_bands(out, dir + "/plain.tif")) << tiles;
  }
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    EXPECT_EQ(entry.path().filename().string().find("skyview-tmp"), std::string::npos) << entry.path();
}

TEST(CogOutput, HorizonBandsKeepTheirNames) {
  const std::string dir = temp_dir("cog-horizon");
  const std::string dsm = write_small_city(dir);
  const std::string common = " --radius 9 --directions 4";
  ASSERT_EQ(run_skyview("horizon " + dsm + " " + dir + "/plain.tif" + common, dir).exit_code, 0);
  const RunResult r = run_skyview("horizon " + dsm + " " + dir + "/cog.tif" + common + " -of COG", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(same_bands(dir + "/cog.tif", dir + "/plain.tif"));
}

}  // namespace
