// skyview dsm: one height raster from DEMs, LiDAR point clouds and building footprints.
#include <algorithm>
#include <cstdio>
#include <sstream>

#include "command.h"
#include "preview_options.h"
#include "skyview/core/error.h"
#include "skyview/core/version.h"
#include "skyview/dsm/dsm_builder.h"
#include "skyview/raster/raster_io.h"

namespace skyview::cli {
namespace {

// Why a run burned none of the footprints it was given: a DSM without its buildings is not what
// was asked for (the grid even grows to their extent).
std::string unburned_message(const DsmOptions& dsm, const DsmReport& rep) {
  std::string why;
  if (dsm.height_field.empty() && dsm.points.empty())
    why = "they have no height: give --height-field (the attribute holding it) or --points";
  else if (dsm.height_field.empty())
    why = "no returns of the point clouds fall inside them, and no --height-field gives their height";
  else
    why = "their " + dsm.height_field + " is empty, or is a height above terrain where there is none (off the DEM)";
  return "none of the " + std::to_string(rep.footprints_skipped) + " footprints of '" + dsm.footprints +
         "' was burned (all skipped): " + why + "; --allow-unburned writes the DSM without them";
}

Runner setup(CLI::App& app) {
  struct Options {
    DsmOptions dsm;
    std::string output, dtm, classes;
    std::vector<double> te;
    OutputOptions out;
    PreviewOptions preview;
    bool allow_unburned = false;
  };
  auto o = std::make_shared<Options>();
  app.add_option("output", o->output, "Output height raster")->required();
  app.add_option("--dem", o->dsm.dems, "Terrain raster(s), any GDAL format and CRS (bilinear)");
  app.add_option("--points", o->dsm.points,
                 "Point cloud(s): LAS 1.0-1.4, PLY, PCD, or x y z text (.xyz/.txt/.csv/.pts)");
  app.add_option("--s_srs", o->dsm.s_srs,
                 "CRS of the point clouds (default: each file's own; PLY/PCD/text carry none and are else taken to be "
                 "in the output CRS)");
  app.add_option("--footprints", o->dsm.footprints, "Building footprints, any OGR polygon layer");
  app.add_option("--height-field", o->dsm.height_field,
                 "Footprint height attribute (above the lowest terrain under it: a flat top)");
  app.add_option("--base-field", o->dsm.base_field, "Footprint base height attribute (absolute)");
  app.add_flag("--absolute-heights", o->dsm.absolute_heights, "The height field is absolute, not above the terrain");
  app.add_option("--res", o->dsm.res, "Cell size in output CRS units (default: the DEM's, else 1)")
      ->check(positive_number());
  app.add_option("--t_srs", o->dsm.t_srs, "Output CRS (default: the first input's)");
  app.add_option("--te", o->te, "Output extent xmin ymin xmax ymax")->expected(4);
  app.add_option("--stat", o->dsm.stat, "Per-cell statistic of the returns: max, mean, min, idw")
      ->check(CLI::IsMember({"max", "mean", "min", "idw"}))
      ->capture_default_str();
  app.add_option("--idw-radius", o->dsm.idw_radius, "IDW: returns within this many cells of a cell centre")
      ->check(positive_number())
      ->capture_default_str();
  app.add_option("--idw-power", o->dsm.idw_power, "IDW: weight 1/distance^power")
      ->check(positive_number())
      ->capture_default_str();
  app.add_option("--classes", o->classes, "Comma-separated LAS classes to keep (e.g. 2,6)");
  app.add_flag("--ground-only", o->dsm.ground_only,
               "Keep ground returns: class 2, or PCL's progressive morphological filter for unclassified clouds");
  app.add_option("--ground-window", o->dsm.ground_window, "Morphological filter: largest window (m), > widest building")
      ->check(positive_number())
      ->capture_default_str();
  app.add_option("--ground-slope", o->dsm.ground_slope, "Morphological filter: terrain slope (rise over run)")
      ->check(positive_number())
      ->capture_default_str();
  app.add_flag("--denoise", o->dsm.denoise, "Remove isolated returns (birds, multipath) with PCL's statistical filter");
  app.add_option("--denoise-k", o->dsm.denoise_k, "Denoise: neighbours per return")
      ->check(positive_number())
      ->capture_default_str();
  app.add_option("--denoise-sigma", o->dsm.denoise_sigma, "Denoise: standard deviations beyond the mean distance")
      ->check(positive_number())
      ->capture_default_str();
  app.add_flag("--fill", o->dsm.fill, "Close nodata holes (GDAL fill-nodata)");
  app.add_option("--fill-distance", o->dsm.fill_distance,
                 "How far, in cells, a nodata cell looks for heights to interpolate from (GDAL's search distance): "
                 "cells farther than this from any height stay nodata")
      ->check(positive_number())
      ->capture_default_str();
  app.add_option("--z-scale", o->dsm.z_scale,
                 "Metres per height unit of the DEMs (0.3048 for feet); default: each DEM's band unit or vertical "
                 "CRS, else metres if its CRS is in metres or degrees")
      ->check(positive_number());
  app.add_option("--footprint-z-scale", o->dsm.footprint_z_scale,
                 "Metres per unit of --height-field and --base-field (0.3048 for feet); default: metres, refused "
                 "where the footprints' CRS is in another unit")
      ->check(positive_number());
  app.add_option("--points-z-scale", o->dsm.points_z_scale,
                 "Metres per z unit of the clouds; default: each cloud's vertical CRS or stated unit, else its "
                 "CRS's unit (x, y and z share one CRS)")
      ->check(positive_number());
  app.add_option("--dtm", o->dtm, "Also write the terrain here: the warped DEMs, else the clouds' bare earth");
  app.add_flag("--allow-unburned", o->allow_unburned,
               "Write the DSM even when none of the footprints could be burned (else an error: a wrong field or no "
               "heights)");
  add_preview_options(app, o->preview, "Also write a PNG of the height band, or --preview-band's (terrain_height)");
  add_output_options(app, o->out);
  app.footer(
      "DSM = max(terrain, buildings, gridded returns) cell by cell. A footprint covers the cells whose centre "
      "lies inside it; a footprint without height takes the 90th percentile of the returns inside it. Without a "
      "DEM, --dtm and footprint heights above the terrain use the clouds' ground returns (class 2, else the "
      "morphological filter), holes filled.");
  return [o, &app] {
    const RunSummary summary("dsm");
    std::vector<std::string> inputs = o->dsm.dems;
    inputs.insert(inputs.end(), o->dsm.points.begin(), o->dsm.points.end());
    inputs.push_back(o->dsm.footprints);
    check_outputs_apart({o->output, o->dtm, o->preview.path}, inputs);
    std::vector<std::string> band_names{"height"};
    if (!o->dtm.empty()) band_names.push_back("terrain_height");
    const std::size_t drawn = check_preview_options(app, o->preview, band_names);
    if (!o->preview.path.empty()) check_output_writable(o->preview.path, o->out.overwrite);
    check_output_writable(o->output, o->out.overwrite);
    check_output_format(o->output, o->out.format, 1, o->out.creation_options);
    if (!o->dtm.empty()) {
      check_output_writable(o->dtm, o->out.overwrite);
      check_output_format(o->dtm, o->out.format, 1, o->out.creation_options);
    }
    o->dsm.want_dtm = !o->dtm.empty();
    if (!o->te.empty()) o->dsm.te = std::array<double, 4>{o->te[0], o->te[1], o->te[2], o->te[3]};
    // LAS classes are 0..255; "1,,2", "2x" and an empty list are typing errors, not filters.
    if (app.count("--classes") > 0 && o->classes.empty())
      throw UsageError("--classes is empty: give classes, or leave it out");
    std::stringstream in(o->classes);
    for (std::string item; std::getline(in, item, ',');) {
      std::size_t used = 0;
      int c = -1;
      try {
        c = std::stoi(item, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0 || used != item.size())
        throw UsageError("--classes takes comma-separated integers, not '" + item + "'");
      if (c < 0 || c > 255) throw UsageError("--classes: class " + item + " is outside the LAS classes 0 to 255");
      o->dsm.classes.push_back(c);
    }
    const DsmResult r = build_dsm(o->dsm);
    const DsmReport& rep = r.report;
    for (const std::string& w : rep.warnings) std::fprintf(stderr, "Warning: %s\n", w.c_str());
    if (!o->dsm.footprints.empty() && rep.footprints_burned + rep.footprints_from_cloud == 0 && !o->allow_unburned)
      throw Error(unburned_message(o->dsm, rep));
    WriteOptions wo;
    wo.format = o->out.format;
    wo.creation_options = o->out.creation_options;
    wo.overwrite = o->out.overwrite;
    wo.metadata = {{"SKYVIEW_VERSION", version()},
                   {"SKYVIEW_COMMAND", command_line()},
                   {"COMBINATION_RULE", "max(terrain, buildings, gridded returns)"},
                   {"POINT_STATISTIC", o->dsm.stat},
                   {"POINTS_READ", std::to_string(rep.points_read)},
                   {"POINTS_USED", std::to_string(rep.points_used)},
                   {"POINTS_REMOVED_AS_NOISE", std::to_string(rep.points_removed_as_noise)},
                   // Which returns were taken as ground, where any were: "all returns" read as if
                   // every return had been, with --classes 6 too.
                   {"GROUND_FROM", rep.ground_source.empty() ? "none (no ground asked for)" : rep.ground_source},
                   {"CELLS_FILLED", std::to_string(rep.cells_filled)},
                   {"FOOTPRINTS_BURNED", std::to_string(rep.footprints_burned)},
                   {"FOOTPRINTS_FROM_CLOUD", std::to_string(rep.footprints_from_cloud)},
                   {"FOOTPRINTS_REPAIRED", std::to_string(rep.footprints_repaired)},
                   {"FOOTPRINTS_SKIPPED", std::to_string(rep.footprints_skipped)},
                   {"FOOTPRINTS_NOT_POLYGONS", std::to_string(rep.footprints_not_polygons)}};
    std::string units;
    for (const std::string& u : rep.height_units) units += (units.empty() ? "" : "; ") + u;
    if (!units.empty()) wo.metadata["HEIGHT_UNITS"] = units;
    write_bands(o->output, r.dsm.width(), r.dsm.height(), r.georef, {{"height", "metre", r.dsm.data(), {}}}, wo);
    if (!o->dtm.empty() && r.dtm.size() > 0) {
      // The terrain's own provenance: the DSM's statistic, fills and footprint counts say nothing of it.
      WriteOptions dtm = wo;
      dtm.metadata = {
          {"SKYVIEW_VERSION", version()},
          {"SKYVIEW_COMMAND", command_line()},
          {"TERRAIN_FROM", o->dsm.dems.empty() ? "the mean of the clouds' ground returns per cell (GROUND_FROM), holes "
                                                 "filled"
                                               : "the DEMs warped onto the grid (bilinear), later ones filling earlier "
                                                 "ones' nodata"}};
      if (o->dsm.dems.empty()) {
        dtm.metadata["GROUND_FROM"] = wo.metadata["GROUND_FROM"];
        dtm.metadata["POINTS_READ"] = wo.metadata["POINTS_READ"];
      }
      if (wo.metadata.count("HEIGHT_UNITS")) dtm.metadata["HEIGHT_UNITS"] = wo.metadata["HEIGHT_UNITS"];
      write_bands(o->dtm, r.dtm.width(), r.dtm.height(), r.georef, {{"terrain_height", "metre", r.dtm.data(), {}}},
                  dtm);
    }
    {
      char what[512];
      std::snprintf(what, sizeof what,
                    "%dx%d cells; %llu of %llu points used (%llu removed as noise); %d footprints burned, %d from the "
                    "cloud, %d repaired, %d skipped; %lld cells filled",
                    r.dsm.width(), r.dsm.height(), static_cast<unsigned long long>(rep.points_used),
                    static_cast<unsigned long long>(rep.points_read),
                    static_cast<unsigned long long>(rep.points_removed_as_noise), rep.footprints_burned,
                    rep.footprints_from_cloud, rep.footprints_repaired, rep.footprints_skipped,
                    static_cast<long long>(rep.cells_filled));
      if (!o->preview.path.empty()) {
        const bool terrain = drawn == 1;
        write_preview(o->preview, terrain ? r.dtm : r.dsm,
                      {band_names[drawn], "metre", terrain ? o->dtm : o->output, r.georef, {}, {}}, o->out.overwrite);
      }
      summary.print(what, o->out.quiet);
    }
    // A sparse cloud on the default 1-unit grid (106 returns over 3249 x 4386 cells of a foot) writes
    // a raster of holes: say so and what to change.
    const auto holding =
        std::count_if(r.dsm.values().begin(), r.dsm.values().end(), [](float v) { return !std::isnan(v); });
    const double held = static_cast<double>(holding) / static_cast<double>(r.dsm.size());
    if (!o->dsm.points.empty() && !o->dsm.fill && held < 0.1) {
      std::fprintf(stderr,
                   "Warning: only %.2g%% of the %dx%d cells hold a height: the grid is much finer than the returns; "
                   "give a coarser --res, or --fill\n",
                   100.0 * held, r.dsm.width(), r.dsm.height());
    }
    if (rep.footprints_not_polygons > 0) {
      std::fprintf(stderr, "Warning: %d %s of '%s' %s no polygon (points, lines or no geometry) and %s left out\n",
                   rep.footprints_not_polygons, rep.footprints_not_polygons == 1 ? "feature" : "features",
                   o->dsm.footprints.c_str(), rep.footprints_not_polygons == 1 ? "has" : "have",
                   rep.footprints_not_polygons == 1 ? "was" : "were");
    }
    if (rep.footprints_skipped > 0) {
      std::fprintf(stderr,
                   "Warning: %d %s skipped (a height above the terrain where there is none, off the DEM; "
                   "no height and no returns; invalid, or covering no cell centre)\n",
                   rep.footprints_skipped, rep.footprints_skipped == 1 ? "footprint was" : "footprints were");
    }
    return 0;
  };
}

const Registration reg("dsm", "Height raster from DEMs, point clouds (LAS, PLY, PCD, XYZ) and building footprints",
                       setup);

}  // namespace
}  // namespace skyview::cli
