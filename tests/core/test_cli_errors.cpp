// Bad input to the executable: one clear line on stderr and a non-zero exit, never a crash.
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <utility>

#include <gdal_priv.h>

#include "cli_run.h"
#include "skyview/sky_view/error_stats.h"
#include "skyview/dsm/las_file.h"
#include "skyview/sky_view/svf_check.h"
#include "test_support.h"

using namespace skyview;
using namespace skyview::test;

namespace {

class CliErrors : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = temp_dir("cli");
    good = dir + "/good.tif";
    write_terrain(good, with_local_metric_crs(rasterize(circular_pit(5, 5), 21, 21, local_grid(21, 21, 1.0))), {});
  }
  std::string dir, good;
};

// GDAL's habits: -co takes one KEY=VALUE a time, so options may come before the files; an output
// named for another format than it is written in is refused.
TEST_F(CliErrors, GdalStyleOptionsBeforeTheFilesAndOutputsNamedForTheirFormat) {
  const RunResult r = run_skyview("svf -co COMPRESS=LZW -co TILED=NO " + good + " " + dir + "/lzw.tif", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  init_gdal();
  GDALDatasetUniquePtr ds(GDALDataset::Open((dir + "/lzw.tif").c_str(), GDAL_OF_RASTER));
  ASSERT_TRUE(ds);
  EXPECT_STREQ(ds->GetMetadataItem("COMPRESSION", "IMAGE_STRUCTURE"), "LZW");
  expect_one_line_error(run_skyview("svf " + good + " " + dir + "/svf.png", dir), "does not end in .tif or .tiff");
  expect_one_line_error(run_skyview("horizon " + good + " " + dir + "/h.nc", dir), "give -of");
  EXPECT_FALSE(std::filesystem::exists(dir + "/svf.png"));
}

// A creation option the driver refuses leaves nothing behind: GDAL's failed Create wrote a bare
// TIFF header under the temporary name, which its own Delete could not open, so until Dec 5 it stayed.
TEST_F(CliErrors, AFailedCreateLeavesNoTemporaryFile) {
  for (const char* command : {"svf", "horizon"}) {
    expect_one_line_error(run_skyview(std::string(command) + " " + good + " " + dir + "/b.tif -co BLOCKXSIZE=7", dir),
                          "TileWidth");
    for (const auto& entry : std::filesystem::directory_iterator(dir))
      EXPECT_EQ(entry.path().filename().string().find("skyview-tmp"), std::string::npos) << entry.path();
  }
}

// On a raster 3 m across the sampled method's 500 m radius puts every sample beyond it for 8
// samples: those configurations are skipped and said, the rest benched (until Dec 5 the first
// refusal ended the whole bench and left its empty folder).
TEST_F(CliErrors, BenchSkipsConfigurationsThatCannotRunOnTheRaster) {
  ASSERT_EQ(run_skyview("synth pit " + dir + "/tiny.tif --size 20 --cell 0.1", dir).exit_code, 0);
  const RunResult r = run_skyview("bench " + dir + "/tiny.tif --methods sampled --repeat 1 --out " + dir + "/b", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("Warning: sampled d=8 s=8 r=500 skipped: --radius 500 m puts every sample"), std::string::npos)
      << r.err;
  std::ifstream in(dir + "/b/bench.json");
  const std::string json((std::istreambuf_iterator<char>(in)), {});
  EXPECT_NE(json.find("\"skipped\""), std::string::npos);
  EXPECT_NE(json.find("\"label\": \"sampled d=32 s=64 r=500\""), std::string::npos) << "the others ran";
  EXPECT_NE(json.find("\"band\": 1"), std::string::npos);
  EXPECT_NE(json.find("\"z_scale\": 1"), std::string::npos);
}

// A run stopped by a signal (Ctrl-C, a batch scheduler's SIGTERM at its time limit) removes the
// hidden temporary file it was writing; until Dec 5 a killed `horizon` left it, megabytes of it.
TEST_F(CliErrors, AStoppedRunLeavesNoTemporaryFile) {
  ASSERT_EQ(run_skyview("synth city " + dir + "/big.tif --size 500", dir).exit_code, 0);
  auto temporary_exists = [&] {
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
      if (entry.path().filename().string().find("skyview-tmp") != std::string::npos) return true;
    }
    return false;
  };
  const std::string in = dir + "/big.tif", out = dir + "/h.tif";
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    std::freopen("/dev/null", "w", stderr);
    execl(SKYVIEW_EXE, SKYVIEW_EXE, "horizon", in.c_str(), out.c_str(), "--method", "march", "--radius", "200",
          "--directions", "64", "-q", static_cast<char*>(nullptr));
    _exit(127);
  }
  bool seen = false;
  for (int i = 0; i < 600 && !(seen = temporary_exists()); ++i) usleep(50000);
  kill(pid, SIGTERM);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(seen) << "the run made no temporary file to remove";
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << "the run ended before the signal: " << status;
  EXPECT_FALSE(temporary_exists());
  EXPECT_FALSE(std::filesystem::exists(out));
}

// A radius shorter than a cell reaches no grid line: every horizon would be open.
TEST_F(CliErrors, ARadiusShorterThanACellIsRefused) {
  expect_one_line_error(run_skyview("svf " + good + " " + dir + "/r.tif --method march --radius 0.5", dir),
                        "reaches no neighbouring cell");
  EXPECT_EQ(run_skyview("svf " + good + " " + dir + "/r1.tif --method march --radius 1", dir).exit_code, 0);
}

// Horizon outputs count the cells whose search leaves the raster, as the svf's do.
TEST_F(CliErrors, HorizonOutputsCountTheirEdgeCells) {
  // (4.999: the raster's CRS measures on the ellipsoid, a hair off whole metres.)
  ASSERT_EQ(run_skyview("horizon " + good + " " + dir + "/h.tif --radius 4.999 --directions 4", dir).exit_code, 0);
  init_gdal();
  GDALDatasetUniquePtr ds(GDALDataset::Open((dir + "/h.tif").c_str(), GDAL_OF_RASTER));
  ASSERT_TRUE(ds);
  // 21 x 21 cells of 1 m: those within 5 m of a side leave, the 11 x 11 around the centre do not.
  EXPECT_STREQ(ds->GetMetadataItem("EDGE_CELLS"), std::to_string(21 * 21 - 11 * 11).c_str());
}

