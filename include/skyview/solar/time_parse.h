#pragma once
// Reading times for the solar commands: ISO 8601 with a UTC offset ("2003-10-17T12:30:30-07:00",
// "...Z") or followed by an IANA zone name ("2024-06-21T12:00 Europe/Athens"), years -2000..6000
// of the proleptic Gregorian calendar. Zone rules come from the system tz database
// (/usr/share/zoneinfo, Debian package tzdata).
#include <string>
#include <vector>

#include "skyview/solar/civil_time.h"

namespace skyview {

// Earliest and latest year the solar code accepts (the SPA's validity range).
constexpr int kMinSolarYear = -2000;
constexpr int kMaxSolarYear = 6000;

struct ParsedTime {
  double unix_utc = 0.0;      // the instant, seconds since 1970-01-01T00:00Z
  double utc_offset_s = 0.0;  // local minus UTC at that instant
  std::string zone;           // IANA name when one was given (directly or as default), else empty
  bool ambiguous = false;     // the local time occurs twice in `zone` (clocks set back); the earlier is taken
};

// Parses `text`. When it carries neither an offset nor a zone, `default_zone` is used (an IANA
// name, or "UTC"); when that is empty too, throws. A local time that a DST change skips throws;
// one that occurs twice resolves to the earlier instant (and sets `ambiguous`). Second 60 is
// accepted only in a leap second: the last second of 30 June or 31 December, UTC. Throws
// skyview::Error on bad input or years outside kMinSolarYear..kMaxSolarYear.
ParsedTime parse_time(const std::string& text, const std::string& default_zone = "");

// "1h", "30m", "30min", "15s", "1d", "90" (seconds), "1.5h"; must be > 0. Throws skyview::Error.
double parse_duration_s(const std::string& text);

// Throws skyview::Error unless `zone` names a zone of the system tz database.
void check_time_zone(const std::string& zone);

// UTC offset in seconds of IANA `zone` at a Unix time (DST included).
double utc_offset_s(const std::string& zone, double unix_time_utc);

// The same for many instants at once: one switch of the C library's zone for the whole batch
// (a single utc_offset_s call re-reads the zone file, ~0.1 ms).
std::vector<double> utc_offsets_s(const std::string& zone, const std::vector<double>& unix_times_utc);

// The instant of a wall-clock time in `zone` (earlier one when ambiguous, which `ambiguous` then
// tells; throws when skipped).
double unix_from_local(const std::string& zone, const CivilDateTime& local, bool* ambiguous = nullptr);

}  // namespace skyview
