#pragma once
// How much memory a horizon run takes, and the tile size that keeps it under a limit. The model is
// an estimate from what each stage holds per cell of the buffer it computes on (docs/tiling.md
// lists the terms); the run reports its measured peak beside it.
#include <cstdint>
#include <string>

#include "skyview/horizon/horizon_engine.h"
#include "skyview/sky_view/sky_view.h"

namespace skyview {

// "8G", "512M", "1.5G", "64K", "2T" (binary units, an optional trailing B or iB) or a number of
// bytes. Throws skyview::UsageError naming `option` for anything else or for zero.
std::uint64_t parse_memory_size(const std::string& text, const std::string& option = "--memory-limit");

// "1.50 GB" (10^9 bytes, as the summary line prints peaks).
std::string memory_text(std::uint64_t bytes);

// What the machine can give this run now: the kernel's estimate of available memory
// (MemAvailable), no more than an address-space limit (ulimit -v) allows.
std::uint64_t available_memory_bytes();

// Bytes a run holds: `per_cell` for each cell of the buffer it computes on (window plus halo),
// `fixed` besides (horizon blocks, GDAL's cache, the program).
struct MemoryModel {
  double per_cell = 0;
  std::uint64_t fixed = 0;
  std::uint64_t bytes(std::int64_t cells) const;
};

// `skyview svf` keeping `keep` and writing `bands` bands; `skyview horizon`.
MemoryModel svf_memory(const HorizonEngine& engine, ProductSet keep, int bands);
MemoryModel horizon_memory(const HorizonEngine& engine);
// `skyview exposure` with an exposure map of `map_cells` cells (its pyramid and summed-area
// tables are held once per tile besides).
MemoryModel exposure_memory(const HorizonEngine& engine, std::int64_t map_cells);

// The largest tile size whose square window plus `halo` on every side fits `limit` bytes by
// `model`, at most `largest`; multiples of 256 cells (the outputs' blocks) where it is that large.
// 0 when not even one cell with its halo fits.
int tile_size_for(const MemoryModel& model, std::uint64_t limit, int halo, int largest);

}  // namespace skyview