// A bad option is said before an existing output: the user fixing the output would meet it next.
TEST_F(CliErrors, OptionErrorsComeBeforeAnExistingOutput) {
  std::ofstream(dir + "/there.tif") << "kept";
  expect_one_line_error(run_skyview("svf " + good + " " + dir + "/there.tif --samples 99999", dir), "--samples");
  expect_one_line_error(run_skyview("horizon " + good + " " + dir + "/there.tif --far-lines 2 --method march", dir),
                        "--far-lines applies only");
  expect_one_line_error(run_skyview("svf " + good + " " + dir + "/there.tif", dir), "exists; use --overwrite");
  std::ifstream kept(dir + "/there.tif");
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(kept), {}), "kept");
}

// --max-error is met by a 95% bound of the p99, which a handful of cells cannot give: one cell
// used to be reported as "met with 95% confidence".
TEST_F(CliErrors, MaxErrorNeedsEnoughCheckedCellsForItsBound) {
  expect_one_line_error(run_skyview("svf " + good + " " + dir + "/m.tif --max-error 0.05 --check-cells 10", dir),
                        "needs 299 cells or more");
  // Without --max-error ten cells still measure, and record no bound.
  const RunResult few = run_skyview("svf " + good + " " + dir + "/c.tif --check-cells 10", dir);
  ASSERT_EQ(few.exit_code, 0) << few.err;
  init_gdal();
  GDALDatasetUniquePtr ds(GDALDataset::Open((dir + "/c.tif").c_str(), GDAL_OF_RASTER));
  ASSERT_TRUE(ds);
  EXPECT_STREQ(ds->GetMetadataItem("SVF_CHECK_CELLS"), "10");
  EXPECT_EQ(ds->GetMetadataItem("SVF_CHECK_P99_UPPER95"), nullptr);
}

TEST_F(CliErrors, MissingFile) {
  expect_one_line_error(run_skyview("svf " + dir + "/nope.tif " + dir + "/o.tif", dir), "no such file");
}

TEST_F(CliErrors, NotARaster) {
  std::ofstream(dir + "/text.tif") << "this is not a raster\n";
  expect_one_line_error(run_skyview("svf " + dir + "/text.tif " + dir + "/o.tif", dir), "no GDAL driver reads it");
  std::filesystem::create_directory(dir + "/folder");
  expect_one_line_error(run_skyview("svf " + dir + "/folder " + dir + "/o.tif", dir), "is a folder, not a raster");
}

TEST_F(CliErrors, UnknownSubcommand) {
  expect_one_line_error(run_skyview("sfv " + good + " " + dir + "/o.tif", dir), "unknown subcommand 'sfv'", 2);
}

TEST_F(CliErrors, SynthAndBenchRefuseWhatTheyCannotMake) {
  expect_one_line_error(run_skyview("synth city " + dir + "/c.tif --crs EPSG:4326", dir), "must be a projected CRS");
  expect_one_line_error(run_skyview("bench " + good + " --methods '' --out " + dir + "/b", dir), "no method given");
  expect_one_line_error(run_skyview("bench " + good + " --methods sweep,sweep --out " + dir + "/b", dir),
                        "given twice");
  // Refused once the folders are made (the input is found out by reading it): they go again, all of
  // them.
  expect_one_line_error(run_skyview("bench " + dir + "/none.tif --methods march --out " + dir + "/nest/a/b", dir),
                        "none.tif");
  EXPECT_FALSE(std::filesystem::exists(dir + "/nest"));
  expect_one_line_error(run_skyview("bench " + good + " --band 2 --methods march --out " + dir + "/b", dir), "band 2");
  EXPECT_FALSE(std::filesystem::exists(dir + "/b"));
}

// A list option (--points) takes every value after it: an output given after one is taken too, and
// the error says why; `--` ends the list.
TEST_F(CliErrors, AListOptionBeforeTheOutputSaysItTookIt) {
  ASSERT_EQ(run_skyview("synth lidar " + dir + "/d.las --size 64", dir).exit_code, 0);
  expect_one_line_error(run_skyview("dsm --points " + dir + "/d.las " + dir + "/dsm.tif", dir),
                        "--points takes every value after it", 2);
  EXPECT_EQ(run_skyview("dsm --points " + dir + "/d.las -- " + dir + "/dsm.tif", dir).exit_code, 0);
  EXPECT_TRUE(std::filesystem::exists(dir + "/dsm.tif"));
}

// A cloud far sparser than the grid leaves a raster of holes: said, with what to change (not under
// -q, so this one runs without it).
TEST_F(CliErrors, ASparseCloudOnAFineGridIsSaid) {
  write_las(dir + "/sparse.las", {{0.5, 0.5, 1.0, 0, 1, 1, 2}, {99.5, 99.5, 2.0, 0, 1, 1, 2}}, [] {
    LasWriteOptions o;
    o.crs_wkt = wkt_of("EPSG:32633");
    return o;
  }());
  // Under -q too (run_skyview adds it): -q silences progress and summaries, never warnings.
  const RunResult r = run_skyview("dsm " + dir + "/sparse.tif --points " + dir + "/sparse.las", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("cells hold a height: the grid is much finer than the returns"), std::string::npos) << r.err;
}

// LAS classes are 0..255: 300 used to pass and end in "none of the returns falls on the grid".
TEST_F(CliErrors, DsmClassesOutsideTheLasRangeAreRefused) {
  write_las(dir + "/two.las", {{0.5, 0.5, 1.0, 0, 1, 1, 2}, {9.5, 9.5, 2.0, 0, 1, 1, 6}}, [] {
    LasWriteOptions o;
    o.crs_wkt = wkt_of("EPSG:32633");
    return o;
  }());
  expect_one_line_error(run_skyview("dsm " + dir + "/c.tif --points " + dir + "/two.las --classes 2,300", dir),
                        "class 300 is outside the LAS classes 0 to 255");
  expect_one_line_error(run_skyview("dsm " + dir + "/c.tif --points " + dir + "/two.las --classes 2,,6", dir),
                        "comma-separated integers, not ''");
}

