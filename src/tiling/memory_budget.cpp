#include "skyview/tiling/memory_budget.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>

#include <tbb/global_control.h>
#include <string>

#include <tbb/task_arena.h>

#include "skyview/core/error.h"

namespace skyview {

namespace {

// Read as doubles (8) with a mask (1), stored as floats (4), copied once extended at the raster's
// edges (4) and once transposed by the sweep (4); GDAL's block cache and the program besides.
constexpr double kInputBytesPerCell = 21;
constexpr std::uint64_t kProgramBytes = std::uint64_t{160} << 20;

}  // namespace

std::uint64_t parse_memory_size(const std::string& text, const std::string& option) {
  const auto bad = [&] {
    return UsageError(option + " '" + text +
                      "' is not a size: a number with K, M, G or T (1G = 1024^3 bytes), such as 8G or 512M");
  };
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    throw bad();
  }
  std::string unit = text.substr(used);
  for (char& c : unit) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  if (unit.size() >= 2 && unit.substr(unit.size() - 2) == "IB")
    unit.resize(unit.size() - 2);
  else if (unit.size() >= 2 && unit.back() == 'B')
    unit.pop_back();
  double scale = 1;
  if (unit == "K")
    scale = 1024.0;
  else if (unit == "M")
    scale = 1024.0 * 1024;
  else if (unit == "G")
    scale = 1024.0 * 1024 * 1024;
  else if (unit == "T")
    scale = 1024.0 * 1024 * 1024 * 1024;
  else if (!unit.empty() && unit != "B")
    throw bad();
  const double bytes = value * scale;
  if (!std::isfinite(bytes) || bytes < 1 || bytes > 1e18 || (text.size() > 0 && std::isspace(text[0]))) throw bad();
  return static_cast<std::uint64_t>(bytes);
}

std::string memory_text(std::uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f GB", static_cast<double>(bytes) / 1e9);
  return text;
}

std::uint64_t available_memory_bytes() {
  std::uint64_t available = 0;
  std::ifstream in("/proc/meminfo");
  for (std::string key; in >> key;) {
    std::uint64_t kb = 0;
    in >> kb;
    if (key == "MemAvailable:") {
      available = kb * 1024;
      break;
    }
    in.ignore(256, '\n');
  }
  if (available == 0) {
    const long pages = sysconf(_SC_AVPHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    if (pages > 0 && page > 0) available = static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page);
  }
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
    // ulimit -v caps the address space, of which the program and its libraries already hold some.
    std::uint64_t mapped = 0;
    std::ifstream status("/proc/self/status");
    for (std::string key; status >> key;) {
      if (key == "VmSize:") {
        status >> mapped;
        mapped *= 1024;
        break;
      }
      status.ignore(256, '\n');
    }
    // The memory model counts the program itself (kProgramBytes) as part of a run's need.
    // Each worker thread reserves address space besides: glibc's malloc arena (64 MiB) and its stack.
    const std::uint64_t threads = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
    const std::uint64_t taken = mapped + threads * (std::uint64_t{72} << 20);
    const std::uint64_t left = limit.rlim_cur + kProgramBytes > taken ? limit.rlim_cur + kProgramBytes - taken : 1;
    available = available == 0 ? left : std::min<std::uint64_t>(available, left);
  }
  return available;
}

std::uint64_t MemoryModel::bytes(std::int64_t cells) const {
  return fixed + static_cast<std::uint64_t>(per_cell * static_cast<double>(cells));
}

MemoryModel svf_memory(const HorizonEngine& engine, ProductSet keep, int bands) {
  MemoryModel m;
  const double sums = SkyViewSums::bytes_per_cell(keep);
  // compute_sky_view: the sweep holds its whole field until it would take twice the sums, the
  // other methods blocks of rows of horizons; then the products' grids (4 bytes a band).
  m.per_cell = kInputBytesPerCell + 4.0 * bands + (engine.streams_directions() ? 2.0 * sums : sums);
  m.fixed = kProgramBytes + (engine.streams_directions() ? 0 : kHorizonBlockBytes);
  return m;
}

MemoryModel horizon_memory(const HorizonEngine& engine) {
  MemoryModel m;
  // A blank mask (1) and a band in degrees (4) for writing; the sweep holds the planes of the
  // directions in progress and of those waiting to be written (two per worker ahead, sweep.cpp),
  // the other methods blocks of rows of horizons.
  const double planes = engine.streams_directions()
                            ? 3.0 * tbb::this_task_arena::max_concurrency() * (engine.params().lower ? 8 : 4)
                            : 0.0;
  m.per_cell = kInputBytesPerCell + 5 + planes;
  m.fixed = kProgramBytes + (engine.streams_directions() ? 0 : kHorizonBlockBytes);
  return m;
}

MemoryModel exposure_memory(const HorizonEngine& engine, std::int64_t map_cells) {
  MemoryModel m;
  // compute_exposure: per cell the surface's normal and slope with four sums in double (64 bytes
  // rounded up), the sky-view sums of svf and svf_surface, six bands of floats (24), an albedo
  // window (4); the sweep's planes in progress as for horizon (upper angles only).
  ProductSet keep = ProductSet::none();
  keep.add(Product::svf).add(Product::svf_surface);
  const double planes = engine.streams_directions() ? 3.0 * tbb::this_task_arena::max_concurrency() * 4 : 0.0;
  m.per_cell = kInputBytesPerCell + 64 + SkyViewSums::bytes_per_cell(keep) + 24 + 4 + planes;
  // The map itself, its pyramid (sums and moments in double, 4/3 of a level) and summed-area
  // tables: under 256 bytes a map cell.
  m.fixed = kProgramBytes + static_cast<std::uint64_t>(256 * std::max<std::int64_t>(map_cells, 0)) +
            (engine.streams_directions() ? 0 : kHorizonBlockBytes);
  return m;
}

int tile_size_for(const MemoryModel& model, std::uint64_t limit, int halo, int largest) {
  if (limit <= model.fixed || model.per_cell <= 0) return 0;
  const double side = std::sqrt(static_cast<double>(limit - model.fixed) / model.per_cell);
  const long size = static_cast<long>(std::floor(side)) - 2L * halo;
  if (size < 1) return 0;
  long out = std::min<long>(size, largest);
  if (out >= 256 && out < largest) out = out / 256 * 256;
  return static_cast<int>(out);
}

}  // namespace skyview
