#pragma once
// What the tiled-run tests share: a small city raster on disk, and bit-for-bit comparison of two
// outputs band by band.
#include <gdal_priv.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "core/cli_run.h"
#include "core/test_support.h"

namespace skyview::test {

// mpirun with two ranks of this build's skyview (OpenMPI refuses root without --allow-run-as-root,
// and CI runs as root).
inline std::string mpirun_two_ranks() {
  return "mpirun --allow-run-as-root --oversubscribe -np 2 " + std::string(SKYVIEW_EXE);
}

// The same svf run in one process into dir/one.vrt (tiles in dir/one), which must succeed, and
// under mpirun into dir/two.vrt (tiles in dir/two), whose result is returned.
inline RunResult svf_once_and_under_mpirun(const std::string& dsm, const std::string& options, const std::string& dir) {
  const RunResult one =
      run_skyview("svf " + dsm + " " + dir + "/one.vrt" + options + " --tiles-dir " + dir + "/one", dir);
  EXPECT_EQ(one.exit_code, 0) << one.err;
  return run_executable(mpirun_two_ranks(),
                        "svf " + dsm + " " + dir + "/two.vrt" + options + " --tiles-dir " + dir + "/two", dir);
}

// A 67 x 53 city on 1 m cells with a metric CRS and a few nodata cells, written to `dir`/dsm.tif:
// sizes that few tile sizes divide.
inline std::string write_small_city(const std::string& dir, int width = 67, int height = 53) {
  Terrain t = with_local_metric_crs(rasterize(synthetic_city(5), width, height, local_grid(width, height, 1.0)));
  for (int r = 20; r < 24; ++r) t.heights(30, r) = std::numeric_limits<float>::quiet_NaN();
  const std::string path = dir + "/dsm.tif";
  write_terrain(path, t, {});
  return path;
}

inline int band_count(const std::string& path) {
  init_gdal();
  GDALDataset* ds = GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY);
  if (!ds) return 0;
  const int n = ds->GetRasterCount();
  GDALClose(ds);
  return n;
}

inline std::string metadata_item(const std::string& path, const char* key) {
  init_gdal();
  GDALDataset* ds = GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY);
  if (!ds) return "";
  const char* v = ds->GetMetadataItem(key);
  std::string out = v ? v : "";
  GDALClose(ds);
  return out;
}

// TILES_BY_RANK of a --tiles-dir run's mosaic ("rank 0: 12, rank 1: 8"): the tiles each rank
// computed; empty where it is absent (one process).
inline std::vector<int> tiles_by_rank(const std::string& vrt) {
  std::vector<int> counts;
  const std::string text = metadata_item(vrt, "TILES_BY_RANK");
  for (std::size_t at = text.find(": "); at != std::string::npos; at = text.find(": ", at + 1))
    counts.push_back(std::stoi(text.substr(at + 2)));
  return counts;
}

// Every band of `a` holds the same bits as `b`'s (NaN where it has NaN), with the same name.
inline ::testing::AssertionResult same_bands(const std::string& a, const std::string& b) {
  const int n = band_count(b);
  if (n == 0 || band_count(a) != n) return ::testing::AssertionFailure() << band_count(a) << " bands against " << n;
  for (int k = 1; k <= n; ++k) {
    const RasterBand x = read_band(a, k), y = read_band(b, k);
    if (x.description != y.description)
      return ::testing::AssertionFailure() << "band " << k << ": " << x.description << " against " << y.description;
    if (x.values.width() != y.values.width() || x.values.height() != y.values.height())
      return ::testing::AssertionFailure() << "band " << k << " sizes differ";
    for (std::size_t i = 0; i < x.values.size(); ++i) {
      const float u = x.values.values()[i], v = y.values.values()[i];
      if (std::isnan(u) != std::isnan(v) || (!std::isnan(u) && std::memcmp(&u, &v, sizeof u) != 0)) {
        return ::testing::AssertionFailure()
               << "band " << k << " (" << y.description << ") cell " << i % x.values.width() << ", "
               << i / x.values.width() << ": " << u << " against " << v;
      }
    }
  }
  return ::testing::AssertionSuccess();
}

// Band `band`'s largest |difference| between `a` and `b` over every cell; infinite where one is
// nodata and the other not.
inline double max_difference(const std::string& a, const std::string& b, int band) {
  const RasterBand x = read_band(a, band), y = read_band(b, band);
  double worst = 0;
  for (std::size_t i = 0; i < x.values.size(); ++i) {
    const float u = x.values.values()[i], v = y.values.values()[i];
    if (std::isnan(u) != std::isnan(v)) return INFINITY;
    if (!std::isnan(u)) worst = std::max(worst, std::abs(static_cast<double>(u) - v));
  }
  return worst;
}

// The real LiDAR terrain tile of ../shared/sample_data (tests skip where it is absent).
inline std::string real_terrain() { return std::string(SKYVIEW_SHARED_DIR) + "/sample_data/terrain/TM1_564_146.tif"; }

// Runs `command` whole into dir/whole.tif and tiled into dir/tiled.tif (both with `common`, which
// makes every crossing exact, so that what differs is the far field alone); returns the tiled path.
inline std::string whole_and_tiled(const std::string& command, const std::string& dsm, const std::string& dir,
                                   const std::string& common, int tile, double far_error) {
  const RunResult whole = run_skyview(command + " " + dsm + " " + dir + "/whole.tif --overwrite" + common, dir);
  EXPECT_EQ(whole.exit_code, 0) << whole.err;
  const std::string out = dir + "/tiled.tif";
  const RunResult r = run_skyview(command + " " + dsm + " " + out + " --overwrite" + common + " --tile-size " +
                                      std::to_string(tile) + " --far-field-error " + std::to_string(far_error),
                                  dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_GT(std::stoi(metadata_item(out, "TILES")), 1);
  EXPECT_LE(std::stod(metadata_item(out, "FAR_FIELD_BOUND_SVF")), far_error);
  EXPECT_EQ(metadata_item(out, "RADIUS_M").rfind("unlimited", 0), 0u);
  return out;
}

}  // namespace skyview::test
