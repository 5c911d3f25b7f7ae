// skyview fisheye-svf: the svf of a fish-eye photograph or sky mask.
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <memory>

#include "command.h"
#include "skyview/core/error.h"
#include "skyview/fisheye/fisheye_svf.h"
#include "skyview/raster/raster_io.h"

namespace skyview::cli {
namespace {

struct FisheyeSvfCliOptions {
  std::string image, projection = "equidistant", center, threshold = "otsu", classified;
  double radius = 0, fov = 180;
  int rings = 36;
  bool mask = false, json = false, overwrite = false, quiet = false;
};

int run(const CLI::App& app, const FisheyeSvfCliOptions& o) {
  FisheyeSvfOptions s;
  s.projection = projection_named(o.projection);
  s.field_of_view = o.fov;
  s.rings = o.rings;
  if (o.mask && app.count("--threshold")) throw Error("--mask reads an existing mask: leave out --threshold");
  s.threshold = o.mask ? SkyThreshold::mask : o.threshold == "blue" ? SkyThreshold::blue : SkyThreshold::otsu;
  if (o.center.empty() != !(o.radius > 0)) throw Error("give --center and --radius together, or neither");
  if (!o.center.empty()) {
    ImageCircle c;
    const std::size_t comma = o.center.find(',');
    char* end = nullptr;
    c.cx = std::strtod(o.center.c_str(), &end);
    const bool ok_x = comma != std::string::npos && end == o.center.c_str() + comma;
    c.cy = ok_x ? std::strtod(o.center.c_str() + comma + 1, &end) : NAN;
    if (!ok_x || *end != '\0' || !std::isfinite(c.cx) || !std::isfinite(c.cy))
      throw Error("--center must be two numbers CX,CY (pixels), not '" + o.center + "'");
    c.radius = o.radius;
    s.circle = c;
  }
  if (!o.classified.empty()) {
    require_extension(o.classified, {".png"}, "--classified");
    check_outputs_apart({o.classified}, {o.image});
    check_output_writable(o.classified, o.overwrite);
  }
  const FisheyeImage image = read_fisheye_image(o.image);
  const FisheyeSvfResult r = fisheye_svf(image, s);
  if (r.circle_found && r.circle.sectors < 8) {  // even under -q: the circle may be off
    std::fprintf(stderr,
                 "Warning: the image circle's rim showed in only %d of 12 sectors (dark at the rim?); check it with "
                 "--classified, or give --center and --radius\n",
                 r.circle.sectors);
  }
  if (r.fractions.coverage < 0.99) {
    std::fprintf(stderr,
                 "Warning: the 90 degree circle runs off the image: it holds %.1f%% of the hemisphere's svf weight, "
                 "and the values are of that part only\n",
                 100.0 * r.fractions.coverage);
  }
  if (!o.classified.empty()) write_classified_png(o.classified, image, r, o.overwrite);
  const SkyFractions& f = r.fractions;
  if (o.json) {
    nlohmann::ordered_json j;
    j["svf"] = f.svf;
    j["svf_annulus"] = f.svf_annulus;
    j["sky_visibility"] = f.sky_visibility;
    j["center"] = {r.circle.cx, r.circle.cy};
    j["radius"] = r.circle.radius;
    j["radius_90"] = r.frame.radius;
    j["circle"] = s.circle ? "given" : r.circle_found ? "found" : "inscribed";
    if (r.circle_found) j["circle_rms"] = r.circle.rms, j["circle_sectors"] = r.circle.sectors;
    j["projection"] = o.projection;
    j["field_of_view"] = o.fov;
    j["classification"] = o.mask ? "mask" : o.threshold;
    if (!o.mask) j["threshold"] = r.classification.threshold;
    j["rings"] = f.rings;
    j["coverage"] = f.coverage;
    j["pixels"] = f.pixels;
    j["sky_pixels"] = f.sky_pixels;
    std::printf("%s\n", j.dump().c_str());
  } else {
    std::printf("svf %.4f\nsvf_annulus %.4f (%d rings)\nsky_visibility %.4f\n", f.svf, f.svf_annulus, f.rings,
                f.sky_visibility);
    std::printf("circle %s: centre %.1f, %.1f, radius %.1f px (90 degrees at %.1f px)\n",
                s.circle         ? "given"
                : r.circle_found ? "found"
                                 : "inscribed",
                r.circle.cx, r.circle.cy, r.circle.radius, r.frame.radius);
  }
  if (!o.quiet) {
    std::fprintf(stderr, "fisheye-svf: svf %.4f from %lld pixels (%.1f%% sky) of '%s'\n", f.svf, f.pixels,
                 f.pixels ? 100.0 * f.sky_pixels / f.pixels : 0.0, o.image.c_str());
  }
  return 0;
}

Runner setup(CLI::App& app) {
  auto o = std::make_shared<FisheyeSvfCliOptions>();
  app.add_option("image", o->image, "Fish-eye photograph (JPEG, PNG, TIFF) or sky mask")->required();
  app.add_option("--projection", o->projection, "equidistant, equisolid, orthographic or stereographic")
      ->check(CLI::IsMember({"equidistant", "equisolid", "orthographic", "stereographic"}))
      ->capture_default_str();
  app.add_option("--center", o->center, "Centre of the image circle, pixels (column, row from the top left)")
      ->type_name("CX,CY");
  app.add_option("--radius", o->radius, "Radius of the image circle, pixels")->check(positive_number());
  app.add_option("--fov", o->fov, "Degrees across the image circle (190 for a Nikon FC-E9)")->capture_default_str();
  app.add_flag("--mask", o->mask, "The image is a sky mask: any non-zero pixel is sky; its circle is inscribed");
  app.add_option("--threshold", o->threshold,
                 "otsu: Otsu on the blue channel (clouds count as sky); blue: Otsu on the blue ratio B/(R+G+B) "
                 "(clear blue sky only)")
      ->check(CLI::IsMember({"otsu", "blue"}))
      ->capture_default_str();
  app.add_option("--rings", o->rings, "Rings of the annulus method (Steyn 1980)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  app.add_flag("--json", o->json, "Print one JSON object on stdout");
  app.add_option("--classified", o->classified, "Also write the photograph beside its classification, PNG");
  app.add_flag("--overwrite", o->overwrite, "Replace an existing --classified picture");
  app.add_flag("-q,--quiet", o->quiet, "No summary on stderr");
  app.footer(
      "A photograph's image circle is found where the lens's vignette meets the black border (a full-frame fish-eye "
      "has none: give --center and --radius); a mask's circle is the one inscribed in the image, as skyview "
      "fisheye draws it. svf is cosine-weighted with per-pixel weights from the projection; svf_annulus is "
      "Steyn's method over --rings rings of equal zenith angle; sky_visibility is the sky's share of the "
      "hemisphere's solid angle.");
  return [o, &app] { return run(app, *o); };
}

const Registration reg("fisheye-svf", "svf of a fish-eye photograph or sky mask", setup);

}  // namespace
}  // namespace skyview::cli