// GROUND_FROM says which returns were taken as ground: class 2 with --ground-only on a classified
// cloud, none where no ground was asked for (it read "all returns" until Dec 3, with --classes 6 too).
TEST_F(CliErrors, DsmSaysWhichReturnsWereGround) {
  ASSERT_EQ(run_skyview("synth lidar " + dir + "/d.las --size 64", dir).exit_code, 0);
  const std::pair<std::string, std::string> runs[] = {{"--classes 6", "none (no ground asked for)"},
                                                      {"--ground-only", "class 2"}};
  for (const auto& [option, ground] : runs) {
    const std::string out = dir + "/dsm.tif";
    ASSERT_EQ(run_skyview("dsm " + out + " --points " + dir + "/d.las " + option + " --overwrite", dir).exit_code, 0);
    GDALDatasetUniquePtr ds(GDALDataset::Open(out.c_str(), GDAL_OF_RASTER));
    ASSERT_TRUE(ds);
    EXPECT_STREQ(ds->GetMetadataItem("GROUND_FROM"), ground.c_str()) << option;
  }
  // The terrain written beside it carries its own provenance, not the DSM's statistic and counts.
  const std::string dtm = dir + "/dtm.tif";
  ASSERT_EQ(
      run_skyview("dsm " + dir + "/dsm.tif --points " + dir + "/d.las --ground-only --dtm " + dtm + " --overwrite", dir)
          .exit_code,
      0);
  GDALDatasetUniquePtr ds(GDALDataset::Open(dtm.c_str(), GDAL_OF_RASTER));
  ASSERT_TRUE(ds);
  EXPECT_NE(std::string(ds->GetMetadataItem("TERRAIN_FROM")).find("ground returns"), std::string::npos);
  EXPECT_STREQ(ds->GetMetadataItem("GROUND_FROM"), "class 2");
  EXPECT_EQ(ds->GetMetadataItem("POINT_STATISTIC"), nullptr);
  EXPECT_EQ(ds->GetMetadataItem("FOOTPRINTS_BURNED"), nullptr);
}

// PCL sits in a module loaded on first use (src/dsm/pcl_module.h): a run that needs no PCL
// works without it; one that does (a PLY cloud, --denoise) gets one line saying what is missing,
// and writes nothing. The module is found beside the executable, or only in SKYVIEW_MODULE_DIR
// when that is set; a file there that is not a module is reported, not skipped.
TEST_F(CliErrors, OnlyRunsThatUsePclNeedItsModule) {
  ASSERT_EQ(run_skyview("synth lidar " + dir + "/d.las --size 64", dir).exit_code, 0);
  std::ofstream(dir + "/p.ply") << "ply\nformat ascii 1.0\nelement vertex 2\nproperty double x\nproperty double y\n"
                                   "property double z\nend_header\n500002.5 6400008.5 10\n500000.5 6400009.5 5\n";
  const std::string ply_run = "dsm " + dir + "/ply.tif --points " + dir + "/p.ply --s_srs EPSG:32633 --overwrite";
  const std::string denoise_run = "dsm " + dir + "/denoised.tif --points " + dir + "/d.las --denoise --overwrite";
  const std::filesystem::path build = std::filesystem::path(SKYVIEW_EXE).parent_path();
  // The executable alone in a folder of its own: its default search finds nothing (unless an
  // install folder holds a module, which the test then cannot judge).
  const std::filesystem::path lone = std::filesystem::path(dir) / "bin" / "skyview";
  std::filesystem::create_directories(lone.parent_path());
  std::filesystem::copy_file(SKYVIEW_EXE, lone);
  struct ModuleDir {  // the children inherit it; the caller's own value comes back whatever happens
    explicit ModuleDir(const char* d) {
      if (const char* v = std::getenv("SKYVIEW_MODULE_DIR")) old = v, had = true;
      d ? setenv("SKYVIEW_MODULE_DIR", d, 1) : unsetenv("SKYVIEW_MODULE_DIR");
    }
    ~ModuleDir() { had ? setenv("SKYVIEW_MODULE_DIR", old.c_str(), 1) : unsetenv("SKYVIEW_MODULE_DIR"); }
    std::string old;
    bool had = false;
  };
  {
    const ModuleDir env(nullptr);
    EXPECT_EQ(run_executable(lone.string(), "dsm " + dir + "/las.tif --points " + dir + "/d.las", dir).exit_code, 0);
    if (!std::filesystem::exists(std::filesystem::path(SKYVIEW_MODULE_INSTALL_DIR) / "libskyview_pcl.so")) {
      expect_one_line_error(run_executable(lone.string(), ply_run, dir),
                            "PCL module: no libskyview_pcl.so in " + lone.parent_path().string());
      expect_one_line_error(run_executable(lone.string(), denoise_run, dir), "set SKYVIEW_MODULE_DIR");
    }
    std::filesystem::copy_file(build / "libskyview_pcl.so", lone.parent_path() / "libskyview_pcl.so");
    EXPECT_EQ(run_executable(lone.string(), ply_run, dir).exit_code, 0);
  }
  const std::string none = dir + "/no_modules", bad = dir + "/bad_module";
  std::filesystem::create_directories(none);
  std::filesystem::create_directories(bad);
  std::ofstream(bad + "/libskyview_pcl.so") << "not a shared library";
  std::filesystem::remove(dir + "/ply.tif");
  {
    const ModuleDir env(none.c_str());
    expect_one_line_error(run_skyview(ply_run, dir), "PCL module: no libskyview_pcl.so in " + none + " (");
    expect_one_line_error(run_skyview(denoise_run, dir), "SKYVIEW_MODULE_DIR names it");
  }
  {
    const ModuleDir env(bad.c_str());
    expect_one_line_error(run_skyview(denoise_run, dir), bad + "/libskyview_pcl.so does not load");
  }
  EXPECT_FALSE(std::filesystem::exists(dir + "/ply.tif"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/denoised.tif"));
  {
    const ModuleDir env(nullptr);
    EXPECT_EQ(run_skyview(ply_run, dir).exit_code, 0);
    EXPECT_EQ(run_skyview(denoise_run, dir).exit_code, 0);
  }
  EXPECT_TRUE(std::filesystem::exists(dir + "/ply.tif"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/denoised.tif"));
}

TEST_F(CliErrors, SingleCellRaster) {
  write_terrain(dir + "/one.tif", rasterize(circular_pit(5, 5), 1, 1, local_grid(1, 1, 1.0)), {});
  expect_one_line_error(run_skyview("svf " + dir + "/one.tif " + dir + "/o.tif", dir), "single cell");
}

TEST_F(CliErrors, AllNodataRaster) {
  Terrain t = rasterize(circular_pit(5, 5), 5, 5, local_grid(5, 5, 1.0));
  for (float& v : t.heights.values()) v = std::numeric_limits<float>::quiet_NaN();
  write_terrain(dir + "/nodata.tif", t, {});
  expect_one_line_error(run_skyview("svf " + dir + "/nodata.tif " + dir + "/o.tif", dir), "only nodata");
}

TEST_F(CliErrors, InfiniteHeights) {
  Terrain t = rasterize(circular_pit(5, 5), 5, 5, local_grid(5, 5, 1.0));
  t.heights(2, 3) = std::numeric_limits<float>::infinity();
  WriteOptions wo;
  wo.nodata = -32768.0f;
  write_terrain(dir + "/inf.tif", t, wo);
  expect_one_line_error(run_skyview("svf " + dir + "/inf.tif " + dir + "/o.tif", dir),
                        "infinite height at cell (2, 3)");
}

TEST_F(CliErrors, UndeclaredNanIsNodataWithAWarning) {
  // A NaN cell in a band whose nodata value is -9999 (write_terrain would write the NaN as -9999).
  const std::string path = dir + "/nan.tif";
  {
    init_gdal();
    GDALDriver* gtiff = GetGDALDriverManager()->GetDriverByName("GTiff");
    GDALDatasetUniquePtr ds(gtiff->Create(path.c_str(), 9, 9, 1, GDT_Float32, nullptr));
    double gt[6] = {500000, 1, 0, 5000009, 0, -1};
    ds->SetGeoTransform(gt);
    ds->SetProjection(test::wkt_of("EPSG:32633").c_str());
    std::vector<float> z(81, 10.0f);
    z[40] = std::numeric_limits<float>::quiet_NaN();
    GDALRasterBand* band = ds->GetRasterBand(1);
    band->SetNoDataValue(-9999);
    ASSERT_EQ(band->RasterIO(GF_Write, 0, 0, 9, 9, z.data(), 9, 9, GDT_Float32, 0, 0), CE_None);
  }
  const RunResult r = run_skyview("svf " + path + " " + dir + "/o.tif", dir);  // -q: it changes the data, so said
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("Warning: 1 NaN cells"), std::string::npos) << r.err;
}

TEST_F(CliErrors, ZeroOrNegativeRadius) {
  for (const char* radius : {"0", "-5"}) {
    const RunResult r = run_skyview("svf " + good + " " + dir + "/o.tif --method march --radius " + radius, dir);
    EXPECT_NE(r.exit_code, 0) << radius;
    EXPECT_NE(r.err.find("radius"), std::string::npos) << r.err;
  }
}

TEST_F(CliErrors, ExistingOutputIsKeptWithoutOverwrite) {
  const std::string out = dir + "/o.tif";
  ASSERT_EQ(run_skyview("svf " + good + " " + out, dir).exit_code, 0);
  const auto before = std::filesystem::last_write_time(out);
  expect_one_line_error(run_skyview("svf " + good + " " + out, dir), "--overwrite");
  EXPECT_EQ(std::filesystem::last_write_time(out), before);
  EXPECT_EQ(run_skyview("svf " + good + " " + out + " --overwrite", dir).exit_code, 0);
  // No temporary files are left behind.
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    files += e.path().filename().string().find("skyview-tmp") != std::string::npos;
  EXPECT_EQ(files, 0);
}

// A 100² synthetic city is harder than the calibration rasters (64 sectors alone are 0.0112 off
// its continuous svf at p99, against 0.0094 on city.tif): --max-error 0.01's calibrated choice does
// not hold there. The svf check sees it and runs a finer choice.
TEST_F(CliErrors, MaxErrorMeasuresItsChoiceAndRunsAgainWhereTheRasterIsHarder) {
  const std::string in = dir + "/city.tif", out = dir + "/svf.tif", unchecked = dir + "/unchecked.tif";
  ASSERT_EQ(run_skyview("synth city --size 100 " + in, dir).exit_code, 0);
  ASSERT_EQ(run_skyview("svf " + in + " " + out + " --max-error 0.01 --products svf", dir).exit_code, 0);
  GDALDatasetUniquePtr ds(GDALDataset::Open(out.c_str(), GDAL_OF_RASTER));
  ASSERT_TRUE(ds);
  EXPECT_STREQ(ds->GetMetadataItem("SVF_CHECK_CELLS"), "1000");
  const std::string tried = ds->GetMetadataItem("MAX_ERROR_TRIED");
  EXPECT_NE(tried.find("; "), std::string::npos) << "ran once: " << tried;
  EXPECT_EQ(std::string(ds->GetMetadataItem("MAX_ERROR_MET")).rfind("yes", 0), 0u);
  EXPECT_LE(std::stod(ds->GetMetadataItem("MAX_ERROR_MEASURED_BOUND")), 0.01);
  // Against the continuous svf (exact horizons in 1024 sectors) over every cell, the request holds.
  const Terrain t = read_terrain(in, {});
  SvfCheckOptions all;
  all.cells = t.width() * t.height();
  all.directions = 256;
  const SvfCheck continuous(t, all);
  ASSERT_TRUE(continuous.exhaustive());
  Grid<float> svf(t.width(), t.height());
  ASSERT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, t.width(), t.height(), svf.data(), t.width(), t.height(),
                                           GDT_Float32, 0, 0),
            CE_None);
  EXPECT_LE(continuous.measure(svf).error_fine.p99, 0.01);
  // Without the check, the calibrated choice alone, which does not hold here.
  ASSERT_EQ(
      run_skyview("svf " + in + " " + unchecked + " --max-error 0.01 --products svf --check-cells 0", dir).exit_code,
      0);
  GDALDatasetUniquePtr plain(GDALDataset::Open(unchecked.c_str(), GDAL_OF_RASTER));
  ASSERT_TRUE(plain);
  EXPECT_EQ(plain->GetMetadataItem("SVF_CHECK_P99"), nullptr);
  EXPECT_EQ(plain->GetMetadataItem("MAX_ERROR_TRIED"), nullptr);
  ASSERT_EQ(plain->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, t.width(), t.height(), svf.data(), t.width(), t.height(),
                                              GDT_Float32, 0, 0),
            CE_None);
  EXPECT_GT(continuous.measure(svf).error_fine.p99, 0.01);
}

