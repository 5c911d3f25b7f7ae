#include "skyview/tiling/pyramid_file.h"

#include <bit>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>

#include "skyview/core/error.h"

namespace skyview {

namespace {

constexpr char kMagic[8] = {'S', 'K', 'Y', 'V', 'P', 'Y', 'R', 'M'};
constexpr std::uint32_t kVersion = 2;  // 2: a flags word, and the minima where its bit 0 is set
constexpr std::uint32_t kHasMinima = 1;
constexpr std::uint32_t kMaxSource = 64 << 10;
constexpr int kMaxFirstLevel = 30;

std::uint64_t fnv1a(std::string_view bytes) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (const char c : bytes) {
    h ^= static_cast<unsigned char>(c);
    h *= 0x100000001b3ull;
  }
  return h;
}

template <class T>
void put(std::string& out, T value) {
  using U = std::conditional_t<sizeof(T) == 8, std::uint64_t, std::uint32_t>;
  const U bits = std::bit_cast<U>(value);
  for (std::size_t i = 0; i < sizeof(U); ++i) out.push_back(static_cast<char>((bits >> (8 * i)) & 0xff));
}

// Reads little-endian numbers off the front of the bytes; any read past their end is an Error.
class Reader {
 public:
  Reader(std::string_view bytes, const std::string& name) : bytes_(bytes), name_(name) {}
  template <class T>
  T get(const char* what) {
    using U = std::conditional_t<sizeof(T) == 8, std::uint64_t, std::uint32_t>;
    need(sizeof(U), what);
    U bits = 0;
    for (std::size_t i = 0; i < sizeof(U); ++i)
      bits |= static_cast<U>(static_cast<unsigned char>(bytes_[at_ + i])) << (8 * i);
    at_ += sizeof(U);
    return std::bit_cast<T>(bits);
  }
  std::string_view take(std::size_t n, const char* what) {
    need(n, what);
    const std::string_view s = bytes_.substr(at_, n);
    at_ += n;
    return s;
  }
  std::size_t left() const { return bytes_.size() - at_; }
  [[noreturn]] void fail(const std::string& why) const {
    throw Error("'" + name_ + "' is not a skyview overview pyramid (" + why + ")");
  }

 private:
  void need(std::size_t n, const char* what) const {
    if (left() < n) fail(std::string("it ends before ") + what);
  }
  std::string_view bytes_;
  std::string name_;
  std::size_t at_ = 0;
};

int cells_at(int n, int level) { return static_cast<int>((static_cast<std::int64_t>(n) + (1 << level) - 1) >> level); }

}  // namespace

std::string encode_pyramid(const PyramidLevels& p, const std::string& source) {
  if (source.size() > kMaxSource) throw Error("a pyramid's source text is over 64 KiB (internal error)");
  std::size_t cells = 0;
  for (const Grid<float>& g : p.max) cells += g.size();
  if (!p.min.empty() && p.min.size() != p.max.size()) throw Error("a pyramid's minima and maxima differ in levels");
  if (!p.min.empty()) cells *= 2;
  std::string out;
  out.reserve(64 + source.size() + 8 * p.relief.size() + 4 * cells + 8);
  out.append(kMagic, sizeof kMagic);
  put(out, kVersion);
  put(out, static_cast<std::uint32_t>(p.first_level));
  put(out, static_cast<std::uint32_t>(p.width));
  put(out, static_cast<std::uint32_t>(p.height));
  put(out, static_cast<std::uint32_t>(p.max.size()));
  put(out, static_cast<std::uint32_t>(p.min.empty() ? 0 : kHasMinima));
  put(out, p.lowest);
  put(out, p.highest);
  put(out, static_cast<std::uint32_t>(source.size()));
  out += source;
  for (const double r : p.relief) put(out, r);
  auto put_levels = [&out](const std::vector<Grid<float>>& levels) {
    for (const Grid<float>& g : levels) {
      if constexpr (std::endian::native == std::endian::little) {
        out.append(reinterpret_cast<const char*>(g.data()), g.size() * sizeof(float));
      } else {
        for (const float v : g.values()) put(out, v);
      }
    }
  };
  put_levels(p.max);
  put_levels(p.min);
  put(out, fnv1a(out));
  return out;
}

