// UTC offsets of IANA zones from the system tz database. Debian 12's GCC 12 has no
// std::chrono::tzdb, and linking the date/tz library would need a build-wide change, so this
// asks the C library: TZ is switched for one localtime_r call under a mutex and restored.
// Other threads that call localtime at that moment could see the zone; skyview does not.
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "skyview/core/error.h"
#include "skyview/solar/time_parse.h"

namespace skyview {

namespace {

std::mutex& tz_mutex() {
  static std::mutex m;
  return m;
}

std::string zoneinfo_dir() {
  const char* dir = std::getenv("TZDIR");
  return dir && *dir ? dir : "/usr/share/zoneinfo";
}

bool is_utc(const std::string& zone) { return zone == "UTC" || zone == "Etc/UTC" || zone == "Z"; }

// Sets TZ for its lifetime and puts the previous value back.
class ScopedTz {
 public:
  explicit ScopedTz(const std::string& zone) {
    if (const char* old = std::getenv("TZ")) previous_ = old;
    ::setenv("TZ", (":" + zone).c_str(), 1);
    ::tzset();
  }
  ~ScopedTz() {
    if (previous_) {
      ::setenv("TZ", previous_->c_str(), 1);
    } else {
      ::unsetenv("TZ");
    }
    ::tzset();
  }
  ScopedTz(const ScopedTz&) = delete;
  ScopedTz& operator=(const ScopedTz&) = delete;

 private:
  std::optional<std::string> previous_;
};

}  // namespace

void check_time_zone(const std::string& zone) {
  if (is_utc(zone)) return;
  bool plain = !zone.empty() && zone.front() != '/' && zone.find("..") == std::string::npos;
  for (char c : zone) {
    const bool ok = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '/' ||
                    c == '_' || c == '-' || c == '+';
    plain = plain && ok;
  }
  if (!plain) throw Error("'" + zone + "' is not a time-zone name (expected e.g. Europe/Athens)");
  const std::string path = zoneinfo_dir() + "/" + zone;
  std::ifstream in(path, std::ios::binary);
  char magic[4] = {};
  if (!in.read(magic, 4) || std::string(magic, 4) != "TZif") {
    throw Error("unknown time zone '" + zone + "' (not in " + zoneinfo_dir() + "; install tzdata)");
  }
}

double utc_offset_s(const std::string& zone, double unix_time_utc) {
  if (is_utc(zone)) return 0.0;
  const std::time_t t = static_cast<std::time_t>(std::floor(unix_time_utc));
  std::tm local{};
  std::lock_guard<std::mutex> lock(tz_mutex());
  ScopedTz scoped(zone);
  if (!::localtime_r(&t, &local)) throw Error("cannot convert " + std::to_string(unix_time_utc) + " to zone " + zone);
  return static_cast<double>(local.tm_gmtoff);
}

std::vector<double> utc_offsets_s(const std::string& zone, const std::vector<double>& unix_times_utc) {
  std::vector<double> offsets(unix_times_utc.size(), 0.0);
  if (is_utc(zone) || unix_times_utc.empty()) return offsets;
  std::lock_guard<std::mutex> lock(tz_mutex());
  ScopedTz scoped(zone);
  for (std::size_t i = 0; i < unix_times_utc.size(); ++i) {
    const std::time_t t = static_cast<std::time_t>(std::floor(unix_times_utc[i]));
    std::tm local{};
    if (!::localtime_r(&t, &local)) throw Error("cannot convert a time to zone " + zone);
    offsets[i] = static_cast<double>(local.tm_gmtoff);
  }
  return offsets;
}

double unix_from_local(const std::string& zone, const CivilDateTime& local, bool* ambiguous) {
  const double wall = seconds_from_civil(local);
  if (ambiguous) *ambiguous = false;
  if (is_utc(zone)) return wall;
  // The offsets a day either side bracket any single transition; a candidate instant is valid
  // when the zone's offset at that instant is the one that produced it.
  const double offsets[2] = {utc_offset_s(zone, wall - 86400.0), utc_offset_s(zone, wall + 86400.0)};
  std::optional<double> earliest;
  bool twice = false;
  for (double offset : offsets) {
    const double candidate = wall - offset;
    if (utc_offset_s(zone, candidate) != offset) continue;
    if (earliest && candidate != *earliest) twice = true;
    if (!earliest || candidate < *earliest) earliest = candidate;
  }
  if (ambiguous) *ambiguous = twice;
  if (!earliest) {
    throw Error("local time " + format_iso_utc(wall).substr(0, 19) + " does not exist in " + zone +
                " (skipped by a clock change)");
  }
  return *earliest;
}

}  // namespace skyview