TEST_F(CliErrors, CheckCellsMeasuresAnyMethod) {
  const std::string out = dir + "/svf.tif";
  ASSERT_EQ(run_skyview("svf " + good + " " + out + " --method march --directions 8 --check-cells 200", dir).exit_code,
            0);
  GDALDatasetUniquePtr ds(GDALDataset::Open(out.c_str(), GDAL_OF_RASTER));
  ASSERT_TRUE(ds);
  EXPECT_STREQ(ds->GetMetadataItem("SVF_CHECK_CELLS"), "200");
  EXPECT_EQ(ds->GetMetadataItem("SVF_CHECK_P99_UPPER95"), nullptr) << "200 cells bound no p99";
  EXPECT_EQ(ds->GetMetadataItem("MAX_ERROR_MET"), nullptr);
  // 8 directions against the check's 64: the pit's rim is round, the sectors are not.
  const double p99 = std::stod(ds->GetMetadataItem("SVF_CHECK_P99"));
  EXPECT_GT(p99, 0.0);
  EXPECT_LT(p99, 0.1);
  expect_one_line_error(run_skyview("svf " + good + " " + dir + "/o.tif --check-cells -5", dir), "--check-cells", 2);
}

TEST_F(CliErrors, NegativeRadiusWithTheDefaultSweep) {
  expect_one_line_error(run_skyview("svf " + good + " " + dir + "/o.tif --radius -100", dir),
                        "--radius: must be a positive number", 2);
}

