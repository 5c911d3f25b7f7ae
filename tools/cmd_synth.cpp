// skyview synth: writes the synthetic and analytic test rasters (sample_dems/ is made with it).
#include "command.h"
#include "skyview/core/error.h"
#include "skyview/core/version.h"
#include "skyview/raster/raster_io.h"
#include "skyview/synthetic/synthetic.h"
#include "skyview/synthetic/synthetic_district.h"

#include <cpl_conv.h>
#include <ogr_spatialref.h>

#include <cmath>

namespace skyview::cli {
namespace {

Runner setup(CLI::App& app) {
  struct Options {
    std::string kind, output, crs = "EPSG:32633";
    int size = 401;
    double cell = 1.0, x0 = 500000.0, y0 = 6400000.0, base = 0.0;
    std::uint64_t seed = 1;
    double density = 2.0;
    int birds = 5;
    OutputOptions out;
  };
  auto o = std::make_shared<Options>();
  app.add_option("kind", o->kind,
                 "city, mountains, canyon, pit, plane (rasters); lidar (LAS) or footprints (vector) of a district")
      ->required()
      ->check(CLI::IsMember({"city", "mountains", "canyon", "pit", "plane", "lidar", "footprints"}));
  app.add_option("output", o->output, "Output raster, LAS or vector file")->required();
  app.add_option("--size", o->size, "Cells per side")->capture_default_str()->check(CLI::Range(3, 20000));
  app.add_option("--cell", o->cell, "Cell size in metres")->capture_default_str()->check(positive_number());
  app.add_option("--crs", o->crs, "CRS of the grid (projected, metres)")->capture_default_str();
  app.add_option("--origin", o->x0, "Easting of the grid centre")->capture_default_str()->check(finite_number());
  app.add_option("--northing", o->y0, "Northing of the grid centre")->capture_default_str()->check(finite_number());
  app.add_option("--seed", o->seed, "Random seed of the synthetic layout")->capture_default_str();
  app.add_option("--density", o->density, "lidar: returns per square metre")
      ->capture_default_str()
      ->check(positive_number());
  app.add_option("--birds", o->birds, "lidar: isolated noise returns high above the district")
      ->capture_default_str()
      ->check(non_negative_number());
  add_output_options(app, o->out);
  app.footer(
      "lidar and footprints describe the same district of size x cell metres around the origin: 3 x 3 blocks, "
      "the middle one with a courtyard, the north-east one without a height attribute, two trees, a few birds.");
  return [o, &app] {
    const bool raster = o->kind != "lidar" && o->kind != "footprints";
    if (o->kind == "lidar") require_extension(o->output, {".las"}, "the LAS output");
    if (o->kind == "footprints") require_extension(o->output, {".geojson", ".json", ".gpkg", ".shp"}, "the footprints");
    for (const char* name : {"--of", "--co"})
      refuse_unused(app, name, raster, "the raster kinds (city, mountains, canyon, pit, plane)");
    refuse_unused(app, "--density", o->kind == "lidar", "lidar");
    refuse_unused(app, "--birds", o->kind == "lidar", "lidar");
    // The analytic kinds have no random layout.
    refuse_unused(app, "--seed", o->kind != "canyon" && o->kind != "pit" && o->kind != "plane",
                  "city, mountains, lidar and footprints");
    ThreadLimit limit(o->out.threads);
    check_output_writable(o->output, o->out.overwrite);
    if (raster) check_output_format(o->output, o->out.format, 1, o->out.creation_options);
    GeoReference g = local_grid(o->size, o->size, o->cell);
    g.geotransform[0] += o->x0;
    g.geotransform[3] += o->y0;
    OGRSpatialReference srs;
    if (srs.SetFromUserInput(o->crs.c_str()) != OGRERR_NONE) throw Error("unknown CRS '" + o->crs + "'");
    if (!srs.IsProjected()) {
      throw UsageError("--crs must be a projected CRS in metres ('" + o->crs + "' is " +
                       (srs.IsGeographic() ? "geographic" : "not projected") + ")");
    }
    // --cell, --origin and the heights are metres: a CRS in feet would label them wrongly.
    const char* unit = nullptr;
    if (std::abs(srs.GetLinearUnits(&unit) - 1.0) > 1e-9) {
      throw UsageError("--crs must be a projected CRS in metres ('" + o->crs + "' is in " +
                       (unit ? unit : "unknown units") + ")");
    }
    if (srs.IsVertical() && std::abs(srs.GetTargetLinearUnits("VERT_CS", &unit) - 1.0) > 1e-9) {
      throw UsageError("--crs must have heights in metres ('" + o->crs + "' has heights in " +
                       (unit ? unit : "unknown units") + ")");
    }
    char* wkt = nullptr;
    srs.exportToWkt(&wkt);
    g.crs_wkt = wkt;
    CPLFree(wkt);
    if (o->kind == "lidar" || o->kind == "footprints") {
      const double side = o->size * o->cell;
      const SyntheticDistrict d = synthetic_district(o->x0 - 0.5 * side, o->y0 - 0.5 * side, side, o->seed);
      if (o->kind == "footprints") {
        write_district_footprints(o->output, d, g.crs_wkt, o->out.overwrite);
      } else {
        LasWriteOptions lo;
        lo.crs_wkt = g.crs_wkt;
        lo.offset[0] = std::round(d.x0), lo.offset[1] = std::round(d.y0);
        lo.scale[0] = lo.scale[1] = lo.scale[2] = 0.01;
        write_las(o->output, district_lidar(d, o->density, o->birds, o->seed), lo);
      }
      return 0;
    }
    HeightFunction f;
    if (o->kind == "city") f = synthetic_city(o->seed);
    if (o->kind == "mountains") f = synthetic_mountains(o->seed);
    if (o->kind == "canyon") f = street_canyon(20.0, 20.0);
    if (o->kind == "pit") f = circular_pit(20.0, 20.0);
    if (o->kind == "plane") f = tilted_plane(30.0 * M_PI / 180.0, 0.0);
    Terrain t = rasterize(f, o->size, o->size, g);
    WriteOptions wo;
    wo.format = o->out.format;
    wo.creation_options = o->out.creation_options;
    wo.overwrite = o->out.overwrite;
    wo.metadata = {{"SKYVIEW_VERSION", version()}, {"SKYVIEW_COMMAND", command_line()}, {"SYNTHETIC_KIND", o->kind}};
    write_terrain(o->output, t, wo);
    return 0;
  };
}

const Registration reg("synth", "Write a synthetic or analytic test raster (city, mountains, canyon, pit, plane)",
                       setup);

}  // namespace
}  // namespace skyview::cli
