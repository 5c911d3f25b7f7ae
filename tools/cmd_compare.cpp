// skyview compare: how far one raster band is from a reference on the same grid (another tool's
// svf against skyview's ray-cast reference, a run against an earlier one), in the statistics
// `skyview bench` reports.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <ogr_spatialref.h>
#include <nlohmann/json.hpp>

#include "command.h"
#include "skyview/core/error.h"
#include "skyview/raster/raster_io.h"
#include "skyview/sky_view/error_stats.h"
#include "skyview/sky_view/sky_view.h"

namespace skyview::cli {
namespace {

// Rasters compare cell by cell only on one grid: the same size and, where both have one, the same
// geotransform (to a millionth of a cell).
struct GridOf {
  const std::string& path;
  const Grid<float>& values;
  const GeoReference& georef;
};

void check_same_grid(const GridOf& a, const GridOf& b) {
  const int wa = a.values.width(), ha = a.values.height(), wb = b.values.width(), hb = b.values.height();
  if (wa != wb || ha != hb) {
    throw Error("'" + a.path + "' is " + std::to_string(wa) + " x " + std::to_string(ha) + " cells but '" + b.path +
                "' is " + std::to_string(wb) + " x " + std::to_string(hb) +
                "; resample one onto the other's grid first");
  }
  if (!a.georef.crs_wkt.empty() && !b.georef.crs_wkt.empty()) {
    OGRSpatialReference sa, sb;
    sa.importFromWkt(a.georef.crs_wkt.c_str());
    sb.importFromWkt(b.georef.crs_wkt.c_str());
    if (!sa.IsSame(&sb)) {
      throw Error("'" + a.path + "' and '" + b.path + "' are in different CRSs; warp one onto the other's grid first");
    }
  }
  if (!a.georef.has_geotransform || !b.georef.has_geotransform) return;
  const auto& ga = a.georef.geotransform;
  const auto& gb = b.georef.geotransform;
  const double cell = std::max(std::hypot(ga[1], ga[4]), std::hypot(ga[2], ga[5]));
  for (int i = 0; i < 6; ++i) {
    if (std::abs(ga[i] - gb[i]) > 1e-6 * cell) {
      throw Error("'" + a.path + "' and '" + b.path + "' have the same size but not the same geotransform");
    }
  }
}

Runner setup(CLI::App& app) {
  struct Options {
    std::string value, reference, dem, json;
    int band = 1, ref_band = 0;
    double scale = 1.0, offset = 0.0, threshold = 0.01, max_slope = -1.0;
    double z_scale = 0.0;  // of --dem; 0: from the raster
    bool quiet = false, overwrite = false;
  };
  auto o = std::make_shared<Options>();
  app.add_option("value", o->value, "Raster to judge")->required();
  app.add_option("reference", o->reference, "Reference raster on the same grid")->required();
  app.add_option("-b,--band", o->band, "Band of the raster to judge")->capture_default_str()->check(positive_number());
  app.add_option("--ref-band", o->ref_band, "Band of the reference (default: the same as -b)")
      ->check(positive_number());
  app.add_option("--scale", o->scale, "Multiply the judged values first (0.01 for percent)")
      ->capture_default_str()
      ->check(finite_number());
  app.add_option("--offset", o->offset, "Then add this")->capture_default_str()->check(finite_number());
  app.add_option("--threshold", o->threshold, "Report the share of cells off by more than this")
      ->capture_default_str()
      ->check(non_negative_number());
  app.add_option("--dem", o->dem, "Elevation raster on the same grid, for --max-slope");
  app.add_option("--z-scale", o->z_scale,
                 "Metres per height unit of --dem (0.3048 for feet); default: its band's unit or vertical CRS, else "
                 "metres if the CRS is in metres or degrees")
      ->check(positive_number());
  app.add_option("--max-slope", o->max_slope,
                 "Compare only cells whose ground slope on --dem is at most this (degrees); cells without a height in "
                 "--dem are left out too")
      ->check(number_in(0.0, 90.0));
  app.add_option("--json", o->json,
                 "Also write the statistics as JSON to this file ('-': standard output, the summary then on stderr)");
  app.add_flag("--overwrite", o->overwrite, "Replace an existing --json file");
  app.add_flag("-q,--quiet", o->quiet, "Print nothing but the JSON");
  app.footer(
      "Statistics of (value * scale + offset - reference) over the cells valid in both: RMSE, bias, 99th percentile "
      "and maximum of the absolute error, and the share of cells off by more than --threshold. "
      "--max-slope leaves out walls and steep cells, where tools that tilt svf by their own slope estimate (SAGA) "
      "disagree by definition rather than by method.");
  return [o] {
    if (o->max_slope >= 0.0 && o->dem.empty()) throw UsageError("--max-slope needs --dem, the elevation raster");
    if (!o->dem.empty() && o->max_slope < 0.0) throw UsageError("--dem is only read for --max-slope");
    const bool json_file = !o->json.empty() && o->json != "-";
    if (json_file) {
      check_outputs_apart({o->json}, {o->value, o->reference, o->dem});
      check_output_writable(o->json, o->overwrite);
    }
    const int ref_band = o->ref_band > 0 ? o->ref_band : o->band;
    RasterBand value = read_band(o->value, o->band);
    const RasterBand reference = read_band(o->reference, ref_band);
    check_same_grid({o->value, value.values, value.georef}, {o->reference, reference.values, reference.georef});
    // An infinite value would make every statistic inf or NaN: refused, as svf refuses one in heights.
    auto refuse_infinite = [](const std::string& path, int band, const Grid<float>& grid) {
      const auto& v = grid.values();
      const auto inf = std::find_if(v.begin(), v.end(), [](float x) { return std::isinf(x); });
      if (inf == v.end()) return;
      const auto i = inf - v.begin(), w = static_cast<std::ptrdiff_t>(grid.width());
      throw Error("band " + std::to_string(band) + " of '" + path + "' holds an infinite value at cell (" +
                  std::to_string(i % w) + ", " + std::to_string(i / w) + "); set it to the nodata value");
    };
    refuse_infinite(o->value, o->band, value.values);
    refuse_infinite(o->reference, ref_band, reference.values);
    // Openness in degrees against an svf, say: the statistics would be of nothing. Said even under -q
    // (it goes to stderr); --scale and --offset are how a deliberate conversion is given.
    if (!value.unit.empty() && !reference.unit.empty() && value.unit != reference.unit && o->scale == 1.0 &&
        o->offset == 0.0) {
      std::fprintf(stderr,
                   "Warning: the bands' units differ ('%s' against '%s'); --scale and --offset convert the first\n",
                   value.unit.c_str(), reference.unit.c_str());
    }
    for (float& v : value.values.values()) v = static_cast<float>(v * o->scale + o->offset);
    std::int64_t steep = 0, no_dem = 0;
    if (o->max_slope >= 0.0) {
      ReadOptions ro;
      ro.z_scale = o->z_scale;
      const Terrain dem = read_terrain(o->dem, ro);
      check_same_grid({o->value, value.values, value.georef}, {o->dem, dem.heights, dem.georef});
      const double limit = o->max_slope * M_PI / 180.0;
      for (int row = 0; row < dem.height(); ++row) {
        for (int col = 0; col < dem.width(); ++col) {
          float& v = value.values(col, row);
          // Counted only where both have a value: the others were never compared.
          if (std::isnan(v) || std::isnan(reference.values(col, row))) continue;
          if (!dem.valid(col, row)) {  // no height, no slope: not known to be flat enough
            v = std::numeric_limits<float>::quiet_NaN(), ++no_dem;
            continue;
          }
          double slope = 0, aspect = 0;
          horn_slope_aspect(dem, col, row, slope, aspect);
          if (slope > limit) v = std::numeric_limits<float>::quiet_NaN(), ++steep;
        }
      }
    }
    const ErrorStats e = compare_to_reference(value.values, reference.values, o->threshold);
    if (e.cells == 0 && steep + no_dem > 0) {
      throw Error("every cell valid in both is steeper than --max-slope " + CLI::detail::to_string(o->max_slope) +
                  " degrees or has no height in --dem (" + std::to_string(steep) + " and " + std::to_string(no_dem) +
                  " left out)");
    }
    if (e.cells == 0) throw Error("no cell is valid in both '" + o->value + "' and '" + o->reference + "'");
    if (!o->quiet) {
      std::string what =
          "band " + std::to_string(o->band) + " of " + o->value + " against band " + std::to_string(ref_band) +
          (reference.description.empty() ? "" : " (" + reference.description + ")") + " of " + o->reference;
      if (o->max_slope >= 0.0) {
        what += "; " + std::to_string(steep) + " cells steeper than " + CLI::detail::to_string(o->max_slope) +
                " degrees left out";
        if (no_dem > 0) what += ", and " + std::to_string(no_dem) + " without a height in " + o->dem;
      }
      // With the JSON on standard output the summary goes to stderr, so that the JSON parses.
      std::FILE* summary = o->json == "-" ? stderr : stdout;
      std::fprintf(summary, "%lld cells compared: %s\n", static_cast<long long>(e.cells), what.c_str());
      std::fprintf(summary, "rmse %.5f  bias %+.5f  p99 %.5f  max %.5f  share above %g: %.4f\n", e.rmse, e.bias, e.p99,
                   e.max_abs, e.threshold, e.share_above);
    }
    if (!o->json.empty()) {
      const nlohmann::json j = {
          {"value", {{"path", o->value}, {"band", o->band}, {"scale", o->scale}, {"offset", o->offset}}},
          {"reference", {{"path", o->reference}, {"band", ref_band}, {"description", reference.description}}},
          {"max_slope_degrees", o->max_slope >= 0.0 ? nlohmann::json(o->max_slope) : nlohmann::json()},
          {"left_out_steep", steep},
          {"left_out_no_dem_height", no_dem},
          {"cells", e.cells},
          {"rmse", e.rmse},
          {"bias", e.bias},
          {"p99_abs", e.p99},
          {"max_abs", e.max_abs},
          {"threshold", e.threshold},
          {"share_above", e.share_above}};
      if (json_file) {
        write_output_file(o->json, j.dump(2) + "\n", o->overwrite);
      } else {
        std::printf("%s\n", j.dump(2).c_str());
      }
    }
    return 0;
  };
}

const Registration reg("compare", "Error statistics of a raster band against a reference on the same grid", setup);

}  // namespace
}  // namespace skyview::cli
