// Speed of the solar code: SPA positions per second (one core), sunrise/transit/sunset per
// second, and time parsing. Run: build/bench_solar --benchmark_min_time=1s
#include <benchmark/benchmark.h>

#include "skyview/solar/solar_position.h"
#include "skyview/solar/sun_events.h"
#include "skyview/solar/time_parse.h"

namespace {

skyview::Site golden_site() {
  skyview::Site s;
  s.latitude_deg = 39.742476;
  s.longitude_deg = -105.1786;
  s.elevation_m = 1830.14;
  s.pressure_mbar = 820.0;
  s.temperature_c = 11.0;
  return s;  // automatic Delta T, as the command uses by default
}

void BM_SolarPosition(benchmark::State& state) {
  const skyview::Site site = golden_site();
  double t = 1066419030.0;  // 2003-10-17T19:30:30Z
  for (auto _ : state) {
    benchmark::DoNotOptimize(skyview::solar_position(t, site));
    t += 1800.0;  // half-hourly steps, as an annual exposure map uses
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_SolarPosition);

void BM_SunEvents(benchmark::State& state) {
  const skyview::Site site = golden_site();
  std::int64_t day = skyview::days_from_civil({2003, 1, 1});
  for (auto _ : state) {
    benchmark::DoNotOptimize(skyview::sun_events(skyview::civil_from_days(day++), -7 * 3600.0, site));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_SunEvents);

void BM_ParseTimeOffset(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(skyview::parse_time("2003-10-17T12:30:30-07:00"));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ParseTimeOffset);

void BM_ParseTimeZone(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(skyview::parse_time("2024-06-21T12:00 Europe/Athens"));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ParseTimeZone);

}  // namespace

BENCHMARK_MAIN();
