// EPW reader, tolerant of the quirks real files have (see ../shared/data/weather/SOURCE.md):
// "unknown" text fields, empty design-condition blocks, CRLF line ends, trailing commas, "-0.00",
// missing-value codes, years that change from month to month, and the PVGIS UTC convention.
#include "skyview/sky/epw.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>
#include <vector>

#include "skyview/core/error.h"
#include "skyview/solar/civil_time.h"

namespace skyview {
namespace {

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, ',')) fields.push_back(field);
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

std::string trim(std::string s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return {};
  return s.substr(first, s.find_last_not_of(" \t\r\n") - first + 1);
}

bool parse_number(const std::string& text, double& value) {
  const std::string t = trim(text);
  if (t.empty()) return false;
  const char* begin = t.data() + (t[0] == '+' ? 1 : 0);
  const auto [end, ec] = std::from_chars(begin, t.data() + t.size(), value);
  return ec == std::errc() && end == t.data() + t.size() && std::isfinite(value);
}

[[noreturn]] void fail(const std::string& path, int line, const std::string& what) {
  throw Error(path + ":" + std::to_string(line) + ": " + what);
}

// Solar fields use 9999 (and 999999 for some generators) as "missing".
double solar_value(const std::string& text, int& missing) {
  double v = 0.0;
  // 9999 is EPW's missing code; above 1600 W/m² no irradiance at the ground has been measured (the
  // solar constant is 1361 W/m², cloud edges raise global irradiance by at most a few tenths).
  if (!parse_number(text, v) || v > 1600.0) {
    ++missing;
    return 0.0;
  }
  if (v < 0.0) {
    if (v < -0.5) ++missing;  // "-0.00" is a zero, not a missing value
    return 0.0;
  }
  return v;
}

int days_in_month(int year, int month) {
  static const int days[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  const bool leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
  return month == 2 && leap ? 29 : days[month - 1];
}

// The hours of the one period a DATA PERIODS line declares ("DATA PERIODS,1,1,Data,Sunday, 1/ 1,12/31"),
// in a 365-day year; 0 where it declares several or its dates are unreadable.
int declared_hours(const std::vector<std::string>& fields) {
  double periods = 0;
  if (fields.size() < 7 || !parse_number(fields[1], periods) || periods != 1.0) return 0;
  // "M/D", or "YYYY/M/D" (the Athens sample's generator writes the year too).
  auto day_of_year = [](const std::string& text) {
    const std::size_t slash = text.rfind('/');
    const std::size_t before =
        slash == std::string::npos || slash == 0 ? std::string::npos : text.rfind('/', slash - 1);
    const std::size_t month_at = before == std::string::npos ? 0 : before + 1;
    double month = 0, day = 0;
    if (slash == std::string::npos || !parse_number(text.substr(month_at, slash - month_at), month) ||
        !parse_number(text.substr(slash + 1), day) || month < 1 || month > 12 || day < 1 ||
        day > days_in_month(2001, static_cast<int>(month)))
      return -1;
    int n = static_cast<int>(day);
    for (int m = 1; m < static_cast<int>(month); ++m) n += days_in_month(2001, m);
    return n;
  };
  const int first = day_of_year(fields[5]), last = day_of_year(fields[6]);
  if (first < 1 || last < 1) return 0;
  return 24 * (last >= first ? last - first + 1 : 365 - first + 1 + last);
}

}  // namespace

