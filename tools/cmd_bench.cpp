// skyview bench: speed against error of every horizon method on one raster.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <vector>

#include "command.h"
#include "skyview/benchmark/method_benchmark.h"
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

Runner setup(CLI::App& app) {
  struct Options {
    std::string input, methods = "sampled,march,sweep", out = "bench-out", azimuth_origin = "grid";
    int band = 1, reference_directions = 64, repeat = 3;
    double z_scale = 0.0;  // 0: from the raster
    bool overwrite = false, quiet = false;
    int threads = 0;
  };
  auto o = std::make_shared<Options>();
  app.add_option("input", o->input, "Elevation raster")->required();
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
  app.add_flag("--overwrite", o->overwrite, "Replace existing result files");
  app.add_flag("-q,--quiet", o->quiet, "No per-configuration lines on stderr");
  app.add_option("--threads", o->threads, "Worker threads (0 = all cores)")->check(non_negative_number());
  app.footer(
      "Times each method over a grid of its parameters and compares svf and sky visibility with the ray-cast "
      "reference (RMSE, bias, 99th percentile, maximum, share of cells off by more than 0.01).");
  return [o] {
    ThreadLimit limit(o->threads);
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
    std::error_code ec;
    // The folders this run makes, deepest first: a run that fails before writing its files leaves
    // none of them behind (removed only while empty).
    std::vector<std::filesystem::path> made;
    for (std::filesystem::path p = std::filesystem::absolute(o->out, ec);
         !p.empty() && !std::filesystem::exists(p, ec) && p != p.parent_path(); p = p.parent_path())
      made.push_back(p);
    struct RemoveIfEmpty {
      std::vector<std::filesystem::path>* folders;
      ~RemoveIfEmpty() {
        std::error_code e;
        if (folders)
          for (const auto& folder : *folders) std::filesystem::remove(folder, e);
      }
    } remove_if_failed{&made};
    std::filesystem::create_directories(o->out, ec);
    if (ec || !std::filesystem::is_directory(o->out))
      throw Error("--out '" + o->out + "' is not a folder that can be made");
    for (const auto& n : names) {
      check_outputs_apart({o->out + "/" + n}, {o->input});
      check_output_writable(o->out + "/" + n, o->overwrite);
    }
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
    remove_if_failed.folders = nullptr;
    return 0;
  };
}

const Registration reg("bench", "Speed against error of every horizon method, judged by the ray-cast reference", setup);

}  // namespace
}  // namespace skyview::cli
