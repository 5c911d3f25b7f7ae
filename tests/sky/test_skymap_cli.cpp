// `skyview skymap` from the command line: a small run writes both bands and the preview; bad
// input gives one error line and a non-zero exit.
#include <gdal_priv.h>
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "sky_test_support.h"
#include "skyview/raster/raster_io.h"
#include "temp_dir.h"

namespace {

struct Result {
  int code;
  std::string output;
};

Result run(const std::string& args) {
  const std::string cmd = std::string(SKYVIEW_EXE) + " skymap " + args + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  std::string out;
  std::array<char, 512> buf;
  while (pipe && fgets(buf.data(), buf.size(), pipe)) out += buf.data();
  const int status = pipe ? pclose(pipe) : -1;
  return {WEXITSTATUS(status), out};
}

TEST(SkymapCli, WritesBandsAndPreview) {
  const std::filesystem::path dir = skyview::test::temp_dir("skymap-cli");
  const std::string out = (dir / "map.tif").string();
  const Result r = run(out + " --lat 45 --lon 7 --from 2024-06-21T00:00Z --to 2024-06-22T00:00Z --size 64 -q");
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(out));
  EXPECT_TRUE(std::filesystem::exists(dir / "map.png"));
  EXPECT_EQ(run("--help").code, 0);
  std::filesystem::remove_all(dir);
}

// Hošek–Wilkie's exposures cover its bands, 320-720 nm: the outputs and the summary line say so.
TEST(SkymapCli, HosekWilkieExposuresSayTheirSpectrum) {
  const std::filesystem::path dir = skyview::test::temp_dir("skymap-cli");
  const std::string out = (dir / "hosek.tif").string();
  const Result r = run(out + " --lat 30 --lon 0 --from 2023-06-21T00:00Z --to 2023-06-22T00:00Z --sky hosek --size 32");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("320-720 nm only"), std::string::npos) << r.output;
  skyview::init_gdal();
  GDALDatasetUniquePtr ds(GDALDataset::Open(out.c_str(), GDAL_OF_RASTER));
  ASSERT_TRUE(ds);
  const char* spectrum = ds->GetMetadataItem("SPECTRUM");
  ASSERT_NE(spectrum, nullptr);
  EXPECT_NE(std::string(spectrum).find("320-720 nm"), std::string::npos) << spectrum;
  std::filesystem::remove_all(dir);
}

// Options the chosen sky does not use are refused rather than ignored; a site that overrides the
// EPW's is said.
TEST(SkymapCli, OptionsTheSkyDoesNotUseAreRefused) {
  const std::string epw = skyview::sky_test::shared_data("weather/chicago.epw");
  struct Case {
    std::string args, message;
  };
  std::vector<Case> cases{
      {"--sky hosek --luminous-efficacy 100 --lat 1 --lon 1 --from 2024-01-01T00:00Z --to 2024-01-02T00:00Z",
       "--luminous-efficacy applies only to --sky preetham"},
      {"--albedo 0.5 --lat 1 --lon 1 --from 2024-01-01T00:00Z --to 2024-01-02T00:00Z", "--albedo applies only to"},
      {"--lat 1 --lon 1 --from 2024-01-01T00:00Z --to 2024-01-02T00:00Z --preview x.jpg",
       "--preview 'x.jpg' must end in .png"},
      // One step would stand for the whole day (30.7 kWh/m2 where 1-minute steps give 11.0).
      {"--lat 30 --lon 0 --from 2023-06-21T00:00Z --to 2023-06-22T00:00Z --step 1d",
       "--step 1d is not shorter than the period"}};
  if (!epw.empty()) {
    cases.push_back({"--sky perez-epw --epw " + epw + " --step 10m", "--step applies only to analytic skies"});
    cases.push_back({"--sky perez-epw --epw " + epw + " --turbidity 3", "--turbidity applies only to"});
  }
  for (const Case& c : cases) {
    const bool preview = c.args.find("--preview") != std::string::npos;
    const Result r = run("x.tif " + std::string(preview ? "" : "--no-preview ") + c.args);
    EXPECT_NE(r.code, 0) << c.args;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  }
  if (epw.empty()) GTEST_SKIP() << "../shared/data/weather/chicago.epw not found";
  const std::filesystem::path dir = skyview::test::temp_dir("skymap-site");
  const Result moved = run((dir / "m.tif").string() + " --no-preview --size 16 --sky perez-epw --epw " + epw +
                           " --lat 45 --lon 7 --from 2024-06-21T00:00Z --to 2024-06-22T00:00Z");
  EXPECT_EQ(moved.code, 0) << moved.output;
  EXPECT_NE(
      moved.output.find("Warning: the sun is placed for --lat 45 --lon 7, not for the EPW's site (41.98, -87.92)"),
      std::string::npos)
      << moved.output;
  std::filesystem::remove_all(dir);
}

