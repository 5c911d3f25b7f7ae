#include <ogr_spatialref.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>

#include "skyview/core/error.h"
#include "skyview/dsm/las_file.h"
#include "skyview/raster/raster_io.h"

namespace skyview {

namespace {

template <class T, class Bytes>
void put(Bytes& b, std::size_t at, T v) {
  std::memcpy(b.data() + at, &v, sizeof v);
}

std::int32_t quantise(double v, double scale, double offset) {
  const double q = std::round((v - offset) / scale);
  if (q < std::numeric_limits<std::int32_t>::min() || q > std::numeric_limits<std::int32_t>::max()) {
    throw Error("coordinate " + std::to_string(v) + " does not fit the LAS scale and offset");
  }
  return static_cast<std::int32_t>(q);
}

// A VLR of the LAS projection records: its 54-byte header (with `description`), then `body`.
std::vector<std::uint8_t> projection_vlr(std::uint16_t record_id, const std::string& description,
                                         const std::vector<std::uint8_t>& body) {
  std::vector<std::uint8_t> vlr(54 + body.size(), 0);
  const std::string user = "LASF_Projection";
  std::copy(user.begin(), user.end(), vlr.begin() + 2);
  put<std::uint16_t>(vlr, 18, record_id);
  put<std::uint16_t>(vlr, 20, static_cast<std::uint16_t>(body.size()));
  std::copy_n(description.begin(), std::min<std::size_t>(description.size(), 31), vlr.begin() + 22);
  std::copy(body.begin(), body.end(), vlr.begin() + 54);
  return vlr;
}

// The EPSG code `srs` names for its node `key` (null: the root), or 0.
long named_epsg(const OGRSpatialReference& srs, const char* key) {
  const char* authority = srs.GetAuthorityName(key);
  const char* code = srs.GetAuthorityCode(key);
  return authority && code && std::string(authority) == "EPSG" ? std::strtol(code, nullptr, 10) : 0;
}

// The CRS's EPSG code as GeoTIFF can hold it (1 to 32766; above are user-defined and private
// codes), from its authority or, failing that, from GDAL's matching; 0 if none.
int epsg_code(const OGRSpatialReference& srs, bool projected) {
  long epsg = named_epsg(srs, projected ? "PROJCS" : "GEOGCS");
  if (epsg <= 0) {
    // The one EPSG CRS GDAL judges equivalent, if exactly one is (confidence 70 and up: the same
    // definition, whatever the names; a proj string's CRS has none).
    int n = 0;
    int* confidence = nullptr;
    OGRSpatialReferenceH* matches = srs.FindMatches(nullptr, &n, &confidence);
    int sure = 0;
    for (int m = 0; m < n; ++m) {
      const long code = named_epsg(*OGRSpatialReference::FromHandle(matches[m]), nullptr);
      if (confidence[m] >= 70 && code > 0) ++sure, epsg = code;
    }
    OSRFreeSRSArray(matches);
    CPLFree(confidence);
    if (sure != 1) epsg = 0;
  }
  return epsg > 0 && epsg < 32767 ? static_cast<int>(epsg) : 0;
}

// The GeoKeyDirectoryTag (record 34735) that LAS 1.0-1.3 readers expect for a CRS with an EPSG code:
// model type (projected or geographic), pixel-is-area, and the code (of the horizontal part: the
// vertical part of a compound CRS is left to the WKT). Empty for a CRS without a code, which then
// travels as WKT only.
std::vector<std::uint8_t> geokeys_of(const OGRSpatialReference& srs) {
  const bool projected = srs.IsProjected();
  if (!projected && !srs.IsGeographic()) return {};
  const int epsg = epsg_code(srs, projected);
  if (epsg == 0) return {};
  struct Key {
    std::uint16_t id, location, count, value;
  };
  const Key keys[] = {{1, 1, 0, 3},                                    // directory version 1, revision 1.0, three keys
                      {1024, 0, 1, std::uint16_t(projected ? 1 : 2)},  // GTModelTypeGeoKey: projected or geographic
                      {1025, 0, 1, 1},                                 // GTRasterTypeGeoKey: pixel is area
                      {std::uint16_t(projected ? 3072 : 2048), 0, 1, std::uint16_t(epsg)}};  // the CRS's code
  std::vector<std::uint8_t> body(sizeof keys);
  std::memcpy(body.data(), keys, sizeof keys);
  return body;
}

// The Extra Bytes VLR (LAS 1.4 R15, 2.6.3): one 192-byte descriptor per attribute, all float32
// (data type 9) without no-data, range, scale or offset.
std::vector<std::uint8_t> extra_bytes_vlr(const std::vector<LasExtraBytes>& extra) {
  std::vector<std::uint8_t> body(192 * extra.size(), 0);
  for (std::size_t k = 0; k < extra.size(); ++k) {
    const std::size_t at = 192 * k;
    body[at + 2] = 9;  // float
    std::copy_n(extra[k].name.begin(), std::min<std::size_t>(extra[k].name.size(), 31), body.begin() + at + 4);
    std::copy_n(extra[k].description.begin(), std::min<std::size_t>(extra[k].description.size(), 31),
                body.begin() + at + 160);
  }
  std::vector<std::uint8_t> vlr(54 + body.size(), 0);
  const std::string user = "LASF_Spec", description = "extra bytes";
  std::copy(user.begin(), user.end(), vlr.begin() + 2);
  put<std::uint16_t>(vlr, 18, 4);
  put<std::uint16_t>(vlr, 20, static_cast<std::uint16_t>(body.size()));
  std::copy(description.begin(), description.end(), vlr.begin() + 22);
  std::copy(body.begin(), body.end(), vlr.begin() + 54);
  return vlr;
}

}  // namespace

void write_las(const std::string& path, const std::vector<LasPoint>& points, const LasWriteOptions& o) {
  const int base = las_point_base_size(o.point_format);
  if (base < 0) throw Error("LAS point format must be 0..10");
  if (o.version_minor != 2 && o.version_minor != 4) throw Error("LAS version must be 1.2 or 1.4");
  if (o.point_format > 5 && o.version_minor < 4) throw Error("point formats 6..10 need LAS 1.4");
  if (!o.extra.empty() && o.version_minor != 4) throw Error("LAS extra bytes need LAS 1.4");
  if (o.extra.size() > 300) throw Error("too many LAS extra bytes attributes");
  for (const LasExtraBytes& e : o.extra) {
    if (e.values.size() != points.size()) throw Error("LAS extra bytes '" + e.name + "' need one value per point");
  }
  const int record = base + 4 * static_cast<int>(o.extra.size());
  const std::uint16_t header_size = o.version_minor == 4 ? 375 : 227;
  // The CRS: in LAS 1.2 as GeoTIFF keys, which 1.2 readers expect, where the CRS has an EPSG code,
  // and as WKT too (which readers that know it prefer); in LAS 1.4 as OGC WKT only (record 2112,
  // with the global encoding's WKT bit), which point formats 6-10 require and 0-5 allow (a choice:
  // R15 suggests GeoTIFF keys there for readers older than 1.4).
  std::vector<std::uint8_t> vlr;
  int vlrs = 0;
  auto add_vlr = [&](const std::vector<std::uint8_t>& record) {
    vlr.insert(vlr.end(), record.begin(), record.end());
    ++vlrs;
  };
  if (!o.crs_wkt.empty()) {
    OGRSpatialReference srs;
    if (srs.importFromWkt(o.crs_wkt.c_str()) != OGRERR_NONE) throw Error("the CRS to write is not valid WKT");
    if (o.crs_wkt.size() + 1 > 0xFFFF) throw Error("the CRS's WKT is too long for a LAS record");
    if (o.version_minor < 4) {
      if (const std::vector<std::uint8_t> keys = geokeys_of(srs); !keys.empty())
        add_vlr(projection_vlr(34735, "GeoTIFF GeoKeyDirectoryTag", keys));
    }
    std::vector<std::uint8_t> text(o.crs_wkt.begin(), o.crs_wkt.end());
    text.push_back(0);
    add_vlr(projection_vlr(2112, "OGC WKT coordinate system", text));
  }
  if (!o.extra.empty()) add_vlr(extra_bytes_vlr(o.extra));
  std::vector<std::uint8_t> h(header_size, 0);
  const std::string signature = "LASF", system = "skyview", software = "skyview write_las";
  std::copy(signature.begin(), signature.end(), h.begin());
  h[24] = 1;
  h[25] = static_cast<std::uint8_t>(o.version_minor);
  std::copy(system.begin(), system.end(), h.begin() + 26);
  std::copy(software.begin(), software.end(), h.begin() + 58);
  put<std::uint16_t>(h, 94, header_size);
  put<std::uint32_t>(h, 96, static_cast<std::uint32_t>(header_size + vlr.size()));
  put<std::uint32_t>(h, 100, static_cast<std::uint32_t>(vlrs));
  // Global encoding's WKT bit: the CRS is WKT (point formats 6-10 must use it, with or without one).
  if (o.version_minor == 4 && (vlrs > 0 || o.point_format >= 6)) put<std::uint16_t>(h, 6, 1u << 4);
  h[104] = static_cast<std::uint8_t>(o.point_format);
  put<std::uint16_t>(h, 105, static_cast<std::uint16_t>(record));
  const bool legacy_ok = o.point_format <= 5 && points.size() <= 0xFFFFFFFFu;
  put<std::uint32_t>(h, 107, legacy_ok ? static_cast<std::uint32_t>(points.size()) : 0);
  // Points by return: legacy 32-bit counts of returns 1..5 at 111, and in LAS 1.4 64-bit counts
  // of returns 1..15 at 255 (readers show these as the survey's return statistics).
  std::uint64_t by_return[15] = {};
  for (const LasPoint& p : points) {
    const int r = o.point_format >= 6 ? p.return_number & 0x0F : p.return_number & 0x07;
    if (r >= 1) ++by_return[r - 1];
  }
  for (int r = 0; r < 5 && legacy_ok; ++r) put<std::uint32_t>(h, 111 + 4 * r, static_cast<std::uint32_t>(by_return[r]));
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double v[3] = {points[i].x, points[i].y, points[i].z};
    for (int k = 0; k < 3; ++k) {
      lo[k] = i ? std::min(lo[k], v[k]) : v[k];
      hi[k] = i ? std::max(hi[k], v[k]) : v[k];
    }
  }
  for (int k = 0; k < 3; ++k) {
    put<double>(h, 131 + 8 * k, o.scale[k]);
    put<double>(h, 155 + 8 * k, o.offset[k]);
    put<double>(h, 179 + 16 * k, hi[k]);
    put<double>(h, 187 + 16 * k, lo[k]);
  }
  if (o.version_minor == 4) {
    put<std::uint64_t>(h, 247, points.size());
    for (int r = 0; r < 15; ++r) put<std::uint64_t>(h, 255 + 8 * r, by_return[r]);
  }
  // The whole file in one buffer, written under a temporary name and renamed into place: a failed
  // write leaves an old file at `path` as it was.
  std::string bytes(h.size() + vlr.size() + static_cast<std::size_t>(record) * points.size(), '\0');
  std::copy(h.begin(), h.end(), bytes.begin());
  std::copy(vlr.begin(), vlr.end(), bytes.begin() + static_cast<std::ptrdiff_t>(h.size()));
  for (std::size_t i = 0; i < points.size(); ++i) {
    const LasPoint& p = points[i];
    const std::size_t at = h.size() + vlr.size() + i * record;
    put<std::int32_t>(bytes, at, quantise(p.x, o.scale[0], o.offset[0]));
    put<std::int32_t>(bytes, at + 4, quantise(p.y, o.scale[1], o.offset[1]));
    put<std::int32_t>(bytes, at + 8, quantise(p.z, o.scale[2], o.offset[2]));
    put<std::uint16_t>(bytes, at + 12, p.intensity);
    if (o.point_format >= 6) {
      bytes[at + 14] = static_cast<char>((p.return_number & 0x0F) | (p.number_of_returns << 4));
      bytes[at + 16] = static_cast<char>(p.classification);
    } else {
      bytes[at + 14] = static_cast<char>((p.return_number & 0x07) | ((p.number_of_returns & 0x07) << 3));
      bytes[at + 15] = static_cast<char>(p.classification & 0x1F);
    }
    for (std::size_t k = 0; k < o.extra.size(); ++k) put<float>(bytes, at + base + 4 * k, o.extra[k].values[i]);
  }
  write_output_file(path, bytes, /*overwrite=*/true);
}

}  // namespace skyview
