// A sky map file written and read back: the same bands, and the request that rebuilds its steps.
#include <gtest/gtest.h>

#include <filesystem>

#include "skyview/core/error.h"
#include "skyview/sky/skymap_file.h"
#include "skyview/synthetic/synthetic.h"
#include "temp_dir.h"

namespace skyview {
namespace {

TEST(SkymapFile, RoundTripKeepsBandsAndTheRequest) {
  const std::filesystem::path dir = test::temp_dir("skymap-file");
  SkyRequest request;
  request.latitude = 40.0;
  request.longitude = 20.0;
  request.tz = "Europe/Athens";
  request.from = "2024-06-01T00:00";
  request.to = "2024-06-03T00:00";
  request.step = "1h";
  request.turbidity = 3.0;
  PreparedSky sky = prepare_sky(request);
  const ExposureMap map = make_exposure_map(sky, 32);
  WriteOptions wo;
  wo.metadata = sky.metadata;
  const std::string path = (dir / "sky.tif").string();
  write_skymap(path, map, wo);

  const SkymapFile file = read_skymap(path);
  ASSERT_EQ(file.map.width(), 32);
  EXPECT_EQ(file.map.band(ExposureBand::direct), map.band(ExposureBand::direct));
  EXPECT_EQ(file.map.band(ExposureBand::diffuse), map.band(ExposureBand::diffuse));
  EXPECT_EQ(file.latitude_deg, 40.0);
  EXPECT_EQ(file.request.sky, "preetham");
  EXPECT_EQ(file.request.turbidity, 3.0);
  EXPECT_EQ(file.request.from, "2024-05-31T21:00:00Z");  // the instants, not the local text
  const PreparedSky again = prepare_sky(file.request);
  ASSERT_EQ(again.steps.size(), sky.steps.size());
  EXPECT_EQ(again.steps.back().conditions.sun_azimuth, sky.steps.back().conditions.sun_azimuth);
}

TEST(SkymapFile, OtherRastersAreRefusedByName) {
  const std::filesystem::path dir = test::temp_dir("skymap-file");
  const Terrain t = rasterize(tilted_plane(0.1, 0.0), 9, 9, local_grid(9, 9, 1.0));
  const std::string dsm = (dir / "dsm.tif").string();
  write_terrain(dsm, t, WriteOptions{});
  try {
    read_skymap(dsm);
    FAIL() << "a DSM read as a sky map";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("is not a sky map written by skyview skymap"), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_skymap((dir / "missing.tif").string()), Error);
}

}  // namespace
}  // namespace skyview
