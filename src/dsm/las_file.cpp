#include "skyview/dsm/las_file.h"

#include <cpl_conv.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "skyview/core/error.h"

namespace skyview {

int las_point_base_size(int format) {
  static const int sizes[] = {20, 28, 26, 34, 57, 63, 30, 36, 38, 59, 67};
  return format >= 0 && format <= 10 ? sizes[format] : -1;
}

struct LasReader::Source {
  std::string path;                      // a file, read with positioned reads
  const std::uint8_t* memory = nullptr;  // or a buffer owned by the caller
  std::uint64_t size = 0;

  // Throws a bare Error; callers add the file name.
  void read(std::uint64_t offset, std::size_t n, void* out) const {
    if (offset > size || n > size - offset) throw Error("read beyond the end of the data");
    if (n == 0) return;  // an empty record has no buffer (memcpy with null is undefined even for 0 bytes)
    if (memory) {
      std::memcpy(out, memory + offset, n);
      return;
    }
    std::ifstream in(path, std::ios::binary);
    in.seekg(static_cast<std::streamoff>(offset));
    in.read(static_cast<char*>(out), static_cast<std::streamsize>(n));
    if (!in) throw Error("read error");
  }
};

namespace {

template <class T>
T get(const std::uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof v);  // LAS is little-endian, as is every machine skyview builds for
  return v;
}

std::string wkt_of(OGRSpatialReference& srs) {
  char* wkt = nullptr;
  srs.exportToWkt(&wkt);
  std::string s = wkt ? wkt : "";
  CPLFree(wkt);
  return s;
}

// GeoKeyDirectoryTag: four u16 of header, then keys of four u16 (id, location, count, value). The
// CRS from the projected or geographic CRS code; `z_unit_metres` from VerticalUnitsGeoKey, else from
// the unit of the EPSG vertical CRS that VerticalCSTypeGeoKey names (0 when neither says).
std::string crs_from_geokeys(const std::vector<std::uint8_t>& data, double& z_unit_metres) {
  if (data.size() < 8) return "";
  const std::size_t keys = get<std::uint16_t>(data.data() + 6);
  int projected = 0, geographic = 0, vertical = 0;
  for (std::size_t k = 0; k < keys && 8 + 8 * (k + 1) <= data.size(); ++k) {
    const std::uint8_t* e = data.data() + 8 + 8 * k;
    const int id = get<std::uint16_t>(e), location = get<std::uint16_t>(e + 2), value = get<std::uint16_t>(e + 6);
    if (location != 0) continue;
    if (id == 3072) projected = value;   // ProjectedCSTypeGeoKey
    if (id == 2048) geographic = value;  // GeographicTypeGeoKey
    if (id == 4096) vertical = value;    // VerticalCSTypeGeoKey
    if (id == 4099) {                    // VerticalUnitsGeoKey: EPSG units of length
      z_unit_metres = value == 9001 ? 1.0 : value == 9002 ? 0.3048 : value == 9003 ? 1200.0 / 3937.0 : 0.0;
    }
  }
  OGRSpatialReference vertical_crs;
  if (z_unit_metres == 0.0 && vertical > 0 && vertical < 32767 &&
      vertical_crs.importFromEPSG(vertical) == OGRERR_NONE && vertical_crs.IsVertical()) {
    const double metres = vertical_crs.GetTargetLinearUnits("VERT_CS");
    if (metres > 0.0 && std::isfinite(metres)) z_unit_metres = metres;
  }
  const int epsg =
      projected > 0 && projected < 32767 ? projected : (geographic > 0 && geographic < 32767 ? geographic : 0);
  OGRSpatialReference srs;
  if (!epsg || srs.importFromEPSG(epsg) != OGRERR_NONE) return "";
  return wkt_of(srs);
}

std::string crs_from_wkt(const std::vector<std::uint8_t>& data) {
  std::string text(data.begin(), data.end());
  text = text.substr(0, text.find('\0'));
  OGRSpatialReference srs;
  if (text.empty() || srs.importFromWkt(text.c_str()) != OGRERR_NONE) return "";
  return wkt_of(srs);
}

}  // namespace

LasReader LasReader::open_file(const std::string& path) {
  LasReader r;
  r.name_ = path;
  r.source_ = std::make_shared<Source>();
  r.source_->path = path;
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw Error("cannot open '" + path + "': no such file or not readable");
  r.source_->size = static_cast<std::uint64_t>(in.tellg());
  r.parse();
  return r;
}

LasReader LasReader::open_memory(const std::uint8_t* data, std::size_t size, const std::string& name) {
  LasReader r;
  r.name_ = name;
  r.source_ = std::make_shared<Source>();
  r.source_->memory = data;
  r.source_->size = size;
  r.parse();
  return r;
}