TEST_F(CliErrors, UnknownMethodBandAndFormat) {
  expect_one_line_error(run_skyview("svf " + good + " " + dir + "/o.tif --method nope", dir), "unknown method");
  expect_one_line_error(run_skyview("svf " + good + " " + dir + "/o.tif -b 3", dir), "band 3 does not exist");
  expect_one_line_error(run_skyview("svf " + good + " " + dir + "/o.tif -of NOPE", dir), "unknown output format");
}

TEST_F(CliErrors, OutputCarriesBandsMetadataAndGeoreference) {
  const std::string out = dir + "/svf.tif";
  ASSERT_EQ(run_skyview("svf " + good + " " + out + " -co COMPRESS=LZW --directions 8 --method march", dir).exit_code,
            0);
  GDALDatasetUniquePtr ds(GDALDataset::Open(out.c_str(), GDAL_OF_RASTER));
  ASSERT_TRUE(ds);
  ASSERT_EQ(ds->GetRasterCount(), 5);
  const char* names[] = {"svf", "svf_surface", "sky_visibility", "openness_positive", "openness_negative"};
  for (int b = 0; b < 5; ++b) EXPECT_STREQ(ds->GetRasterBand(b + 1)->GetDescription(), names[b]);
  EXPECT_STREQ(ds->GetRasterBand(4)->GetUnitType(), "degree");
  EXPECT_STREQ(ds->GetMetadataItem("DIRECTIONS"), "8");
  EXPECT_STREQ(ds->GetMetadataItem("METHOD"), "march");
  EXPECT_STREQ(ds->GetMetadataItem("CURVATURE"), "off (auto)") << "a 500 m radius drops angles by < 0.01°";
  EXPECT_EQ(ds->GetMetadataItem("REFRACTION"), nullptr);
  EXPECT_STREQ(ds->GetMetadataItem("COMPRESSION", "IMAGE_STRUCTURE"), "LZW");
  int has = 0;
  EXPECT_EQ(ds->GetRasterBand(1)->GetNoDataValue(&has), -9999.0);
  EXPECT_TRUE(has);
  double gt[6];
  ASSERT_EQ(ds->GetGeoTransform(gt), CE_None);
  EXPECT_DOUBLE_EQ(gt[1], 1.0);
  // The pit bottom centre, cos²(atan(5/5)) = 0.5 for a smooth rim; 1 m cells make the rim ragged.
  float v = 0;
  ASSERT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Read, 10, 10, 1, 1, &v, 1, 1, GDT_Float32, 0, 0), CE_None);
  EXPECT_NEAR(v, 0.5, 0.05);
  // Auto is recorded as what it resolved to: on for a 5 km radius (0.02° at its end).
  const std::string far = dir + "/far.tif";
  ASSERT_EQ(run_skyview("svf " + good + " " + far + " --directions 8 --method march --radius 5000", dir).exit_code, 0);
  GDALDatasetUniquePtr curved(GDALDataset::Open(far.c_str(), GDAL_OF_RASTER));
  ASSERT_TRUE(curved);
  EXPECT_STREQ(curved->GetMetadataItem("CURVATURE"), "on (auto)");
  EXPECT_STREQ(curved->GetMetadataItem("REFRACTION"), "0.13");
}

// The methods that hold all directions of a block of rows write GeoTIFF tiles no taller than the
// rows their 256 MB hold (300 cells at 1024 directions: 213 rows, so tiles of 208), unless the user
// set the tiling. Until Dec 3 a tile row of 256 was held whatever the directions.
TEST_F(CliErrors, HorizonTilesFitTheRowsHeldAtOnce) {
  const std::string wide = dir + "/wide.tif", out = dir + "/h.tif";
  write_terrain(wide, rasterize(circular_pit(5, 5), 300, 20, local_grid(300, 20, 1.0)), {});
  ASSERT_EQ(run_skyview("horizon " + wide + " " + out + " --method march --radius 3 --directions 1024", dir).exit_code,
            0);
  int x = 0, y = 0;
  {
    GDALDatasetUniquePtr ds(GDALDataset::Open(out.c_str(), GDAL_OF_RASTER));
    ASSERT_TRUE(ds);
    ds->GetRasterBand(1)->GetBlockSize(&x, &y);
    EXPECT_EQ(x, 256);
    EXPECT_EQ(y, 208);
    // Band names in [0, 360): the last of 1024 sectors from north.
    EXPECT_STREQ(ds->GetRasterBand(1024)->GetDescription(), "horizon_azimuth_359.6484375");
  }
  ASSERT_EQ(run_skyview("horizon " + wide + " " + out +
                            " --method march --radius 3 --directions 1024 --overwrite "
                            "-co BLOCKYSIZE=32",
                        dir)
                .exit_code,
            0);
  GDALDatasetUniquePtr ds(GDALDataset::Open(out.c_str(), GDAL_OF_RASTER));
  ds->GetRasterBand(1)->GetBlockSize(&x, &y);
  EXPECT_EQ(y, 32);
}

TEST_F(CliErrors, HorizonBandsNameTheirAzimuths) {
  const std::string out = dir + "/h.tif";
  ASSERT_EQ(run_skyview("horizon " + good + " " + out + " --directions 4 --method march", dir).exit_code, 0);
  GDALDatasetUniquePtr ds(GDALDataset::Open(out.c_str(), GDAL_OF_RASTER));
  ASSERT_EQ(ds->GetRasterCount(), 4);
  EXPECT_STREQ(ds->GetRasterBand(2)->GetDescription(), "horizon_azimuth_90");
  // Bottom of a pit of radius 5 and depth 5: the rim's elevation is about 45 degrees.
  float v = 0;
  ASSERT_EQ(ds->GetRasterBand(2)->RasterIO(GF_Read, 10, 10, 1, 1, &v, 1, 1, GDT_Float32, 0, 0), CE_None);
  EXPECT_NEAR(v, 45.0, 3.0);
}