// The period is recorded as given and as UTC instants, with the zone that resolved it: FROM alone
// read 2024-06-01T00:00 with nothing to say which midnight.
TEST(SkymapCli, ThePeriodIsRecordedInUtc) {
  const std::filesystem::path dir = skyview::test::temp_dir("skymap-utc");
  const std::string out = (dir / "tz.tif").string();
  const Result r = run(out +
                       " --no-preview --size 16 --lat 52 --lon 13 --tz Europe/Berlin --from 2024-06-01T00:00 "
                       "--to 2024-06-02T00:00");
  ASSERT_EQ(r.code, 0) << r.output;
  skyview::init_gdal();
  GDALDatasetUniquePtr ds(GDALDataset::Open(out.c_str(), GDAL_OF_RASTER));
  ASSERT_TRUE(ds);
  EXPECT_STREQ(ds->GetMetadataItem("FROM"), "2024-06-01T00:00");
  EXPECT_STREQ(ds->GetMetadataItem("FROM_UTC"), "2024-05-31T22:00:00Z");
  EXPECT_STREQ(ds->GetMetadataItem("TO_UTC"), "2024-06-01T22:00:00Z");
  EXPECT_STREQ(ds->GetMetadataItem("TIME_ZONE"), "Europe/Berlin");
  ds.reset();
  std::filesystem::remove_all(dir);
}

// A sky that delivers more than arrives outside the atmosphere is said: Preetham's does at
// turbidity 10 with the sun at the zenith, not at 2.5.
TEST(SkymapCli, ExposureAboveTheExtraterrestrialIsSaid) {
  const std::filesystem::path dir = skyview::test::temp_dir("skymap-energy");
  const std::string noon = " --no-preview --size 32 --lat 0 --lon 0 --from 2024-03-20T11:37Z --to 2024-03-20T12:37Z";
  const Result clear = run((dir / "a.tif").string() + noon + " --turbidity 2.5");
  EXPECT_EQ(clear.code, 0) << clear.output;
  EXPECT_EQ(clear.output.find("Warning"), std::string::npos) << clear.output;
  const Result hazy = run((dir / "b.tif").string() + noon + " --turbidity 10");
  EXPECT_EQ(hazy.code, 0) << hazy.output;
  EXPECT_NE(hazy.output.find("outside the atmosphere (Preetham's diffuse part has no energy balance"),
            std::string::npos)
      << hazy.output;
  std::filesystem::remove_all(dir);
}

TEST(SkymapCli, BadInputIsOneErrorLine) {
  for (const char* args :
       {"x.tif --lat 95 --lon 0 --from 2024-01-01T00:00Z --to 2024-01-02T00:00Z", "x.tif --sky perez-epw",
        "x.tif --lat 1 --lon 1 --from 2024-01-02T00:00Z --to 2024-01-01T00:00Z",
        "x.tif --lat 1 --lon 1 --sky sunny --from 2024-01-01T00:00Z --to 2024-01-02T00:00Z",
        "x.tif --sky perez-epw --epw /nonexistent.epw"}) {
    const Result r = run(std::string("--no-preview ") + args);
    EXPECT_NE(r.code, 0) << args;
    EXPECT_EQ(r.output.find("error:"), r.output.rfind("error:")) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  }
}

}  // namespace
