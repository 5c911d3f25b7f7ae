#include "skyview/tiling/tile_manifest.h"

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "skyview/core/error.h"
#include "skyview/raster/output_files.h"

namespace skyview {

TileManifest::TileManifest(nlohmann::json run) : run_(std::move(run)) {}

std::optional<TileManifest> TileManifest::load(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return std::nullopt;
  std::ifstream in(path);
  nlohmann::json j;
  try {
    in >> j;
    TileManifest m(j.at("run"));
    for (const auto& [name, t] : j.at("tiles").items())
      m.tiles_[name] = {t.at("file").get<std::string>(), t.at("checksum").get<std::string>(),
                        t.value("summary", nlohmann::json::object())};
    if (j.contains("files"))
      for (const auto& [name, f] : j.at("files").items()) m.files_[name] = f;
    return m;
  } catch (const nlohmann::json::exception& e) {
    throw Error("'" + path + "' is not a skyview tile manifest (" + e.what() +
                "); remove it, or give --overwrite to start the tiles again");
  }
}

const TileRecord* TileManifest::find(const std::string& tile) const {
  const auto it = tiles_.find(tile);
  return it == tiles_.end() ? nullptr : &it->second;
}

const nlohmann::json* TileManifest::kept(const std::string& name) const {
  const auto it = files_.find(name);
  return it == files_.end() ? nullptr : &it->second;
}

void TileManifest::save(const std::string& path) const {
  nlohmann::json j;
  j["format"] = "skyview tile manifest 1";
  j["run"] = run_;
  j["tiles"] = nlohmann::json::object();
  for (const auto& [name, t] : tiles_)
    j["tiles"][name] = {{"file", t.file}, {"checksum", t.checksum}, {"summary", t.summary}};
  if (!files_.empty()) j["files"] = files_;
  write_output_file(path, j.dump(2) + "\n", true);
}

std::string file_checksum(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot read '" + path + "'");
  std::uint64_t h = 0xcbf29ce484222325ull;
  char buffer[1 << 16];
  while (in) {
    in.read(buffer, sizeof buffer);
    for (std::streamsize i = 0; i < in.gcount(); ++i) {
      h ^= static_cast<unsigned char>(buffer[i]);
      h *= 0x100000001b3ull;
    }
  }
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
  return text;
}

nlohmann::json input_identity(const std::string& path) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  const auto time = std::filesystem::last_write_time(path, ec);
  return {{"path", path},
          {"size", ec ? 0 : static_cast<std::uint64_t>(size)},
          {"mtime_ns", ec ? 0 : static_cast<long long>(time.time_since_epoch().count())}};
}

}  // namespace skyview