// With the sectors started on grid north, each band is named by its true azimuth, within [0, 360)
// (here grid north is 30° east of true north, so the last of 16 bands is at 7.5°), and the outputs
// record the rotation; svf starts there by default, horizon on true north.
TEST_F(CliErrors, SectorsFromGridNorthNameTheirTrueAzimuths) {
  GeoReference g = local_grid(21, 21, 1.0);
  const double turn = 30.0 * M_PI / 180.0;
  g.geotransform[1] = std::cos(turn), g.geotransform[2] = -std::sin(turn);
  g.geotransform[4] = -std::sin(turn), g.geotransform[5] = -std::cos(turn);
  const std::string turned = dir + "/turned.tif", h = dir + "/h.tif", s = dir + "/s.tif";
  write_terrain(turned, rasterize(circular_pit(5, 5), 21, 21, g), {});
  ASSERT_EQ(run_skyview("horizon " + turned + " " + h + " --directions 16 --azimuth-origin grid", dir).exit_code, 0);
  GDALDatasetUniquePtr ds(GDALDataset::Open(h.c_str(), GDAL_OF_RASTER));
  ASSERT_EQ(ds->GetRasterCount(), 16);
  EXPECT_STREQ(ds->GetRasterBand(1)->GetDescription(), "horizon_azimuth_30");
  EXPECT_STREQ(ds->GetRasterBand(16)->GetDescription(), "horizon_azimuth_7.5");
  EXPECT_STREQ(ds->GetMetadataItem("SECTOR_ROTATION_DEG"), "30");
  ASSERT_EQ(run_skyview("svf " + turned + " " + s + " --products svf", dir).exit_code, 0);
  GDALDatasetUniquePtr svf(GDALDataset::Open(s.c_str(), GDAL_OF_RASTER));
  EXPECT_EQ(std::string(svf->GetMetadataItem("AZIMUTH_ORIGIN")).rfind("grid", 0), 0u);
  ASSERT_EQ(run_skyview("horizon " + good + " " + h + " --directions 4 --overwrite", dir).exit_code, 0);
  ds.reset(GDALDataset::Open(h.c_str(), GDAL_OF_RASTER));
  EXPECT_EQ(std::string(ds->GetMetadataItem("AZIMUTH_ORIGIN")).rfind("north", 0), 0u);
}

// --azimuths grid-lines: the bands name the grid's lines and the angle each stands for, the
// outputs say so, and counts or methods it cannot serve are refused with one line.
TEST_F(CliErrors, GridLineAzimuthsNameTheirBandsAndRefuseWhatTheyCannotServe) {
  const std::string h = dir + "/h.tif", s = dir + "/s.tif";
  ASSERT_EQ(run_skyview("horizon " + good + " " + h + " --directions 16 --azimuths grid-lines", dir).exit_code, 0);
  GDALDatasetUniquePtr ds(GDALDataset::Open(h.c_str(), GDAL_OF_RASTER));
  ASSERT_EQ(ds->GetRasterCount(), 16);
  EXPECT_STREQ(ds->GetRasterBand(2)->GetDescription(), "horizon_azimuth_26.56505118");
  EXPECT_STREQ(ds->GetRasterBand(3)->GetDescription(), "horizon_azimuth_45");
  EXPECT_NEAR(std::stod(ds->GetRasterBand(3)->GetMetadataItem("SECTOR_WIDTH_DEG")), 13.75, 0.01);
  EXPECT_EQ(std::string(ds->GetMetadataItem("AZIMUTHS")).rfind("grid-lines", 0), 0u);
  ASSERT_EQ(run_skyview("svf " + good + " " + s + " --products svf --azimuths grid-lines", dir).exit_code, 0);
  expect_one_line_error(
      run_skyview("svf " + good + " " + s + " --overwrite --azimuths grid-lines --directions 32", dir),
      "needs 4, 8 or 16 directions (got 32)");
  expect_one_line_error(
      run_skyview("svf " + good + " " + s + " --overwrite --azimuths grid-lines --directions 16 --method sampled", dir),
      "needs fixed directions");
  expect_one_line_error(
      run_skyview("svf " + good + " " + s + " --overwrite --azimuths grid-lines --max-error 0.01", dir), "--azimuths");
  expect_one_line_error(
      run_skyview("horizon " + good + " " + h + " --overwrite --azimuths grid-lines --azimuth-origin north", dir),
      "starts on grid north");
  expect_one_line_error(run_skyview("svf " + good + " " + s + " --overwrite --azimuths grid-lines --samples 16", dir),
                        "every direction is exact");
}

// GDAL's message for a format that cannot hold the bands breaks lines; the error stays one line.
// Formats of bytes would round svf to 0 or 1 with only a warning: they are refused first.
TEST_F(CliErrors, FormatThatCannotHoldTheBands) {
  expect_one_line_error(run_skyview("horizon " + good + " " + dir + "/h.asc -of AAIGrid --directions 8", dir),
                        "driver doesn't support 8 bands");
  EXPECT_FALSE(std::filesystem::exists(dir + "/h.asc"));
  expect_one_line_error(run_skyview("svf " + good + " " + dir + "/s.jpg -of JPEG", dir), "cannot hold float32");
  EXPECT_FALSE(std::filesystem::exists(dir + "/s.jpg"));
}

// An output that names an input, another output, or something that is not a file is refused before
// any work, with or without --overwrite; the input is left as it was.
TEST_F(CliErrors, OutputsNeverReplaceInputsOrOtherOutputs) {
  const auto size = std::filesystem::file_size(good);
  const auto before = std::filesystem::last_write_time(good);
  expect_one_line_error(run_skyview("svf " + good + " " + good + " --overwrite", dir), "is also an input");
  expect_one_line_error(run_skyview("svf " + good + " " + dir + "/./good.tif --overwrite", dir), "is also an input");
  std::filesystem::create_symlink(good, dir + "/link.tif");
  expect_one_line_error(run_skyview("svf " + good + " " + dir + "/link.tif --overwrite", dir), "is also an input");
  expect_one_line_error(run_skyview("svf " + good + " " + dir + "/o.tif --preview " + good + " --overwrite", dir),
                        "is also an input");
  expect_one_line_error(run_skyview("svf " + good + " " + dir + "/o.tif --preview " + dir + "/o.tif", dir),
                        "two outputs are both");
  expect_one_line_error(run_skyview("svf " + good + " " + dir + "/o.tif --preview " + dir + "/./o.tif", dir),
                        "name the same output file");
  EXPECT_FALSE(std::filesystem::exists(dir + "/o.tif"));
  EXPECT_EQ(std::filesystem::file_size(good), size);
  EXPECT_EQ(std::filesystem::last_write_time(good), before);
  // A VRT reads its source: the source is an input too.
  {
    GDALDatasetUniquePtr src(GDALDataset::Open(good.c_str(), GDAL_OF_RASTER));
    GDALDriver* vrt = GetGDALDriverManager()->GetDriverByName("VRT");
    GDALDatasetUniquePtr copy(
        vrt->CreateCopy((dir + "/view.vrt").c_str(), src.get(), FALSE, nullptr, nullptr, nullptr));
    ASSERT_TRUE(copy);
  }
  expect_one_line_error(run_skyview("svf " + dir + "/view.vrt " + good + " --overwrite", dir), "is also an input");
  EXPECT_EQ(std::filesystem::last_write_time(good), before);
  std::filesystem::create_directory(dir + "/folder.tif");
  expect_one_line_error(run_skyview("svf " + good + " " + dir + "/folder.tif --overwrite", dir),
                        "is not a regular file");
  EXPECT_TRUE(std::filesystem::is_directory(dir + "/folder.tif"));
}