PyramidLevels decode_pyramid(std::string_view bytes, const std::string& name, std::string* source) {
  Reader in(bytes, name);
  if (in.take(sizeof kMagic, "its magic") != std::string_view(kMagic, sizeof kMagic))
    in.fail("it does not start with SKYVPYRM");
  const std::uint32_t version = in.get<std::uint32_t>("its version");
  if (version != kVersion)
    in.fail("format version " + std::to_string(version) + ", this skyview reads " + std::to_string(kVersion));
  // The checksum first: a damaged file says so, whatever its damage.
  if (bytes.size() < 8 || fnv1a(bytes.substr(0, bytes.size() - 8)) !=
                              Reader(bytes.substr(bytes.size() - 8), name).get<std::uint64_t>("its checksum"))
    in.fail("its checksum does not match: the file is damaged or incomplete");
  PyramidLevels p;
  const std::uint32_t first = in.get<std::uint32_t>("its first level");
  const std::uint32_t width = in.get<std::uint32_t>("its width");
  const std::uint32_t height = in.get<std::uint32_t>("its height");
  const std::uint32_t levels = in.get<std::uint32_t>("its level count");
  const std::uint32_t flags = in.get<std::uint32_t>("its flags");
  if (flags & ~kHasMinima) in.fail("flags " + std::to_string(flags) + " this skyview does not know");
  const bool minima = (flags & kHasMinima) != 0;
  if (first < 1 || first > kMaxFirstLevel) in.fail("first level " + std::to_string(first) + ", not 1 to 30");
  if (width < 1 || height < 1 || width > 0x7fffffffu || height > 0x7fffffffu)
    in.fail("a raster of " + std::to_string(width) + " x " + std::to_string(height) + " cells");
  p.first_level = static_cast<int>(first);
  p.width = static_cast<int>(width);
  p.height = static_cast<int>(height);
  // The levels' sizes follow from the raster's and the first level; so does their count.
  std::vector<std::pair<int, int>> sizes{{cells_at(p.width, p.first_level), cells_at(p.height, p.first_level)}};
  while (sizes.back().first > 1 || sizes.back().second > 1)
    sizes.emplace_back((sizes.back().first + 1) / 2, (sizes.back().second + 1) / 2);
  if (levels != sizes.size())
    in.fail(std::to_string(levels) + " levels where its sizes make " + std::to_string(sizes.size()));
  p.lowest = in.get<double>("its lowest height");
  p.highest = in.get<double>("its highest height");
  const bool empty = p.lowest == INFINITY && p.highest == -INFINITY;
  if (!empty && !(std::isfinite(p.lowest) && std::isfinite(p.highest) && p.lowest <= p.highest))
    in.fail("a height range that is no range");
  const std::uint32_t source_length = in.get<std::uint32_t>("its source's length");
  if (source_length > kMaxSource) in.fail("a source text of " + std::to_string(source_length) + " bytes");
  const std::string_view text = in.take(source_length, "its source");
  for (std::size_t l = 0; l < sizes.size(); ++l) {
    const double r = in.get<double>("its reliefs");
    if (!(std::isfinite(r) && r >= 0)) in.fail("level " + std::to_string(l) + "'s relief is not a height");
    p.relief.push_back(r);
  }
  std::uint64_t cells = 0;
  for (const auto& [w, h] : sizes) cells += static_cast<std::uint64_t>(w) * static_cast<std::uint64_t>(h);
  if (minima) cells *= 2;
  if (in.left() != 4 * cells + 8)
    in.fail(std::to_string(in.left()) + " bytes of levels and checksum where its sizes make " +
            std::to_string(4 * cells + 8));
  auto take_levels = [&](std::vector<Grid<float>>& levels) {
    for (const auto& [w, h] : sizes) {
      Grid<float> g(w, h);
      const std::string_view data = in.take(g.size() * sizeof(float), "its levels");
      if constexpr (std::endian::native == std::endian::little) {
        std::memcpy(g.data(), data.data(), data.size());
      } else {
        Reader values(data, name);
        for (float& v : g.values()) v = values.get<float>("its levels");
      }
      levels.push_back(std::move(g));
    }
  };
  take_levels(p.max);
  if (minima) take_levels(p.min);
  if (source) *source = std::string(text);
  return p;
}

PyramidLevels read_pyramid_file(const std::string& path, std::string* source) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot read the overview pyramid '" + path + "'");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw Error("cannot read the overview pyramid '" + path + "'");
  return decode_pyramid(bytes, path, source);
}

std::string pyramid_checksum(std::string_view bytes) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx",
                static_cast<unsigned long long>(fnv1a(bytes.substr(0, bytes.size() < 8 ? 0 : bytes.size() - 8))));
  return text;
}

}  // namespace skyview