void LasReader::parse() {
  const std::string& f = name_;
  auto fail = [&](const std::string& why) { throw Error("'" + f + "' is not a valid LAS file: " + why); };
  const std::uint64_t size = source_->size;
  if (size < 227) fail("only " + std::to_string(size) + " bytes, shorter than any LAS header (227)");
  std::uint8_t h[375] = {};
  source_->read(0, static_cast<std::size_t>(std::min<std::uint64_t>(size, 375)), h);
  if (std::memcmp(h, "LASF", 4) != 0) fail("no LASF signature");
  LasHeader& hd = header_;
  hd.version_major = h[24];
  hd.version_minor = h[25];
  if (hd.version_major != 1 || hd.version_minor > 4) {
    fail("version " + std::to_string(hd.version_major) + "." + std::to_string(hd.version_minor) +
         " (supported: 1.0 to 1.4)");
  }
  hd.header_size = get<std::uint16_t>(h + 94);
  hd.point_offset = get<std::uint32_t>(h + 96);
  hd.vlr_count = get<std::uint32_t>(h + 100);
  const int raw_format = h[104];
  hd.record_length = get<std::uint16_t>(h + 105);
  const std::uint32_t legacy_count = get<std::uint32_t>(h + 107);
  const std::uint16_t min_header = hd.version_minor <= 2 ? 227 : (hd.version_minor == 3 ? 235 : 375);
  if (hd.header_size < min_header) {
    fail("header size " + std::to_string(hd.header_size) + " is below the " + std::to_string(min_header) +
         " bytes of LAS 1." + std::to_string(hd.version_minor));
  }
  if (hd.header_size > size) fail("header size " + std::to_string(hd.header_size) + " exceeds the file");
  if (raw_format & 0xC0) {
    throw Error("'" + f + "' is LAZ-compressed; decompress it first, e.g. `laszip -i " + f +
                " -o out.las` or `pdal translate " + f + " out.las`");
  }
  hd.point_format = raw_format;
  const int base = las_point_base_size(hd.point_format);
  if (base < 0) fail("point data format " + std::to_string(raw_format) + " (supported: 0 to 10)");
  if (hd.record_length < base) {
    fail("point record length " + std::to_string(hd.record_length) + " is below the " + std::to_string(base) +
         " bytes of point format " + std::to_string(hd.point_format));
  }
  for (int i = 0; i < 3; ++i) {
    hd.scale[i] = get<double>(h + 131 + 8 * i);
    hd.offset[i] = get<double>(h + 155 + 8 * i);
    hd.max[i] = get<double>(h + 179 + 16 * i);
    hd.min[i] = get<double>(h + 187 + 16 * i);
    if (!std::isfinite(hd.scale[i]) || hd.scale[i] == 0.0) fail("zero or non-finite scale factor");
    if (!std::isfinite(hd.offset[i])) fail("non-finite offset");
  }
  hd.point_count = legacy_count;
  if (hd.version_minor >= 4) {
    hd.evlr_offset = get<std::uint64_t>(h + 235);
    hd.evlr_count = get<std::uint32_t>(h + 243);
    const std::uint64_t count64 = get<std::uint64_t>(h + 247);
    if (legacy_count != 0 && count64 != 0 && legacy_count != count64) {
      fail("legacy point count " + std::to_string(legacy_count) + " disagrees with " + std::to_string(count64));
    }
    hd.point_count = count64 != 0 ? count64 : legacy_count;
  }
  if (hd.point_offset < hd.header_size || hd.point_offset > size) {
    fail("offset to point data " + std::to_string(hd.point_offset) + " lies outside [" +
         std::to_string(hd.header_size) + ", " + std::to_string(size) + "]");
  }
  if (hd.record_length != 0 && hd.point_count > (size - hd.point_offset) / hd.record_length) {
    fail("truncated: the header promises " + std::to_string(hd.point_count) + " points of " +
         std::to_string(hd.record_length) + " bytes but only " +
         std::to_string((size - hd.point_offset) / hd.record_length) + " fit in the file");
  }
  if (hd.record_length != 0) {
    const std::uint64_t points_end = hd.point_offset + hd.point_count * hd.record_length;
    std::uint64_t limit =
        hd.evlr_count > 0 && hd.evlr_offset >= points_end && hd.evlr_offset <= size ? hd.evlr_offset : size;
    // LAS 1.3 and 1.4 may keep waveform packets after the points.
    const std::uint64_t waveforms = hd.version_minor >= 3 && hd.header_size >= 235 ? get<std::uint64_t>(h + 227) : 0;
    if (waveforms >= points_end && waveforms < limit) limit = waveforms;
    hd.records_beyond_count = limit > points_end ? (limit - points_end) / hd.record_length : 0;
  }
  // VLRs sit between the header and the point data; each must fit there.
  std::string wkt, geokeys;
  std::uint64_t at = hd.header_size;
  auto note_record = [&](const char* user, int id, const std::vector<std::uint8_t>& body) {
    if (std::strncmp(user, "LASF_Projection", 16) == 0) {
      if (id == 2112) wkt = crs_from_wkt(body);
      if (id == 34735) geokeys = crs_from_geokeys(body, hd.z_unit_metres);
    }
    if (std::strncmp(user, "laszip encoded", 16) == 0) {
      throw Error("'" + f + "' is LAZ-compressed; decompress it first, e.g. `laszip -i " + f + " -o out.las`");
    }
  };
  for (std::uint32_t i = 0; i < hd.vlr_count; ++i) {
    if (at + 54 > hd.point_offset) fail("VLR " + std::to_string(i) + " runs into the point data");
    std::uint8_t v[54];
    source_->read(at, 54, v);
    const std::uint16_t length = get<std::uint16_t>(v + 20);
    if (at + 54 + length > hd.point_offset) fail("VLR " + std::to_string(i) + " runs into the point data");
    char user[17] = {};
    std::memcpy(user, v + 2, 16);
    std::vector<std::uint8_t> body(length);
    if (length) source_->read(at + 54, length, body.data());
    note_record(user, get<std::uint16_t>(v + 18), body);
    at += 54 + length;
  }
  if (hd.evlr_count > 0) {
    const std::uint64_t points_end = hd.point_offset + hd.point_count * hd.record_length;
    if (hd.evlr_offset < points_end || hd.evlr_offset > size) fail("EVLR offset outside the file");
    at = hd.evlr_offset;
    for (std::uint32_t i = 0; i < hd.evlr_count; ++i) {
      if (at + 60 > size) fail("EVLR " + std::to_string(i) + " runs past the end of the file");
      std::uint8_t v[60];
      source_->read(at, 60, v);
      const std::uint64_t length = get<std::uint64_t>(v + 20);
      if (length > size - at - 60) fail("EVLR " + std::to_string(i) + " runs past the end of the file");
      char user[17] = {};
      std::memcpy(user, v + 2, 16);
      // Only CRS records are read; waveform or other large EVLRs are skipped.
      if (std::strncmp(user, "LASF_Projection", 16) == 0 && length < (1u << 20)) {
        std::vector<std::uint8_t> body(static_cast<std::size_t>(length));
        source_->read(at + 60, body.size(), body.data());
        note_record(user, get<std::uint16_t>(v + 18), body);
      }
      at += 60 + length;
    }
  }
  hd.crs_wkt = !wkt.empty() ? wkt : geokeys;  // WKT wins where a file carries both
}

