#pragma once
// The record of a run written as one GeoTIFF per tile (--tiles-dir): which run the folder belongs
// to (input path, size and modification time, options, version) and each finished tile with a
// checksum of its file, so that a rerun after a crash or a kill skips the tiles that are whole and
// redoes the rest. Saved after every tile under a temporary name and renamed, so that it always
// describes files that exist in full.
#include <map>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace skyview {

struct TileRecord {
  std::string file;                                   // the tile's file name in the folder
  std::string checksum;                               // file_checksum of it
  nlohmann::json summary = nlohmann::json::object();  // what the run sums over tiles (edge cells ...)
};

class TileManifest {
 public:
  explicit TileManifest(nlohmann::json run);
  // The manifest at `path`, or nullopt where there is none. Throws skyview::Error for a file that
  // is not a manifest.
  static std::optional<TileManifest> load(const std::string& path);
  const nlohmann::json& run() const { return run_; }
  // The same input, options and version.
  bool same_run(const nlohmann::json& run) const { return run_ == run; }
  const TileRecord* find(const std::string& tile) const;
  void record(const std::string& tile, TileRecord record) { tiles_[tile] = std::move(record); }
  void forget(const std::string& tile) { tiles_.erase(tile); }
  std::size_t size() const { return tiles_.size(); }
  // The run's other files (the far field's pyramid), each a record of its own ("file", "checksum").
  void keep(const std::string& name, nlohmann::json record) { files_[name] = std::move(record); }
  const nlohmann::json* kept(const std::string& name) const;
  // Throws skyview::Error naming `path` when it cannot be written.
  void save(const std::string& path) const;

 private:
  nlohmann::json run_;
  std::map<std::string, TileRecord> tiles_;
  std::map<std::string, nlohmann::json> files_;
};

// 64-bit FNV-1a of the file's bytes, as 16 hex digits; throws skyview::Error when it cannot be read.
std::string file_checksum(const std::string& path);

// What identifies an input file: its path as given, its size and modification time.
nlohmann::json input_identity(const std::string& path);

}  // namespace skyview
