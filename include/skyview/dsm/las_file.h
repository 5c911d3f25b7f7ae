#pragma once
// A LAS 1.0-1.4 reader written here (Debian 12 packages no LAS library). Every header field and
// record count is checked against the file size before a point is read; points are streamed in
// chunks so a file of any size needs a fixed amount of memory; LAZ is refused with the command
// that decompresses it. Reference: ASPRS LAS Specification 1.4 R15 (2019).
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace skyview {

struct LasHeader {
  int version_major = 1, version_minor = 2;
  int point_format = 0;
  std::uint16_t header_size = 0, record_length = 0;
  std::uint32_t point_offset = 0, vlr_count = 0;
  std::uint64_t point_count = 0;
  std::uint64_t evlr_offset = 0;
  std::uint32_t evlr_count = 0;
  double scale[3] = {0, 0, 0}, offset[3] = {0, 0, 0};
  double min[3] = {0, 0, 0}, max[3] = {0, 0, 0};
  std::string crs_wkt;  // from the OGC WKT (E)VLR or the GeoTIFF keys; empty when absent
  // Metres per z unit where the GeoTIFF keys state it (VerticalUnitsGeoKey: metre, foot, US survey
  // foot); 0 when they do not.
  double z_unit_metres = 0.0;
  // Whole point records' worth of bytes after the counted points, before the EVLRs or the file's
  // end: points a header that undercounts leaves unread (0 for a well-formed file).
  std::uint64_t records_beyond_count = 0;
};

struct LasPoint {
  double x, y, z;
  std::uint16_t intensity;
  std::uint8_t return_number, number_of_returns, classification;
};

// Base record sizes of point formats 0..10 (extra bytes may follow).
int las_point_base_size(int format);

class LasReader {
 public:
  // Reads and validates the header and (E)VLRs of a file, or of a memory buffer (fuzzing,
  // tests). Throws skyview::Error naming `name` and the problem.
  static LasReader open_file(const std::string& path);
  static LasReader open_memory(const std::uint8_t* data, std::size_t size, const std::string& name = "<memory>");

  const LasHeader& header() const { return header_; }

  // Calls `chunk` with up to `chunk_points` decoded points at a time, in file order.
  void read_points(const std::function<void(const std::vector<LasPoint>&)>& chunk,
                   std::size_t chunk_points = 1 << 20) const;

  struct Source;  // the bytes: a file or a memory buffer

 private:
  void parse();
  std::shared_ptr<Source> source_;
  LasHeader header_;
  std::string name_;
};

// A per-point attribute written as LAS 1.4 extra bytes (float32, one value per point, described in
// the Extra Bytes VLR: LASF_Spec record 4) so that PDAL and QGIS show it by name.
struct LasExtraBytes {
  std::string name;         // up to 31 characters
  std::string description;  // up to 31 characters
  std::vector<float> values;
};

struct LasWriteOptions {
  int version_minor = 2;  // 2 or 4
  int point_format = 0;   // 0..10
  double scale[3] = {0.001, 0.001, 0.001}, offset[3] = {0, 0, 0};
  // Written when not empty (and refused unless GDAL reads it as WKT): as an OGC WKT VLR with the
  // global encoding's WKT bit in LAS 1.4; in LAS 1.2 as GeoTIFF keys (when the CRS has an EPSG code
  // below 32767) and as WKT.
  std::string crs_wkt;
  std::vector<LasExtraBytes> extra;  // LAS 1.4 only; each with one value per point
};

// Writes `points` as an uncompressed LAS file (synthetic samples and tests), under a temporary
// name renamed into place; a file at `path` is replaced only once the new one is complete.
void write_las(const std::string& path, const std::vector<LasPoint>& points, const LasWriteOptions& options);

}  // namespace skyview