void LasReader::read_points(const std::function<void(const std::vector<LasPoint>&)>& chunk,
                            std::size_t chunk_points) const {
  const LasHeader& hd = header_;
  const bool modern = hd.point_format >= 6;
  std::vector<std::uint8_t> raw;
  std::vector<LasPoint> points;
  chunk_points = std::max<std::size_t>(1, chunk_points);
  for (std::uint64_t first = 0; first < hd.point_count; first += chunk_points) {
    const std::size_t n = static_cast<std::size_t>(std::min<std::uint64_t>(chunk_points, hd.point_count - first));
    raw.resize(n * hd.record_length);
    try {
      source_->read(hd.point_offset + first * hd.record_length, raw.size(), raw.data());
    } catch (const Error& e) {
      throw Error("'" + name_ + "': " + e.what() + " at point " + std::to_string(first));
    }
    points.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint8_t* p = raw.data() + i * hd.record_length;
      LasPoint& q = points[i];
      q.x = get<std::int32_t>(p) * hd.scale[0] + hd.offset[0];
      q.y = get<std::int32_t>(p + 4) * hd.scale[1] + hd.offset[1];
      q.z = get<std::int32_t>(p + 8) * hd.scale[2] + hd.offset[2];
      q.intensity = get<std::uint16_t>(p + 12);
      if (modern) {
        q.return_number = p[14] & 0x0F;
        q.number_of_returns = p[14] >> 4;
        q.classification = p[16];
      } else {
        q.return_number = p[14] & 0x07;
        q.number_of_returns = (p[14] >> 3) & 0x07;
        q.classification = p[15] & 0x1F;
      }
    }
    chunk(points);
  }
}

}  // namespace skyview
