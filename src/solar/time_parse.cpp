// ISO 8601 reading for the solar commands: the date, the time of day, then a UTC offset or
// an IANA zone name. Hand-written because years -2000..6000 and zone names after a space are
// outside what std::get_time or strptime read.
#include "skyview/solar/time_parse.h"

#include <cctype>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "skyview/core/error.h"

namespace skyview {

namespace {

// A cursor over the text that throws with the whole input quoted.
class Reader {
 public:
  explicit Reader(const std::string& text) : text_(text) {}
  bool done() const { return pos_ >= text_.size(); }
  char peek() const { return done() ? '\0' : text_[pos_]; }
  bool accept(char c) {
    if (peek() != c) return false;
    ++pos_;
    return true;
  }
  void expect(char c, const char* what) {
    if (!accept(c)) fail(what);
  }
  // Reads exactly `n` digits (n > 0) or, with n == 0, one or more.
  long digits(int n, const char* what) {
    const std::size_t start = pos_;
    while (!done() && std::isdigit(static_cast<unsigned char>(peek())) && (n == 0 || pos_ - start < std::size_t(n))) {
      ++pos_;
    }
    if (pos_ == start || (n > 0 && pos_ - start != std::size_t(n)) || pos_ - start > 9) fail(what);
    return std::stol(text_.substr(start, pos_ - start));
  }
  double fraction() {
    const std::size_t start = pos_;
    while (!done() && std::isdigit(static_cast<unsigned char>(peek()))) ++pos_;
    if (pos_ == start) fail("digits after the decimal point");
    return std::stod("0." + text_.substr(start, pos_ - start));
  }
  std::string rest() const { return text_.substr(pos_); }
  [[noreturn]] void fail(const char* what) const {
    throw Error("cannot read time '" + text_ + "': expected " + what +
                " (e.g. 2003-10-17T12:30:30-07:00, ...Z, or '2024-06-21T12:00 Europe/Athens')");
  }