// NaN passes every range check by comparison; the numbers that steer a run refuse it, and an
// accuracy of 0 is refused rather than ignored.
TEST_F(CliErrors, NumbersThatSteerTheRunMustBeNumbers) {
  expect_one_line_error(run_skyview("svf " + good + " " + dir + "/o.tif --refraction nan", dir),
                        "--refraction: must be a finite number", 2);
  expect_one_line_error(run_skyview("svf " + good + " " + dir + "/o.tif --max-error nan", dir),
                        "--max-error: must be a number above 0 and at most 1", 2);
  expect_one_line_error(run_skyview("svf " + good + " " + dir + "/o.tif --max-error 0", dir),
                        "--max-error: must be a number above 0 and at most 1", 2);
  expect_one_line_error(run_skyview("svf " + good + " " + dir + "/o.tif --threads -1", dir),
                        "--threads: must be zero or positive", 2);
  expect_one_line_error(run_skyview("svf " + good + " " + dir + "/o.tif --far-lines 3", dir), "--far-lines", 2);
  EXPECT_FALSE(std::filesystem::exists(dir + "/o.tif"));
}

// An option the run would not use is refused, not ignored: the user asked a different question.
TEST_F(CliErrors, OptionsTheRunWouldNotUseAreRefused) {
  const std::string o = " " + dir + "/o.tif";
  const std::pair<std::string, std::string> refused[] = {
      {"svf " + good + o + " --rays 1024", "--rays applies only to --method raycast (this run uses sweep)"},
      {"svf " + good + o + " --method march --samples 8",
       "--samples applies only to --method sampled, or sweep at unlimited radius (this run uses march)"},
      {"svf " + good + o + " --radius 10 --samples 7",
       "--samples applies only to --method sampled, or sweep at unlimited radius (this run uses sweep with --radius "
       "10)"},
      {"svf " + good + o + " --curvature off --refraction 0.2",
       "--refraction applies only to runs with Earth curvature"},
      {"svf " + good + o + " --method raycast --refraction 0.2",
       "--refraction applies only to runs with Earth curvature (--curvature on or auto; the ray cast models none) "
       "(this run uses raycast)"},
      {"svf " + good + o + " --directions 2048 --check-cells 10",
       "--check-cells measures against the run's own sectors, at most 1024 (this run has --directions 2048)"},
      {"svf " + good + o + " --method raycast --seed 3", "--seed applies only to --method sampled"},
      {"svf " + good + o + " --max-error 0.02 --directions 64",
       "--directions applies only to runs without --max-error"},
      {"svf " + good + o + " --max-error 0.02 --method march", "--method applies only to runs without --max-error"},
      {"svf " + good + o + " --max-error 0.02 --far-lines 1", "--far-lines applies only to runs without --max-error"},
      {"svf " + good + o + " --far-lines 1 --radius 50",
       "--far-lines applies only to --method sweep at unlimited radius (this run uses sweep with --radius 50)"},
      {"horizon " + good + o + " --method march --far-lines 2",
       "--far-lines applies only to --method sweep at unlimited radius (this run uses march)"},
      {"horizon " + good + o + " --method raycast --rays 64", "--rays applies only to skyview svf"},
      {"synth lidar " + dir + "/l.las -of GTiff", "--of applies only to the raster kinds"}};
  for (const auto& [args, message] : refused) expect_one_line_error(run_skyview(args, dir), message);
  EXPECT_FALSE(std::filesystem::exists(dir + "/o.tif"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/l.las"));
  // With --curvature auto (the default) it is a request for rasters where curvature counts: on
  // this small one it runs, and says the refraction went unused.
  const RunResult unused = run_skyview("svf " + good + o + " --refraction 0.2 --directions 4", dir);
  EXPECT_EQ(unused.exit_code, 0) << unused.err;
  EXPECT_NE(unused.err.find("Warning: --refraction has no effect: --curvature auto left Earth curvature off"),
            std::string::npos)
      << unused.err;
  std::filesystem::remove(dir + "/o.tif");
  EXPECT_EQ(run_skyview("svf " + good + o + " --method raycast --rays 16 --directions 4", dir).exit_code, 0);
}

// A file's name must say the format it is written in, and a format that cannot hold the bands is
// refused before the work, not after it.
TEST_F(CliErrors, OutputsMustBeWritableInTheirFormatBeforeTheWork) {
  expect_one_line_error(run_skyview("svf " + good + " " + dir + "/o.tif --preview " + dir + "/p.jpg", dir),
                        "must end in .png");
  expect_one_line_error(run_skyview("synth lidar " + dir + "/l.tif", dir), "must end in .las");
  expect_one_line_error(run_skyview("synth footprints " + dir + "/f.tif", dir),
                        "must end in one of .geojson, .json, .gpkg, .shp");
  const RunResult r = run_skyview("svf " + good + " " + dir + "/o.asc -of AAIGrid", dir);
  expect_one_line_error(r, "GDAL format 'AAIGrid' cannot write 5 float32 bands: AAIG driver doesn't support 5 bands");
  EXPECT_EQ(r.err.find("vsimem"), std::string::npos) << r.err;
  // XYZ writes only the first band, with a warning: counted back from the probe.
  expect_one_line_error(run_skyview("svf " + good + " " + dir + "/o.xyz -of XYZ", dir),
                        "GDAL format 'XYZ' keeps 1 of 5 float32 bands");
  // Formats created band by band that hold one band: SAGA says so, GTX keeps one silently. Until
  // Dec 3 both were found out only when the run's bands were written.
  expect_one_line_error(run_skyview("svf " + good + " " + dir + "/o.sdat -of SAGA", dir),
                        "GDAL format 'SAGA' cannot write 5 float32 bands: SAGA Binary Grid only supports 1 band");
  expect_one_line_error(run_skyview("svf " + good + " " + dir + "/o.gtx -of GTX", dir), "GDAL format 'GTX' ");
  EXPECT_EQ(run_skyview("svf " + good + " " + dir + "/o.sdat -of SAGA --products svf", dir).exit_code, 0);
  EXPECT_EQ(run_skyview("svf " + good + " " + dir + "/o.asc -of AAIGrid --products svf", dir).exit_code, 0);
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    EXPECT_EQ(e.path().filename().string().find("skyview-tmp"), std::string::npos) << e.path();
  }
}

// Runs whose every cell would come out blank or open are refused instead of written.
TEST_F(CliErrors, RunsThatCouldOnlyGiveBlankOrOpenSkiesAreRefused) {
  expect_one_line_error(run_skyview("svf " + good + " " + dir + "/o.tif --edge nodata", dir),
                        "which with an unlimited radius is every cell");
  // The pit raster is 21 m across: no 11 m circle fits in it, a 10 m one fits at its centre only
  // (9.999: the raster's CRS measures on the ellipsoid, a hair off whole metres).
  expect_one_line_error(run_skyview("horizon " + good + " " + dir + "/o.tif --edge nodata --radius 11", dir),
                        "which with --radius 11 is every cell of this raster");
  EXPECT_EQ(run_skyview("svf " + good + " " + dir + "/o.tif --edge nodata --radius 9.999", dir).exit_code, 0);
  std::filesystem::remove(dir + "/o.tif");
  expect_one_line_error(run_skyview("svf " + good + " " + dir + "/o.tif --method sampled --radius 1e30", dir),
                        "every sample of the sampled method beyond the raster");
  EXPECT_FALSE(std::filesystem::exists(dir + "/o.tif"));
}

// Heights packed as integers with a scale and an offset (value = raw * scale + offset) are read
// unpacked; their nodata is a raw value.
TEST(PackedRasters, ScaleAndOffsetAreApplied) {
  const std::string dir = temp_dir("packed"), path = dir + "/packed.tif";
  {
    GDALAllRegister();
    GDALDriver* gtiff = GetGDALDriverManager()->GetDriverByName("GTiff");
    GDALDatasetUniquePtr ds(gtiff->Create(path.c_str(), 3, 2, 1, GDT_Int16, nullptr));
    ASSERT_TRUE(ds);
    const GeoReference g = local_grid(3, 2, 1.0);
    double gt[6];
    std::copy(g.geotransform.begin(), g.geotransform.end(), gt);
    ds->SetGeoTransform(gt);
    GDALRasterBand* band = ds->GetRasterBand(1);
    band->SetScale(0.01);
    band->SetOffset(100.0);
    band->SetNoDataValue(-32768);
    std::int16_t raw[6] = {0, 150, -200, 12345, -32768, 7};
    ASSERT_EQ(band->RasterIO(GF_Write, 0, 0, 3, 2, raw, 3, 2, GDT_Int16, 0, 0), CE_None);
  }
  const Terrain t = read_terrain(path, ReadOptions{});
  const double want[6] = {100.0, 101.5, 98.0, 223.45, std::nan(""), 100.07};
  for (int i = 0; i < 6; ++i) {
    const double got = t.base_height + t.heights(i % 3, i / 3);
    if (std::isnan(want[i])) {
      EXPECT_TRUE(std::isnan(t.heights(i % 3, i / 3))) << i;
    } else {
      EXPECT_NEAR(got, want[i], 1e-4) << i;
    }
  }
}

// `skyview horizon` writes each band as the method finds it (the sweep hands directions over one at
// a time): every band must be its direction's horizons, in degrees.
TEST_F(CliErrors, HorizonBandsAreTheEnginesDirections) {
  const Terrain t = read_terrain(good, {});
  for (const char* method : {"sweep", "march"}) {
    const std::string out = dir + "/h_" + method + ".tif";
    ASSERT_EQ(
        run_skyview(std::string("horizon ") + good + " " + out + " --directions 16 --method " + method, dir).exit_code,
        0);
    HorizonParams p;
    p.directions = 16;
    HorizonField field;
    ProgressCounter progress;
    make_horizon_engine(method, p)->compute(t, Window::whole(t), field, progress);
    GDALDatasetUniquePtr ds(GDALDataset::Open(out.c_str(), GDAL_OF_RASTER));
    ASSERT_EQ(ds->GetRasterCount(), 16);
    std::vector<float> band(field.cells());
    for (int k = 0; k < 16; ++k) {
      ASSERT_EQ(ds->GetRasterBand(k + 1)->RasterIO(GF_Read, 0, 0, t.width(), t.height(), band.data(), t.width(),
                                                   t.height(), GDT_Float32, 0, 0),
                CE_None);
      for (std::size_t i = 0; i < band.size(); ++i) {
        ASSERT_EQ(band[i], static_cast<float>(field.upper_at(i, k) * 180.0 / M_PI)) << method << " band " << k;
      }
    }
  }
}

// --products writes the bands asked for, in that order, with the values of the full run (the
// horizons do not depend on whether the lowest angles are walked too).
TEST_F(CliErrors, ProductsChooseTheBands) {
  const std::string all = dir + "/all.tif", two = dir + "/two.tif";
  ASSERT_EQ(run_skyview("svf " + good + " " + all + " --directions 16", dir).exit_code, 0);
  ASSERT_EQ(run_skyview("svf " + good + " " + two + " --directions 16 --products sky_visibility,svf", dir).exit_code,
            0);
  GDALDatasetUniquePtr a(GDALDataset::Open(all.c_str(), GDAL_OF_RASTER));
  GDALDatasetUniquePtr b(GDALDataset::Open(two.c_str(), GDAL_OF_RASTER));
  ASSERT_TRUE(a && b);
  ASSERT_EQ(b->GetRasterCount(), 2);
  EXPECT_STREQ(b->GetRasterBand(1)->GetDescription(), "sky_visibility");
  EXPECT_STREQ(b->GetRasterBand(2)->GetDescription(), "svf");
  const int n = a->GetRasterXSize() * a->GetRasterYSize();
  std::vector<float> va(n), vb(n);
  for (auto [band_all, band_two] : {std::pair{3, 1}, std::pair{1, 2}}) {
    ASSERT_EQ(a->GetRasterBand(band_all)->RasterIO(GF_Read, 0, 0, 21, 21, va.data(), 21, 21, GDT_Float32, 0, 0),
              CE_None);
    ASSERT_EQ(b->GetRasterBand(band_two)->RasterIO(GF_Read, 0, 0, 21, 21, vb.data(), 21, 21, GDT_Float32, 0, 0),
              CE_None);
    EXPECT_EQ(va, vb) << "band " << band_all;
  }
  expect_one_line_error(run_skyview("svf " + good + " " + dir + "/o.tif --products svf,tilt", dir),
                        "unknown product 'tilt'", 2);
  expect_one_line_error(run_skyview("svf " + good + " " + dir + "/o.tif --products svf,svf", dir), "given twice", 2);
}

}  // namespace
