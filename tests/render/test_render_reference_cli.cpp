// skyview render --reference with --skymap: the exposure reference's bands and their difference
// image, and the open ground's reference against the map's horizontal total.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "core/cli_run.h"
#include "render_test_support.h"
#include "skyview/raster/raster_read.h"
#include "skyview/sky/skymap_file.h"
#include "temp_dir.h"

using namespace skyview;
using namespace skyview::test;

TEST(RenderCli, ExposureReferenceBandsAndDifferenceImage) {
  const std::string dir = temp_dir("render-reference-cli");
  Scene s;
  s.meshes.push_back(ground_mesh(200));
  s.meshes.push_back(box_mesh("house", {-5, 10, 0}, {5, 20, 12}));
  write_obj(s, dir + "/house.obj");
  const std::string map = dir + "/sky.tif";
  ASSERT_EQ(run_skyview("skymap " + map +
                            " --no-preview --lat 52.5 --lon 13.4 --from 2024-06-21T00:00Z --to 2024-06-22T00:00Z "
                            "--step 1h --size 64",
                        dir)
                .exit_code,
            0);
  const std::string out = dir + "/view.tif";
  const RunResult r = run_skyview("render " + dir + "/house.obj " + out +
                                      " --camera 0,-10,40 --look-at 0,5,0 --size 24x18 --directions 8 --samples 8 "
                                      "--skymap " +
                                      map + " --reference --reference-rays 512 --diff-preview " + dir + "/diff.png",
                                  dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir + "/diff.png"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/diff_exposure.png"));
  // svf, svf_large, svf_fine, exposure x3, depth, normal x3, svf_reference x2, exposure_reference x2.
  const RasterBand ref = read_band(out, 13), se = read_band(out, 14), exposure = read_band(out, 4);
  EXPECT_EQ(ref.description, "exposure_reference");
  EXPECT_EQ(se.description, "exposure_reference_stderr");
  EXPECT_EQ(ref.unit, "kWh m-2");
  // The bottom row sees open ground in front of the house, well away from it: the map's
  // horizontal total within four standard errors and the map's cell discretisation.
  const SkymapFile sky = read_skymap(map);
  const double total = sky.map.irradiation(ExposureBand::global, {0, 0, 1}) / 1000;
  for (int col : {2, 12, 21}) {
    const double e = ref.values(col, 17), sigma = se.values(col, 17);
    ASSERT_FALSE(std::isnan(e));
    EXPECT_NEAR(e, total, 4 * sigma + 0.01 * total) << "column " << col;
    EXPECT_NEAR(exposure.values(col, 17), e, 0.05 * total + 4 * sigma) << "column " << col;
  }
}