EpwFile read_epw(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open EPW file");
  EpwFile file;
  bool have_location = false, in_data = false;
  static const std::regex offset_comment(R"(Irradiance Time Offset \(h\)\s*:\s*([-+0-9.eE]+))", std::regex::icase);
  std::string line;
  int number = 0;
  // Line of the record seen for each month, day and hour: an EPW holds one year, so a repeated
  // hour would be counted twice.
  std::vector<int> seen_at(13 * 32 * 25, 0);
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (number == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);  // a UTF-8 byte-order mark
    if (trim(line).empty()) continue;
    const auto fields = split_fields(line);
    const std::string key = trim(fields[0]);
    if (!in_data) {
      if (key == "LOCATION") {
        if (fields.size() < 10) fail(path, number, "LOCATION line has fewer than 10 fields");
        EpwLocation& loc = file.location;
        loc.city = trim(fields[1]);
        if (!parse_number(fields[6], loc.latitude_deg) || !parse_number(fields[7], loc.longitude_deg) ||
            !parse_number(fields[8], loc.time_zone_h) || std::abs(loc.latitude_deg) > 90.0 ||
            std::abs(loc.longitude_deg) > 180.0 || std::abs(loc.time_zone_h) > 14.0) {
          fail(path, number, "LOCATION line has no valid latitude, longitude and time zone");
        }
        if (!parse_number(fields[9], loc.elevation_m)) loc.elevation_m = 0.0;
        have_location = true;
      } else if (key.rfind("COMMENTS", 0) == 0) {
        std::smatch m;
        if (std::regex_search(line, m, offset_comment)) {
          double offset = 0.0;
          if (!parse_number(m[1].str(), offset) || std::abs(offset) > 1.0) {
            fail(path, number, "unreadable Irradiance Time Offset");
          }
          file.hours_in_utc = true;  // PVGIS writes UTC hours with this comment
          file.irradiance_time_offset_h = offset;
        }
      } else if (key == "DATA PERIODS") {
        // Records per hour: each record is read as one hour, so sub-hourly data would count n times.
        double per_hour = 1.0;
        if (fields.size() > 2 && (!parse_number(fields[2], per_hour) || per_hour != 1.0)) {
          fail(path, number,
               "DATA PERIODS gives " + trim(fields[2]) +
                   " records per hour; skyview reads hourly EPW files only (one record per hour)");
        }
        file.declared_hours = declared_hours(fields);
        in_data = true;
      }
      continue;
    }
    if (fields.size() < 16) fail(path, number, "data record has fewer than 16 fields");
    double year, month, day, hour;
    if (!parse_number(fields[0], year) || !parse_number(fields[1], month) || !parse_number(fields[2], day) ||
        !parse_number(fields[3], hour) || month < 1 || month > 12 || day < 1 || hour < 1 || hour > 24) {
      fail(path, number, "data record has no valid date and hour");
    }
    EpwRecord r;
    r.year = static_cast<int>(year);
    r.month = static_cast<int>(month);
    r.day = static_cast<int>(day);
    r.hour = static_cast<int>(hour);
    if (r.day > days_in_month(r.year, r.month)) fail(path, number, "data record has a day beyond its month");
    int& first = seen_at[(r.month * 32 + r.day) * 25 + r.hour];
    if (first > 0) {
      fail(path, number,
           "data record repeats month " + std::to_string(r.month) + ", day " + std::to_string(r.day) + ", hour " +
               std::to_string(r.hour) + " of line " + std::to_string(first) + " (an EPW file holds one year)");
    }
    first = number;
    r.global_horizontal = solar_value(fields[13], file.missing_solar_values);
    r.direct_normal = solar_value(fields[14], file.missing_solar_values);
    r.diffuse_horizontal = solar_value(fields[15], file.missing_solar_values);
    if (double albedo; fields.size() > 32 && parse_number(fields[32], albedo) && albedo >= 0.0 && albedo <= 1.0)
      r.albedo = albedo;
    file.records.push_back(r);
  }
  if (!have_location) throw Error(path + ": not an EPW file (no LOCATION line)");
  if (!in_data) throw Error(path + ": no DATA PERIODS line (the last of the EPW header's eight) before the records");
  if (file.records.empty()) throw Error(path + ": EPW file has no data records");
  const double zone_h = file.hours_in_utc ? 0.0 : file.location.time_zone_h;
  for (EpwRecord& r : file.records) {
    const double hours = r.hour + file.irradiance_time_offset_h - zone_h;
    r.time_utc = static_cast<double>(days_from_civil(CivilDate{r.year, r.month, r.day})) * 86400.0 + hours * 3600.0;
  }
  return file;
}

std::optional<double> mean_albedo(const EpwFile& file) {
  double sum = 0.0, weight = 0.0;
  for (const EpwRecord& r : file.records) {
    if (std::isnan(r.albedo) || !(r.global_horizontal > 0.0)) continue;
    sum += r.albedo * r.global_horizontal;
    weight += r.global_horizontal;
  }
  if (!(weight > 0.0)) return std::nullopt;
  return sum / weight;
}

}  // namespace skyview
