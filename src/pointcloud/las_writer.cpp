#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "skyview/error.h"
#include "skyview/las_file.h"
#include "skyview/raster_io.h"

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

}  // namespace

void write_las(const std::string& path, const std::vector<LasPoint>& points, const LasWriteOptions& o) {
  const int base = las_point_base_size(o.point_format);
  if (base < 0) throw Error("LAS point format must be 0..10");
  if (o.version_minor != 2 && o.version_minor != 4) throw Error("LAS version must be 1.2 or 1.4");
  if (o.point_format > 5 && o.version_minor < 4) throw Error("point formats 6..10 need LAS 1.4");
  const std::uint16_t header_size = o.version_minor == 4 ? 375 : 227;
  std::vector<std::uint8_t> vlr;
  if (!o.crs_wkt.empty()) {
    vlr.assign(54 + o.crs_wkt.size() + 1, 0);
    const std::string user = "LASF_Projection";
    std::copy(user.begin(), user.end(), vlr.begin() + 2);
    put<std::uint16_t>(vlr, 18, 2112);
    put<std::uint16_t>(vlr, 20, static_cast<std::uint16_t>(o.crs_wkt.size() + 1));
    std::copy(o.crs_wkt.begin(), o.crs_wkt.end(), vlr.begin() + 54);
  }
  std::vector<std::uint8_t> h(header_size, 0);
  const std::string signature = "LASF", system = "skyview", software = "skyview write_las";
  std::copy(signature.begin(), signature.end(), h.begin());
  h[24] = 1;
  h[25] = static_cast<std::uint8_t>(o.version_minor);
  std::copy(system.begin(), system.end(), h.begin() + 26);
  std::copy(software.begin(), software.end(), h.begin() + 58);
  put<std::uint16_t>(h, 94, header_size);
  put<std::uint32_t>(h, 96, static_cast<std::uint32_t>(header_size + vlr.size()));
  put<std::uint32_t>(h, 100, vlr.empty() ? 0 : 1);
  h[104] = static_cast<std::uint8_t>(o.point_format);
  put<std::uint16_t>(h, 105, static_cast<std::uint16_t>(base));
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
  std::string bytes(h.size() + vlr.size() + static_cast<std::size_t>(base) * points.size(), '\0');
  std::copy(h.begin(), h.end(), bytes.begin());
  std::copy(vlr.begin(), vlr.end(), bytes.begin() + static_cast<std::ptrdiff_t>(h.size()));
  for (std::size_t i = 0; i < points.size(); ++i) {
    const LasPoint& p = points[i];
    const std::size_t at = h.size() + vlr.size() + i * base;
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
  }
  write_output_file(path, bytes, /*overwrite=*/true);
}

}  // namespace skyview
