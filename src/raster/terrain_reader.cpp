#include "skyview/raster/terrain_reader.h"

#include <algorithm>

#include "raster/raw_band.h"
#include "skyview/core/error.h"

namespace skyview {

using namespace detail;

namespace {

// Rows read at a time by the scan: about 8 MB of doubles, and whole blocks of the file.
int scan_rows(GDALDataset& ds, int band) {
  int bx = 0, by = 0;
  ds.GetRasterBand(band)->GetBlockSize(&bx, &by);
  const int width = std::max(1, ds.GetRasterXSize());
  const int rows = std::max(1, (1 << 20) / width);
  by = std::max(1, by);
  return std::max(by, rows / by * by);
}

}  // namespace

RasterSize raster_size(const std::string& path, int band) {
  const DatasetPtr ds = open_raster_band(path, band);
  return {ds->GetRasterXSize(), ds->GetRasterYSize()};
}

struct TerrainReader::State {
  std::string path;
  ReadOptions options;
  DatasetPtr ds;
  int width = 0, height = 0;
  double metres = 1.0;
  double base = 0.0;
  GeoReference georef;
  GroundFrame frame = GroundFrame::uniform(1.0);
};

TerrainReader::TerrainReader(const std::string& path, const ReadOptions& options, ReadReport* report)
    : s_(std::make_unique<State>()) {
  State& s = *s_;
  s.path = path;
  s.options = options;
  s.ds = open_raster_band(path, options.band);
  s.width = s.ds->GetRasterXSize();
  s.height = s.ds->GetRasterYSize();
  if (static_cast<std::int64_t>(s.width) * s.height < 2)
    throw Error("'" + path + "' has a single cell: a horizon needs at least two cells");
  s.georef = georeference_of(*s.ds);
  const HeightUnit unit = band_height_unit(*s.ds, options, path, s.georef);
  s.metres = unit.metres;
  // The scan: the range of heights (their base), and the counts and checks read_terrain makes.
  HeightScan scan;
  RawWindow raw;
  const int step = scan_rows(*s.ds, options.band);
  for (int row0 = 0; row0 < s.height; row0 += step) {
    const Window strip{0, row0, s.width, std::min(step, s.height - row0)};
    read_raw_window(*s.ds, options.band, path, strip, raw);
    convert_heights(raw.values, raw.mask, raw.has_nodata != 0, raw.nodata, s.metres, options, path, strip, scan);
  }
  check_height_range(path, scan, static_cast<std::int64_t>(s.width) * s.height, options.band);
  scan.counts.height_unit = unit.source;
  s.base = 0.5 * (scan.lo + scan.hi);
  s.frame = checked_frame(path, s.georef, s.width, s.height);
  check_units(path, s.georef, s.width, s.height, s.frame, scan.hi - scan.lo, unit.source);
  if (report) *report = scan.counts;
}

TerrainReader::~TerrainReader() = default;

int TerrainReader::width() const { return s_->width; }
int TerrainReader::height() const { return s_->height; }
const GeoReference& TerrainReader::georef() const { return s_->georef; }
const GroundFrame& TerrainReader::frame() const { return s_->frame; }
double TerrainReader::base_height() const { return s_->base; }

Terrain TerrainReader::read(const Window& w) const {
  const State& s = *s_;
  if (w.col0 < 0 || w.row0 < 0 || w.cols < 1 || w.rows < 1 || w.col0 + w.cols > s.width || w.row0 + w.rows > s.height)
    throw Error("window outside '" + s.path + "' (internal error)");
  RawWindow raw;
  read_raw_window(*s.ds, s.options.band, s.path, w, raw);
  HeightScan ignored;  // counted by the scan
  convert_heights(raw.values, raw.mask, raw.has_nodata != 0, raw.nodata, s.metres, s.options, s.path, w, ignored);
  Terrain t;
  t.base_height = s.base;
  t.heights = Grid<float>(w.cols, w.rows);
  // As read_terrain stores them: the same double difference rounded once.
  for (std::size_t i = 0; i < raw.values.size(); ++i)
    t.heights.values()[i] = static_cast<float>(raw.values[i] - s.base);
  t.frame = s.frame;
  t.georef = s.georef.window(w.col0, w.row0);
  t.origin_col = w.col0;
  t.origin_row = w.row0;
  t.full_width = s.width;
  t.full_height = s.height;
  return t;
}

}  // namespace skyview
