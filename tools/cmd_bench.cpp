// skyview bench: speed against error of every horizon method on one raster.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <vector>

#include "command.h"
#include "sky_job.h"
#include "skyview/benchmark/exposure_benchmark.h"
#include "skyview/benchmark/method_benchmark.h"
#include "skyview/benchmark/shadow_benchmark.h"
#include "skyview/core/error.h"
#include "skyview/raster/raster_io.h"

namespace skyview::cli {
namespace {

std::vector<std::string> split_list(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

// The --out folder and the files a bench writes there: made (with its parents) before any work, the
// files checked as outputs; folders made for a run that then fails are removed again (while empty).
class OutFolder {
 public:
  OutFolder(const std::string& out, const std::vector<std::string>& names, const std::vector<std::string>& inputs,
            bool overwrite) {
    std::error_code ec;
    for (std::filesystem::path p = std::filesystem::absolute(out, ec);
         !p.empty() && !std::filesystem::exists(p, ec) && p != p.parent_path(); p = p.parent_path())
      made_.push_back(p);
    std::filesystem::create_directories(out, ec);
    if (ec || !std::filesystem::is_directory(out)) {
      remove_made();
      throw Error("--out '" + out + "' is not a folder that can be made");
    }
    try {
      for (const auto& n : names) {
        check_outputs_apart({out + "/" + n}, inputs);
        check_output_writable(out + "/" + n, overwrite);
      }
    } catch (...) {
      remove_made();
      throw;
    }
  }
  ~OutFolder() { remove_made(); }
  OutFolder(const OutFolder&) = delete;
  OutFolder& operator=(const OutFolder&) = delete;
  void keep() { made_.clear(); }

 private:
  void remove_made() {
    std::error_code e;
    for (const auto& folder : made_) std::filesystem::remove(folder, e);  // deepest first, only while empty
    made_.clear();
  }
  std::vector<std::filesystem::path> made_;
};

// skyview bench --exposure: the fast method's settings timed and judged by the exact method.
int bench_exposure(const std::string& input, const std::string& out, int band, double z_scale, SkyRequest sky,
                   int map_size, int reference_directions, int repeat, bool overwrite, bool quiet) {
  check_sky_request(sky);
  if (map_size < 16 || map_size > 8192) throw Error("--map-size must be within 16 .. 8192");
  OutFolder folder(out, {"exposure.json", "exposure.md", "exposure.png"}, {input, sky.epw}, overwrite);
  ReadOptions ro;
  ro.band = band;
  ro.z_scale = z_scale;
  const Terrain terrain = read_terrain(input, ro);
  std::string source;
  const Site site = raster_sun_site(terrain, input, sky.latitude, sky.longitude, sky.elevation, source);
  PreparedSky prepared = prepare_sky(sky, site);
  print_warnings(prepared.warnings);
  const auto t0 = std::chrono::steady_clock::now();
  ExposureSky exposure_sky;
  exposure_sky.map = make_exposure_map(prepared, map_size);
  exposure_sky.sun = sun_steps(*prepared.model, prepared.steps);
  const double map_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!quiet) {
    std::fprintf(stderr, "exposure map %dx%d of %zu steps in %.1f s; reference: exact, sweep, %d directions...\n",
                 map_size, map_size, prepared.steps.size(), map_seconds, reference_directions);
  }
  if (reference_directions > map_size)
    throw Error("--reference-directions " + std::to_string(reference_directions) + " exceeds the map's " +
                std::to_string(map_size) + " columns; give a larger --map-size");
  const ExposureBenchReference ref = exposure_bench_reference(terrain, exposure_sky, reference_directions);
  if (!quiet) std::fprintf(stderr, "reference done in %.1f s\n", ref.seconds);
  // Slices no finer than the map's columns.
  std::vector<ExposureBenchConfig> grid;
  for (const ExposureBenchConfig& c : default_exposure_bench_grid()) {
    if (c.params.directions <= map_size) {
      grid.push_back(c);
    } else {
      std::fprintf(stderr, "Warning: %s skipped: more directions than the map's %d columns\n", c.label.c_str(),
                   map_size);
    }
  }
  const auto results = run_exposure_bench(terrain, exposure_sky, grid, ref, repeat, [&](const ExposureBenchResult& r) {
    if (!quiet) {
      std::fprintf(stderr, "%-34s %8.3f s  p99 %.4f  rmse %.4f\n", r.config.label.c_str(), r.seconds, r.all.p99,
                   r.all.rmse);
    }
  });
  std::string name = std::filesystem::path(input).filename().string();
  nlohmann::json json = exposure_bench_to_json(name, ref, results);
  json["map_seconds"] = map_seconds;
  json["sky"] = prepared.metadata;
  std::string md = exposure_bench_to_markdown(name, ref, results);
  md += "\nSky: " + prepared.metadata["SKY"] + " at " + prepared.metadata["LATITUDE"] + ", " +
        prepared.metadata["LONGITUDE"] + ", " + std::to_string(prepared.steps.size()) + " steps; map " +
        std::to_string(map_size) + "x" + std::to_string(map_size) + " built once in " +
        std::to_string(map_seconds).substr(0, 4) + " s (not in the times).\n";
  write_output_file(out + "/exposure.json", json.dump(2) + "\n", overwrite);
  write_output_file(out + "/exposure.md", md, overwrite);
  plot_exposure_bench(out + "/exposure.png", "skyview bench --exposure: " + name, results, overwrite);
  std::fputs(md.c_str(), stdout);
  folder.keep();
  return 0;
}

// skyview bench --shadows: the shadow-map family against exact rays on docs/shadows.md's views,
// and a far view of INPUT (any scene input) where given.
int bench_shadows(const std::string& input, const std::string& out, int repeat, bool overwrite, bool quiet) {
  OutFolder folder(out, {"shadows.json", "shadows.md"}, {input}, overwrite);
  const std::string work = (std::filesystem::temp_directory_path() / "skyview_bench_shadows").string();
  std::vector<ShadowBenchView> views;
  const auto city = load_shadow_bench_scene("city", work);
  const auto city_rays = std::make_shared<const RayScene>(*city);
  views.push_back(make_shadow_bench_view("city_far", city, city_rays));
  views.push_back(make_shadow_bench_view("city_near", city, city_rays));
  views.push_back(make_shadow_bench_view("district", load_shadow_bench_scene("district", work)));
  if (!input.empty()) {
    views.push_back(
        make_shadow_bench_view(std::filesystem::path(input).stem().string(), load_shadow_bench_scene(input, work)));
  }
  std::vector<ShadowBenchRow> rows;
  for (const ShadowBenchView& v : views) {
    for (ShadowMethod m : {ShadowMethod::exact, ShadowMethod::pcf, ShadowMethod::vsm, ShadowMethod::lvsm,
                           ShadowMethod::csm, ShadowMethod::hsm}) {
      rows.push_back(run_shadow_bench(v, m, repeat));
      if (!quiet) {
        const ShadowBenchRow& r = rows.back();
        std::fprintf(stderr, "%-10s %-5s %8.1f ms  wrong %.3f %%\n", v.name.c_str(), shadow_method_name(m).c_str(),
                     1000 * r.seconds, 100 * r.error.wrong_share());
      }
    }
  }
  std::string md = shadow_bench_markdown(rows);
  md +=
      "\nReceivers: the first hits of a 400 x 300 pinhole camera; sun at azimuth 215, elevation 30 deg; default "
      "options (docs/shadows.md); ms: median wall time of " +
      std::to_string(repeat) + " runs, CPU ms: the process's user + system time per run.\n";
  nlohmann::json json;
  json["rows"] = shadow_bench_json(rows);
  json["repeat"] = repeat;
  write_output_file(out + "/shadows.json", json.dump(2) + "\n", overwrite);
  write_output_file(out + "/shadows.md", md, overwrite);
  std::fputs(md.c_str(), stdout);
  folder.keep();
  return 0;
}

Runner setup(CLI::App& app) {
  struct Options {
    std::string input, methods = "sampled,march,sweep", out = "bench-out", azimuth_origin = "grid";
    int band = 1, reference_directions = 64, repeat = 3;
    double z_scale = 0.0;  // 0: from the raster
    bool overwrite = false, quiet = false, exposure = false, shadows = false;
    int threads = 0, map_size = 512;
    SkyRequest sky;
    const CLI::App* app = nullptr;
  };
  auto o = std::make_shared<Options>();
  o->app = &app;
  app.add_option("input", o->input,
                 "Elevation raster (required); with --shadows, an optional scene (any skyview scene input) seen from "
                 "far besides the synthetic views");
  app.add_option("--methods", o->methods, "Comma-separated methods")->capture_default_str();
  app.add_option("--out", o->out, "Folder for bench.json, bench.md and bench.png")->capture_default_str();
  app.add_option("--reference-directions", o->reference_directions, "Directions of the ray-cast reference")
      ->capture_default_str()
      ->check(CLI::Range(4, 4096));
  app.add_option("--repeat", o->repeat,
                 "Runs per configuration (median time), in rounds over all configurations so that the machine's drift "
                 "hits all alike")
      ->capture_default_str()
      ->check(CLI::Range(1, 100));
  app.add_option(
         "--azimuth-origin", o->azimuth_origin,
         "Centre of the first sector for the reference and every run: grid (as skyview svf by default) or north")
      ->check(CLI::IsMember({"north", "grid"}))
      ->capture_default_str();
  app.add_option("-b,--band", o->band, "Input band")->capture_default_str();
  app.add_option(
         "--z-scale", o->z_scale,
         "Metres per height unit (0.3048 for feet); default: the band's unit or vertical CRS, else metres if the "
         "CRS is in metres or degrees")
      ->check(positive_number());
  app.add_flag("--exposure", o->exposure,
               "Bench skyview exposure instead: the fast method's settings against the exact one (exposure.json, "
               "exposure.md, exposure.png), with the sky options below");
  add_sky_options(app, o->sky, "--exposure; default: the raster's centre");
  app.add_flag("--shadows", o->shadows,
               "Bench the sun-shadow methods instead (exact rays, pcf, vsm, lvsm, csm, hsm) against exact rays on the "
               "synthetic city (far and near), a footprint district and INPUT if given (shadows.json, shadows.md)");
  app.add_option("--map-size", o->map_size, "--exposure: the exposure map's width and height")->capture_default_str();
  app.add_flag("--overwrite", o->overwrite, "Replace existing result files");
  app.add_flag("-q,--quiet", o->quiet, "No per-configuration lines on stderr");
  app.add_option("--threads", o->threads, "Worker threads (0 = all cores)")->check(non_negative_number());
  app.footer(
      "Times each method over a grid of its parameters and compares svf and sky visibility with the ray-cast "
      "reference (RMSE, bias, 99th percentile, maximum, share of cells off by more than 0.01).");
  return [o] {
    ThreadLimit limit(o->threads);
    for (const std::string& name : sky_option_names()) refuse_unused(*o->app, name, o->exposure, "--exposure");
    refuse_unused(*o->app, "--map-size", o->exposure, "--exposure");
    if (o->shadows) {
      refuse_unused(*o->app, "--exposure", false, "runs without --shadows");
      for (const char* name : {"--methods", "--azimuth-origin", "--reference-directions", "--band", "--z-scale"})
        refuse_unused(*o->app, name, false, "runs without --shadows");
      return bench_shadows(o->input, o->out, o->repeat, o->overwrite, o->quiet);
    }
    if (o->input.empty()) throw UsageError("bench needs INPUT, the elevation raster");
    if (o->exposure) {
      refuse_unused(*o->app, "--methods", false, "runs without --exposure (--exposure benches its own settings)");
      refuse_unused(*o->app, "--azimuth-origin", false, "runs without --exposure (its runs start on grid north)");
      return bench_exposure(o->input, o->out, o->band, o->z_scale, o->sky, o->map_size, o->reference_directions,
                            o->repeat, o->overwrite, o->quiet);
    }
    const std::vector<std::string> names{"bench.json", "bench.md", "bench.png"};
    auto grid = default_bench_grid(split_list(o->methods));  // bad --methods before any folder is made
    const AzimuthOrigin origin = azimuth_origin_named(o->azimuth_origin);
    for (BenchConfig& c : grid) c.params.azimuth_origin = origin;
    int finest = 0;
    for (const BenchConfig& c : grid) finest = std::max(finest, c.params.directions);
    // A warning even under -q: it says that some of the numbers written are not what they seem.
    if (finest > o->reference_directions) {
      std::fprintf(stderr,
                   "Warning: the reference's %d directions are fewer than the %d of the finest configurations, whose "
                   "errors then include the reference's own sector error (marked reference_limited)\n",
                   o->reference_directions, finest);
    }
    OutFolder folder(o->out, names, {o->input}, o->overwrite);
    ReadOptions ro;
    ro.band = o->band;
    ro.z_scale = o->z_scale;
    ReadReport report;
    const Terrain terrain = read_terrain(o->input, ro, &report);
    if (!o->quiet) std::fprintf(stderr, "reference: raycast with %d directions...\n", o->reference_directions);
    const BenchReference ref = compute_reference(terrain, o->reference_directions, origin);
    if (!o->quiet) {
      std::fprintf(stderr, "reference done in %.1f s; continuous svf at %zu cells in %.1f s\n", ref.seconds,
                   ref.continuous->cells().size(), ref.continuous->seconds());
      std::fprintf(stderr, "%zu configurations in %d rounds; each is listed as the last round finishes it\n",
                   grid.size(), o->repeat);
    }
    std::vector<BenchSkipped> skipped;
    const auto results = run_bench(
        terrain, grid, ref, o->repeat,
        [&](const BenchResult& r) {
          if (!o->quiet) {
            std::fprintf(stderr, "%-28s %8.3f s  svf p99 %.4f  rmse %.4f  cont. p99 %.4f\n", r.config.label().c_str(),
                         r.seconds, r.svf.p99, r.svf.rmse, r.svf_continuous.p99);
          }
        },
        &skipped);
    // Even under -q: the tables lack these rows.
    for (const BenchSkipped& s : skipped)
      std::fprintf(stderr, "Warning: %s skipped: %s\n", s.label.c_str(), s.why.c_str());
    if (results.empty()) throw Error("no configuration can run on '" + o->input + "': " + skipped.front().why);
    std::string name = std::filesystem::path(o->input).filename().string();
    if (o->band != 1) name += " band " + std::to_string(o->band);
    nlohmann::json json = bench_to_json(o->input, ref, results);
    json["band"] = o->band;
    json["z_scale"] = report.z_scale;
    json["height_unit"] = report.height_unit;
    for (const BenchSkipped& s : skipped) json["skipped"].push_back({{"label", s.label}, {"why", s.why}});
    write_output_file(o->out + "/bench.json", json.dump(2) + "\n", o->overwrite);
    std::string md = bench_to_markdown(name, ref, results);
    if (!skipped.empty()) md += "\nSkipped, as they cannot run on this raster:\n\n";
    for (const BenchSkipped& s : skipped) md += "- " + s.label + ": " + s.why + "\n";
    write_output_file(o->out + "/bench.md", md, o->overwrite);
    plot_bench(o->out + "/bench.png", "skyview bench: " + name, results, o->overwrite);
    std::fputs(md.c_str(), stdout);
    folder.keep();
    return 0;
  };
}

const Registration reg("bench", "Speed against error of every horizon method, judged by the ray-cast reference", setup);

}  // namespace
}  // namespace skyview::cli