 private:
  const std::string& text_;
  std::size_t pos_ = 0;
};

bool is_leap(long year) { return (year % 4 == 0 && year % 100 != 0) || year % 400 == 0; }

int days_in_month(long year, int month) {
  static const int days[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  return month == 2 && is_leap(year) ? 29 : days[month - 1];
}

std::vector<std::string> split_whitespace(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> parts;
  for (std::string word; in >> word;) parts.push_back(word);
  return parts;
}

// Second 60 names a leap second, which UTC inserts only at the end of 30 June or 31 December:
// anywhere else it is a typing error that would silently become the next minute.
void check_leap_second(const std::string& text, const CivilDateTime& local, double unix_utc) {
  if (local.second < 60.0) return;
  const double after = std::floor(unix_utc);  // the leap second's instant, as POSIX time counts it
  const auto days = static_cast<std::int64_t>(std::floor(after / 86400.0));
  const CivilDate next = civil_from_days(days);
  if (after == static_cast<double>(days) * 86400.0 && next.day == 1 && (next.month == 1 || next.month == 7)) return;
  throw Error("'" + text + "' has second 60, which exists only in a leap second (23:59:60 UTC on 30 June or " +
              "31 December)");
}

}  // namespace

ParsedTime parse_time(const std::string& text, const std::string& default_zone) {
  // "DATE[T]TIME[OFFSET] [ZONE]" or "DATE TIME[OFFSET] [ZONE]".
  std::vector<std::string> parts = split_whitespace(text);
  if (parts.empty()) throw Error("empty time");
  std::string stamp = parts[0], zone;
  std::size_t next = 1;
  if (next < parts.size() && std::isdigit(static_cast<unsigned char>(parts[next][0]))) stamp += "T" + parts[next++];
  if (next < parts.size()) zone = parts[next++];
  if (next < parts.size()) throw Error("cannot read time '" + text + "': unexpected '" + parts[next] + "'");

  Reader in(stamp);
  long sign = 1;
  if (in.accept('-')) {
    sign = -1;
  } else {
    in.accept('+');
  }
  CivilDateTime local;
  const long year = sign * in.digits(0, "a year");
  in.expect('-', "'-' after the year");
  const long month = in.digits(2, "a two-digit month");
  in.expect('-', "'-' after the month");
  const long day = in.digits(2, "a two-digit day");
  if (year < kMinSolarYear || year > kMaxSolarYear) {
    throw Error("year " + std::to_string(year) + " in '" + text + "' is outside " + std::to_string(kMinSolarYear) +
                ".." + std::to_string(kMaxSolarYear));
  }
  if (month < 1 || month > 12 || day < 1 || day > days_in_month(year, static_cast<int>(month))) {
    throw Error("'" + text + "' is not a calendar date");
  }
  local.date = {static_cast<int>(year), static_cast<int>(month), static_cast<int>(day)};
  if (in.accept('T') || in.accept('t')) {
    local.hour = static_cast<int>(in.digits(2, "a two-digit hour"));
    if (in.accept(':')) {
      local.minute = static_cast<int>(in.digits(2, "two-digit minutes"));
      if (in.accept(':')) {
        local.second = static_cast<double>(in.digits(2, "two-digit seconds"));
        if (in.accept('.') || in.accept(',')) local.second += in.fraction();
      }
    }
    const bool end_of_day = local.hour == 24 && local.minute == 0 && local.second == 0.0;
    if ((local.hour > 23 && !end_of_day) || local.minute > 59 || local.second >= 61.0) {
      throw Error("'" + text + "' is not a time of day");
    }
  }

  std::optional<double> offset;
  if (in.accept('Z') || in.accept('z')) {
    offset = 0.0;
  } else if (in.peek() == '+' || in.peek() == '-') {
    const double offset_sign = in.accept('-') ? -1.0 : (in.accept('+'), 1.0);
    const long hours = in.digits(2, "a two-digit offset hour");
    long minutes = 0, seconds = 0;
    const bool extended = in.accept(':');
    if (extended || !in.done()) minutes = in.digits(2, "two-digit offset minutes");
    // Local mean time's seconds, as skyview prints them (+01:19:32), read back.
    if (extended && in.accept(':')) seconds = in.digits(2, "two-digit offset seconds");
    if (hours > 18 || minutes > 59 || seconds > 59 || (hours == 18 && minutes + seconds > 0))
      throw Error("UTC offset in '" + text + "' is outside -18:00..+18:00");
    offset = offset_sign * (hours * 3600.0 + minutes * 60.0 + static_cast<double>(seconds));
  }
  if (!in.done()) in.fail("the end of the time or a UTC offset");

  ParsedTime result;
  if (offset && !zone.empty()) throw Error("time '" + text + "' gives both a UTC offset and a zone; give one");
  if (offset) {
    result.utc_offset_s = *offset;
    result.unix_utc = seconds_from_civil(local) - *offset;
    check_leap_second(text, local, result.unix_utc);
    return result;
  }
  if (zone.empty()) zone = default_zone;
  if (zone.empty()) {
    throw Error("time '" + text + "' has no UTC offset or zone: add Z, +hh:mm, a zone name, or --tz");
  }
  check_time_zone(zone);
  result.zone = zone;
  result.unix_utc = unix_from_local(zone, local, &result.ambiguous);
  result.utc_offset_s = utc_offset_s(zone, result.unix_utc);
  check_leap_second(text, local, result.unix_utc);
  return result;
}

double parse_duration_s(const std::string& text) {
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  const std::string unit = used ? text.substr(used) : "";
  double scale = 0.0;
  if (unit.empty() || unit == "s" || unit == "sec") scale = 1.0;
  if (unit == "m" || unit == "min") scale = 60.0;
  if (unit == "h") scale = 3600.0;
  if (unit == "d") scale = 86400.0;
  if (used == 0 || scale == 0.0 || !std::isfinite(value) || value <= 0.0) {
    throw Error("cannot read duration '" + text + "': expected a positive number with s, m, min, h or d (e.g. 1h)");
  }
  return value * scale;
}

}  // namespace skyview
