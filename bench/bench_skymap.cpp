// Annual 512×512 exposure maps at 30-minute steps for every sky model (the 10 s target).
// Sun positions are computed once outside the timed loop; the EPW case uses chicago.epw's hours.
#include <benchmark/benchmark.h>

#include <filesystem>

#include "skyview/sky/epw.h"
#include "skyview/sky/exposure_map.h"
#include "skyview/sky/exposure_steps.h"
#include "skyview/sky/sky_models.h"

namespace {

using namespace skyview;

std::vector<ExposureStep> year_steps() {
  Site site;
  site.latitude_deg = 30.0;
  // 2023-01-01T00:00Z .. 2024-01-01T00:00Z
  return regular_steps(site, 1672531200.0, 1704067200.0, 1800.0);
}

void run(benchmark::State& state, const SkyModel& model, const std::vector<ExposureStep>& steps) {
  for (auto _ : state) {
    ExposureMap map = integrate_exposure(model, steps, {});
    benchmark::DoNotOptimize(map.band(ExposureBand::diffuse).data());
  }
  state.counters["steps"] = static_cast<double>(steps.size());
}

void BM_AnnualPreetham(benchmark::State& state) {
  static const auto steps = year_steps();
  run(state, *make_preetham_sky(2.5), steps);
}
void BM_AnnualHosekWilkie(benchmark::State& state) {
  static const auto steps = year_steps();
  run(state, *make_hosek_wilkie_sky(2.5, 0.2), steps);
}
void BM_AnnualIsotropic(benchmark::State& state) {
  static const auto steps = year_steps();
  run(state, *make_isotropic_sky(make_preetham_sky(2.5)), steps);
}
void BM_AnnualPerezEpw(benchmark::State& state) {
  const std::string path = std::string(SKYVIEW_SHARED_DIR) + "/data/weather/chicago.epw";
  if (!std::filesystem::exists(path)) {
    state.SkipWithError("chicago.epw not found under SKYVIEW_SHARED_DIR");
    return;
  }
  const EpwFile file = read_epw(path);
  Site site;
  site.latitude_deg = file.location.latitude_deg;
  site.longitude_deg = file.location.longitude_deg;
  run(state, *make_perez_all_weather_sky(), epw_steps(file, site));
}

BENCHMARK(BM_AnnualPreetham)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_AnnualHosekWilkie)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_AnnualIsotropic)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_AnnualPerezEpw)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
