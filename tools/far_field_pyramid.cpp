#include "far_field_pyramid.h"

#include <cstdio>
#include <filesystem>

#include "horizon_job.h"
#include "skyview/core/error.h"
#include "skyview/raster/output_files.h"
#include "skyview/tiling/pyramid_file.h"
#include "tile_ranks.h"

namespace skyview::cli {

namespace {

// The kept pyramid where it is of this input and first level (and holds minima where the run needs
// them); nullptr where there is none (or it is not this run's, or damaged: then built again, which
// costs a read of the raster, not a result).
std::shared_ptr<const OverviewPyramid> kept_pyramid(HorizonJob& job, int first_level, bool minima) {
  const TilePlan& plan = job.tiles;
  std::error_code ec;
  if (plan.pyramid_file.empty() || !std::filesystem::exists(plan.pyramid_file, ec)) return nullptr;
  try {
    std::string source;
    PyramidLevels p = read_pyramid_file(plan.pyramid_file, &source);
    if (source != plan.pyramid_source || p.first_level != first_level || p.width != job.reader->width() ||
        p.height != job.reader->height() || (minima && p.min.empty()))
      return nullptr;
    return std::make_shared<OverviewPyramid>(std::move(p));
  } catch (const Error& e) {
    std::fprintf(stderr, "Warning: %s; building it again from the raster\n", e.what());
    return nullptr;
  }
}

}  // namespace

std::shared_ptr<const OverviewPyramid> run_pyramid(HorizonJob& job, int first_level, bool minima) {
  TileRanks& ranks = TileRanks::world();
  std::shared_ptr<const OverviewPyramid> pyramid;
  auto make = [&] {
    pyramid = kept_pyramid(job, first_level, minima);
    job.tiles.pyramid_reused = pyramid != nullptr;
    if (!pyramid) pyramid = std::make_shared<OverviewPyramid>(*job.reader, first_level, minima);
  };
  if (!ranks.parallel()) {
    make();
    return pyramid;
  }
  // The same bytes on every rank, so the same halo and far field: the same bits as one process.
  const std::string bytes = ranks.broadcast([&] {
    make();
    return encode_pyramid(pyramid->levels(), job.tiles.pyramid_source);
  });
  if (ranks.rank() == 0) return pyramid;
  return std::make_shared<OverviewPyramid>(decode_pyramid(bytes, "the pyramid rank 0 sent"));
}

bool keep_run_pyramid(const HorizonJob& job, TileManifest& manifest) {
  const auto* far = dynamic_cast<const FarField*>(job.far_field.get());
  if (!far || job.tiles.pyramid_file.empty()) return false;
  const std::string bytes = encode_pyramid(far->pyramid()->levels(), job.tiles.pyramid_source);
  if (!job.tiles.pyramid_reused) write_output_file(job.tiles.pyramid_file, bytes, true);
  manifest.keep("far_field_pyramid", {{"file", kPyramidFileName},
                                      {"checksum", pyramid_checksum(bytes)},
                                      {"bytes", bytes.size()},
                                      {"source", job.tiles.pyramid_source}});
  return true;
}

}  // namespace skyview::cli
