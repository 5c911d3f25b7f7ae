// skyview render: a camera view of a 3-D scene with the two-scale sky visibility and the solar
// exposure of "Solar exposure of complex cities" (Sections 5 and 6) per pixel, as an image of
// bands (no geotransform: a pixel grid) and a false-colour preview.
#include <cmath>
#include <cstdio>
#include <optional>

#include "command.h"
#include "preview_options.h"
#include "render_exposure_reference.h"
#include "render_points.h"
#include "render_sun.h"
#include "scene_options.h"
#include "skyview/core/error.h"
#include "skyview/core/number_text.h"
#include "skyview/preview/raster_preview.h"
#include "skyview/raster/band_writer.h"
#include "skyview/raster/output_checks.h"
#include "skyview/render/svf_reference.h"
#include "skyview/render/two_scale_visibility.h"
#include "skyview/sky/exposure_pyramid.h"
#include "skyview/sky/skymap_file.h"

namespace skyview::cli {
namespace {

struct Options {
  SceneInputOptions scene;
  std::string camera, look_at, up = "0,0,1", size = "800x600";
  double fov = 60.0, orthographic = 0.0;
  TwoScaleOptions visibility;
  std::string combine = "multiply";
  int exposure_samples = 0;
  std::string skymap, reads = "area";
  ZenithOptions zenith;
  std::string zenith_in, zenith_out;
  RenderSunOptions sun;
  bool reference = false;
  int reference_rays = 128;
  PreviewOptions preview;
  std::string diff_preview, points_out;
  OutputOptions out;
};

std::string vec_text(const Vec3d& v) { return number_text(v[0]) + "," + number_text(v[1]) + "," + number_text(v[2]); }

int run(const CLI::App& app, Options& o) {
  RunSummary summary("render");
  if (o.scene.inputs.size() < 2)
    throw UsageError("render needs SCENE... OUT.tif: at least one scene input and the output");
  const std::string output = o.scene.inputs.back();
  o.scene.inputs.pop_back();
  if (!o.diff_preview.empty()) require_extension(o.diff_preview, {".png"}, "--diff-preview");
  if (!o.zenith_out.empty()) require_extension(o.zenith_out, {".tif", ".tiff"}, "--save-zenith");
  if (!o.points_out.empty()) require_extension(o.points_out, {".las"}, "--points-out");
  refuse_unused(app, "--diff-preview", o.reference, "runs with --reference");
  refuse_unused(app, "--reference-rays", o.reference, "runs with --reference");
  refuse_unused(app, "--reads", !o.skymap.empty(), "runs with --skymap");
  refuse_unused(app, "--exposure-samples", !o.skymap.empty(), "runs with --skymap");
  refuse_unused(app, "--fov", o.orthographic == 0, "perspective views (not with --orthographic)");
  if (!o.zenith_in.empty()) {
    for (const char* name : {"--save-zenith", "--zenith-res", "--zenith-layers"}) {
      refuse_unused(app, name, false, "runs that make the zenith map (not with --zenith)");
    }
  }
  // The bands the output will hold, in order, for --preview-band.
  std::vector<std::string> names{"svf", "svf_large", "svf_fine"};
  if (!o.skymap.empty()) names.insert(names.end(), {"exposure", "exposure_direct", "exposure_diffuse"});
  check_render_sun_options(app, o.sun);
  if (!o.sun.time.empty()) names.insert(names.end(), {sun_band_name(o.sun), "direct_now", "diffuse_now", "global_now"});
  names.insert(names.end(), {"depth", "normal_x", "normal_y", "normal_z"});
  if (o.reference) names.insert(names.end(), {"svf_reference", "svf_reference_stderr"});
  if (o.reference && !o.skymap.empty()) names.insert(names.end(), {"exposure_reference", "exposure_reference_stderr"});
  const std::string exposure_diff = o.skymap.empty() ? "" : exposure_diff_path(o.diff_preview);
  const std::size_t drawn = check_preview_options(app, o.preview, names, 0);
  CameraSpec spec;
  spec.position = parse_vec3(o.camera, "--camera");
  spec.look_at = parse_vec3(o.look_at, "--look-at");
  spec.up = parse_vec3(o.up, "--up");
  parse_size(o.size, spec.width, spec.height, "--size");
  spec.fov_deg = o.fov;
  spec.orthographic_width = o.orthographic;
  Camera probe(spec, {0, 0, 0});  // option checks before the scene is read
  o.visibility.combine = o.combine == "intersect" ? ScaleCombination::intersect : ScaleCombination::multiply;
  check_outputs_apart({output, o.preview.path, o.diff_preview, exposure_diff, o.zenith_out, o.sun.colour_out,
                       o.sun.shadow_diff, o.points_out},
                      [&] {
                        auto in = o.scene.inputs;
                        in.push_back(o.skymap);
                        in.push_back(o.zenith_in);
                        return in;
                      }());
  for (const std::string& path : {output, o.preview.path, o.diff_preview, exposure_diff, o.zenith_out, o.sun.colour_out,
                                  o.sun.shadow_diff, o.points_out}) {
    if (!path.empty()) check_output_writable(path, o.out.overwrite);
  }
  check_output_format(output, o.out.format, static_cast<int>(names.size()), o.out.creation_options);

  ThreadLimit limit(o.out.threads);
  const Scene scene = load_scene_inputs(app, o.scene);
  const RayScene rays(scene);
  const Camera camera(spec, scene.origin);
  if (point_inside_scene(rays, camera.eye())) {
    throw UsageError("--camera " + o.camera + " is inside an object of the scene (or on its surface): move it outside");
  }
  // The sun (below the horizon: an error) and the exposure maps first: a bad file fails before any rendering.
  std::optional<SunInstant> instant;
  std::optional<InstantSky> instant_sky;
  if (!o.sun.time.empty()) {
    instant = place_sun(o.sun, scene);
    instant_sky.emplace(o.sun, *instant, o.visibility.directions);
  }
  std::optional<SkymapFile> sky;
  std::optional<ExposurePyramid> pyramid;
  std::optional<ExposureSampler> sampler;
  if (!o.skymap.empty()) {
    sky = read_skymap(o.skymap);
    pyramid.emplace(sky->map);
    SamplerOptions so;
    so.reads = o.reads == "mipmap" ? SamplerReads::mipmap : SamplerReads::area;
    if (o.exposure_samples > 0)
      so.max_sample_rows = std::max(1, (sky->map.height() + o.exposure_samples - 1) / o.exposure_samples);
    if (o.visibility.directions > sky->map.width()) {
      throw UsageError("--directions " + std::to_string(o.visibility.directions) + " is more than the sky map's " +
                       std::to_string(sky->map.width()) + " columns");
    }
    sampler.emplace(*pyramid, o.visibility.directions, 0.0, so);
  }
  const ZenithDepthMap zenith =
      o.zenith_in.empty() ? ZenithDepthMap::build(scene, rays, o.zenith) : ZenithDepthMap::load(o.zenith_in, scene);
  WriteOptions wo;
  wo.creation_options = o.out.creation_options;
  wo.format = o.out.format;
  wo.overwrite = o.out.overwrite;
  if (!o.zenith_out.empty()) {
    WriteOptions zo = wo;
    zo.format = "GTiff";
    zo.metadata["SKYVIEW_COMMAND"] = command_line();
    zenith.save(o.zenith_out, scene, zo);
  }
  const ViewBuffers view = render_view_buffers(rays, camera);
  if (view.hits() == 0) std::fprintf(stderr, "Warning: the camera sees no part of the scene (every pixel is sky)\n");
  // Without --skymap the instant's map rides on the one visibility pass; with it, a second pass
  // (the same seed: the same regions) reads the instant's.
  const ExposureSampler* instant_sampler = instant_sky ? &instant_sky->sampler() : nullptr;
  const TwoScaleBands bands =
      two_scale_visibility(view, camera, zenith, o.visibility, sampler ? &*sampler : instant_sampler);
  std::optional<RenderSunBands> sun;
  if (instant) {
    std::vector<float> diffuse =
        diffuse_now_of(sampler ? two_scale_visibility(view, camera, zenith, o.visibility, instant_sampler) : bands);
    sun = render_sun(o.sun, *instant, *instant_sky, scene, rays, view, camera.eye(), std::move(diffuse));
  }
  std::optional<SvfReference> reference;
  if (o.reference) reference = svf_reference(rays, view, o.reference_rays);
  std::optional<ExposureReference> exposure_ref;
  if (o.reference && sky) exposure_ref = exposure_reference(rays, view, sky->map, o.reference_rays);

  // Depth and normals as bands; the normal in (east, north, up) of the scene's CRS.
  const std::size_t n = view.position.size();
  std::vector<float> nx(n), ny(n), nz(n);
  for (std::size_t i = 0; i < n; ++i) nx[i] = view.normal[i][0], ny[i] = view.normal[i][1], nz[i] = view.normal[i][2];
  std::vector<OutputBand> out{
      {"svf",
       "1",
       bands.svf.data(),
       {{"DEFINITION", "sky-view factor, cosine-weighted on the pixel's normal: the two scales combined"}}},
      {"svf_large",
       "1",
       bands.svf_large.data(),
       {{"DEFINITION", "large-scale svf from the zenithal depth map (Section 5.1, with the opening angle)"}}},
      {"svf_fine",
       "1",
       bands.svf_fine.data(),
       {{"DEFINITION",
         "fine-scale visibility, 1 - horizon-based ambient occlusion on the camera's depth (Section 5.2, Eq. 6)"}}},
  };
  if (sampler) {  // --skymap's (with only --time the bands hold the instant's, given as diffuse_now)
    out.push_back({"exposure",
                   "kWh m-2",
                   bands.exposure.data(),
                   {{"DEFINITION",
                     "direct + diffuse radiant exposure over the sky map's period through the visible sky (Section 6, "
                     "Eqs. 7-10)"}}});
    out.push_back(
        {"exposure_direct", "kWh m-2", bands.exposure_direct.data(), {{"DEFINITION", "the sun's part of exposure"}}});
    out.push_back(
        {"exposure_diffuse", "kWh m-2", bands.exposure_diffuse.data(), {{"DEFINITION", "the sky's part of exposure"}}});
  }
  if (sun) {
    out.push_back({sun_band_name(o.sun),
                   "1",
                   sun->visibility.data(),
                   {{"DEFINITION", o.sun.soft ? "visible share of the sun's disc at --time, 0..1"
                                              : "the sun at --time seen from the surface, 0 (shadow) .. 1 (sunlit; a "
                                                "shadow map's filter gives values between)"}}});
    out.push_back({"direct_now",
                   "W m-2",
                   sun->direct_now.data(),
                   {{"DEFINITION",
                     "beam irradiance on the surface at --time: the clear sky's direct normal irradiance x max(0, "
                     "normal . sun) x the sun band"}}});
    out.push_back({"diffuse_now",
                   "W m-2",
                   sun->diffuse_now.data(),
                   {{"DEFINITION",
                     "diffuse irradiance on the surface at --time: the clear sky's radiance over the pixel's visible "
                     "sky (two-scale visibility, as the exposure bands)"}}});
    out.push_back({"global_now", "W m-2", sun->global_now.data(), {{"DEFINITION", "direct_now + diffuse_now"}}});
  }
  out.push_back(
      {"depth", "metre", view.depth.data(), {{"DEFINITION", "distance from the camera along the pixel's ray"}}});
  out.push_back(
      {"normal_x", "1", nx.data(), {{"DEFINITION", "unit surface normal, east component (facing the camera)"}}});
  out.push_back({"normal_y", "1", ny.data(), {{"DEFINITION", "unit surface normal, north component"}}});
  out.push_back({"normal_z", "1", nz.data(), {{"DEFINITION", "unit surface normal, up component"}}});
  if (reference) {
    out.push_back({"svf_reference",
                   "1",
                   reference->svf.data(),
                   {{"DEFINITION", "ray-cast reference svf: fraction of cosine-weighted rays reaching the sky"}}});
    out.push_back({"svf_reference_stderr",
                   "1",
                   reference->stderr_.data(),
                   {{"DEFINITION", "binomial standard error of svf_reference, sqrt(p(1-p)/rays)"}}});
  }
  if (exposure_ref) add_exposure_reference_bands(out, *exposure_ref);
  auto& meta = wo.metadata;
  meta["SKYVIEW_COMMAND"] = command_line();
  meta["RENDER_METHOD"] = "two-scale screen-space sky visibility";
  meta["RENDER_CITATION"] =
      "Munoz-Pandiella et al., Solar exposure of complex cities, Sections 5 (large and fine scale) and 6 (exposure, "
      "Eqs. 7-10); fine scale after Bavoil et al. 2008 (HBAO)";
  meta["CAMERA"] = vec_text(spec.position);
  meta["LOOK_AT"] = vec_text(spec.look_at);
  meta["CAMERA_UP"] = vec_text(spec.up);
  meta["PROJECTION"] = camera.orthographic() ? "orthographic, width " + number_text(o.orthographic) + " m"
                                             : "perspective, vertical field of view " + number_text(o.fov) + " degrees";
  meta["SCENE_CRS"] = scene.crs_wkt.empty() ? "none (local metres)" : scene.crs_wkt;
  meta["DIRECTIONS"] = std::to_string(o.visibility.directions);
  meta["SAMPLES"] = std::to_string(o.visibility.samples);
  meta["MAX_DISTANCE_M"] = number_text(o.visibility.max_distance);
  meta["OPENING_MAX_DISTANCE_M"] = number_text(o.visibility.opening_max_distance);
  meta["FINE_RADIUS_M"] = number_text(o.visibility.fine_radius);
  meta["COMBINE"] = o.combine;
  meta["ZENITH_RESOLUTION_M"] = number_text(zenith.resolution());
  meta["ZENITH_SIZE"] = std::to_string(zenith.width()) + "x" + std::to_string(zenith.height());
  meta["ZENITH_LAYERED_TEXELS"] = std::to_string(zenith.layered_texels());
  if (sampler) {
    meta["SKYMAP"] = o.skymap;
    meta["EXPOSURE_SAMPLER_READS"] = o.reads;
    meta["EXPOSURE_SAMPLES"] =
        o.exposure_samples > 0 ? std::to_string(o.exposure_samples) : "as Eq. 7 (square samples)";
    for (const auto& [key, value] : sky->metadata) {
      if (key.rfind("SKYVIEW_", 0) != 0) meta["SKY_" + key] = value;
    }
  }
  if (sun) meta.insert(sun->metadata.begin(), sun->metadata.end());
  if (reference) meta["REFERENCE_RAYS"] = std::to_string(o.reference_rays);
  write_bands(output, view.width, view.height, GeoReference{}, out, wo);
  if (sun) write_render_sun_pictures(o.sun, *instant, *sun, camera, view, o.out.overwrite);
  if (!o.points_out.empty()) write_render_points(o.points_out, view, scene, out);

  if (!o.preview.path.empty()) {
    const OutputBand& band = out[drawn];
    const Grid<float> values(view.width, view.height, std::vector<float>(band.values, band.values + n));
    PreviewBand pb{band.description, band.unit, output, GeoReference{}, std::nullopt, std::nullopt};
    if (band.unit == "1" && band.description.rfind("svf", 0) == 0) pb.fixed_range = std::pair{0.0, 1.0};
    if (sun && band.description == sun_band_name(o.sun)) {
      pb.ramp = ColourRamp::grey;  // sunlit and shaded are the ends of a fixed 0..1 ramp
      pb.fixed_range = std::pair{0.0, 1.0};
    }
    write_preview(o.preview, values, pb, o.out.overwrite);
  }
  double diff_sum = 0, diff_abs = 0, large_abs = 0;
  std::size_t diff_n = 0;
  if (reference) {
    Grid<float> diff(view.width, view.height, std::numeric_limits<float>::quiet_NaN());
    for (std::size_t i = 0; i < n; ++i) {
      if (!view.hit(i)) continue;
      diff.values()[i] = bands.svf.values()[i] - reference->svf.values()[i];
      diff_sum += diff.values()[i];
      diff_abs += std::abs(diff.values()[i]);
      large_abs += std::abs(bands.svf_large.values()[i] - reference->svf.values()[i]);
      ++diff_n;
    }
    if (!o.diff_preview.empty()) {
      PreviewSpec ps;
      ps.title = "svf - svf_reference - " + output;
      ps.band = "svf - svf_reference";
      ps.unit = "1";
      ps.ramp = ColourRamp::diverging;
      ps.range = std::make_pair(-0.5, 0.5);
      write_raster_preview(o.diff_preview, diff, ps, o.out.overwrite);
    }
  }
  double mean_svf = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (view.hit(i)) mean_svf += bands.svf.values()[i];
  }
  const std::size_t hits = view.hits();
  std::string what = std::to_string(view.width) + "x" + std::to_string(view.height) + ", " + std::to_string(hits) +
                     " pixels on the scene, " + std::to_string(o.visibility.directions) + "x(" +
                     std::to_string(o.visibility.samples) + "+" + std::to_string(o.visibility.samples) +
                     "), zenith map " + std::to_string(zenith.width()) + "x" + std::to_string(zenith.height()) +
                     ", mean svf " + number_text(hits ? std::round(mean_svf / hits * 1000) / 1000 : 0.0);
  if (diff_n) {
    what += ", svf - reference mean " + number_text(std::round(diff_sum / diff_n * 1000) / 1000) + " mean abs " +
            number_text(std::round(diff_abs / diff_n * 1000) / 1000) + " (svf_large mean abs " +
            number_text(std::round(large_abs / diff_n * 1000) / 1000) + ")";
  }
  if (exposure_ref)
    what += exposure_agreement_text(
        compare_exposure(bands.exposure, *exposure_ref, exposure_diff, output, o.out.overwrite));
  if (sun) what += "; " + sun->summary;
  summary.print(what, o.out.quiet);
  return 0;
}

Runner setup(CLI::App& app) {
  auto o = std::make_shared<Options>();
  add_scene_options(app, o->scene, "--mesh-up")
      ->description(
          "Scene inputs (DSM rasters, footprint layers, CityGML, CityJSON, mesh files: OBJ, PLY, glTF/GLB, STL, ...), "
          "then the output image OUT.tif");
  app.add_option("--camera", o->camera, "The camera's position X,Y,Z in the scene's CRS (metres)")->required();
  app.add_option("--look-at", o->look_at, "The point X,Y,Z the camera looks at")->required();
  app.add_option("--up", o->up, "The camera's up vector X,Y,Z")->capture_default_str();
  app.add_option("--fov", o->fov, "Vertical field of view in degrees, above 0 and below 180 (perspective)")
      ->check(finite_number())
      ->capture_default_str();
  app.add_option("--orthographic", o->orthographic,
                 "An orthographic view this many metres wide instead of a perspective one")
      ->check(positive_number());
  app.add_option("--size", o->size, "Image WIDTHxHEIGHT in pixels")->capture_default_str();
  app.add_option("--directions", o->visibility.directions, "N_dir: directions of both visibility scales")
      ->capture_default_str();
  app.add_option("--samples", o->visibility.samples, "S_dir: samples per direction of both scales")
      ->capture_default_str();
  app.add_option("--max-distance", o->visibility.max_distance, "Metres the large scale marches in the zenith map")
      ->check(positive_number())
      ->capture_default_str();
  app.add_option("--opening-max-distance", o->visibility.opening_max_distance,
                 "Close a direction whose opening (the edge of the cover over a point) lies farther than this, metres; "
                 "0: no limit")
      ->check(non_negative_number())
      ->capture_default_str();
  app.add_option("--fine-radius", o->visibility.fine_radius, "Reach of the fine scale (HBAO) in metres")
      ->check(positive_number())
      ->capture_default_str();
  app.add_option("--combine", o->combine,
                 "multiply: the paper's (large-scale svf and exposure times the fine-scale term); intersect: the fine "
                 "scale's horizons raise the large scale's in each direction")
      ->check(CLI::IsMember({"multiply", "intersect"}))
      ->capture_default_str();
  app.add_option("--seed", o->visibility.seed, "Seed of the per-pixel random rotations")->capture_default_str();
  app.add_option("--skymap", o->skymap, "An exposure map written by skyview skymap: adds the exposure bands");
  app.add_option("--exposure-samples", o->exposure_samples,
                 "Most exposure-map samples per direction (n_s of Eq. 7 at full visibility); default: as Eq. 7's "
                 "square samples")
      ->check(CLI::Range(1, 4096));
  app.add_option("--reads", o->reads,
                 "How exposure samples read the map: area (exact rectangles) or mipmap (the paper's)")
      ->check(CLI::IsMember({"area", "mipmap"}))
      ->capture_default_str();
  app.add_option("--zenith-res", o->zenith.resolution, "Texel size of the zenithal depth map, metres")
      ->check(positive_number())
      ->capture_default_str();
  app.add_option("--zenith-layers", o->zenith.max_layers, "Most surface heights the zenith map keeps per texel")
      ->check(CLI::Range(1, 255))
      ->capture_default_str();
  app.add_option("--save-zenith", o->zenith_out, "Also write the zenith map as a GeoTIFF, to reuse with --zenith");
  app.add_option("--zenith", o->zenith_in, "Reuse a zenith map written by --save-zenith for this scene");
  app.add_flag("--reference", o->reference,
               "Add svf_reference and svf_reference_stderr (per-pixel Embree cosine-weighted hemisphere sampling) and, "
               "with --skymap, exposure_reference and exposure_reference_stderr");
  app.add_option("--reference-rays", o->reference_rays, "Rays per pixel of --reference")
      ->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
  add_render_sun_options(app, o->sun);
  add_preview_options(app, o->preview,
                      "Also write a false-colour PNG of the svf band, or --preview-band's, with a legend");
  app.add_option("--diff-preview", o->diff_preview,
                 "With --reference: a PNG of svf - svf_reference (and, with --skymap, D_exposure.png of exposure - "
                 "exposure_reference)");
  app.add_option("--points-out", o->points_out,
                 "Also write the visible points as a LAS 1.4 point cloud in the scene's CRS, the bands as extra bytes");
  add_output_options(app, o->out);
  app.footer(
      "Bands: svf, svf_large, svf_fine, [exposure, exposure_direct, exposure_diffuse with --skymap], [sunlit or "
      "sun_fraction, direct_now, diffuse_now, global_now with --time], depth, normal_x, "
      "normal_y, normal_z, [svf_reference, svf_reference_stderr with --reference], [exposure_reference, "
      "exposure_reference_stderr with --reference and --skymap]; a pixel grid without "
      "geotransform, NaN where the pixel sees sky. See docs/commands/render.md.");
  return [o, &app] { return run(app, *o); };
}

const Registration registration(
    "render", "A camera view of a 3-D scene with two-scale sky visibility and solar exposure per pixel", setup);

}  // namespace
}  // namespace skyview::cli
