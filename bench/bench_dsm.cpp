// LAS reading and max gridding throughput, in points per second, on a synthetic 5-million-point
// LAS 1.4 file written once to the temp folder.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <random>

#include "skyview/dsm/dsm_builder.h"
#include "skyview/dsm/las_file.h"

namespace {

const std::string& cloud() {
  static const std::string path = [] {
    const std::string p = (std::filesystem::temp_directory_path() / "skyview-bench-5M.las").string();
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(0.0, 1000.0), z(0.0, 60.0);
    std::vector<skyview::LasPoint> pts(5'000'000);
    for (auto& q : pts) q = {500000.0 + u(rng), 6400000.0 + u(rng), z(rng), 0, 1, 1, 2};
    skyview::LasWriteOptions o;
    o.version_minor = 4;
    o.point_format = 6;
    o.offset[0] = 500000;
    o.offset[1] = 6400000;
    skyview::write_las(p, pts, o);
    return p;
  }();
  return path;
}

void BM_LasRead(benchmark::State& state) {
  const auto reader = skyview::LasReader::open_file(cloud());
  std::uint64_t n = 0;
  for (auto _ : state) {
    reader.read_points([&](const std::vector<skyview::LasPoint>& c) { n += c.size(); });
  }
  state.counters["points_per_s"] = benchmark::Counter(static_cast<double>(n), benchmark::Counter::kIsRate);
}

void BM_DsmMaxGridding(benchmark::State& state) {
  skyview::DsmOptions o;
  o.points = {cloud()};
  o.res = 1.0;
  o.t_srs = "EPSG:32633";  // the synthetic file carries no CRS
  std::uint64_t n = 0;
  for (auto _ : state) n += skyview::build_dsm(o).report.points_read;
  state.counters["points_per_s"] = benchmark::Counter(static_cast<double>(n), benchmark::Counter::kIsRate);
}

}  // namespace

BENCHMARK(BM_LasRead)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
BENCHMARK(BM_DsmMaxGridding)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
BENCHMARK_MAIN();
