// ISO 8601 times with offsets and IANA zones, the proleptic Gregorian calendar over the SPA's
// years, durations, and one-line errors for bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "skyview/solar/civil_time.h"
#include "skyview/core/error.h"
#include "skyview/solar/time_parse.h"

using namespace skyview;

TEST(TimeCalendar, KnownDays) {
  EXPECT_EQ(days_from_civil({1970, 1, 1}), 0);
  EXPECT_EQ(days_from_civil({2000, 3, 1}), 11017);
  EXPECT_EQ(days_from_civil({1969, 12, 31}), -1);
  // JD 0 is noon of -4713-11-24 in the proleptic Gregorian calendar.
  const double jd0 = unix_from_julian_day(0.0);
  const CivilDate d = civil_from_days(static_cast<std::int64_t>(std::floor(jd0 / 86400.0)));
  EXPECT_EQ(d.year, -4713);
  EXPECT_EQ(d.month, 11);
  EXPECT_EQ(d.day, 24);
  EXPECT_DOUBLE_EQ(julian_day_from_unix(seconds_from_civil({{2000, 1, 1}, 12})), 2451545.0);
}

TEST(TimeCalendar, RoundTripOverTheSolarRange) {
  const std::int64_t first = days_from_civil({-2000, 1, 1}), last = days_from_civil({6000, 12, 31});
  EXPECT_EQ(last - first + 1, 8001LL * 365 + 8001 / 4 - 80 + 20 + 1);  // 1941 leap years in -2000..6000
  for (std::int64_t day = first; day <= last; day += 97) {
    EXPECT_EQ(days_from_civil(civil_from_days(day)), day);
  }
}

TEST(TimeParse, UtcOffsets) {
  const double expected = seconds_from_civil({{2003, 10, 17}, 19, 30, 30});
  EXPECT_DOUBLE_EQ(parse_time("2003-10-17T12:30:30-07:00").unix_utc, expected);
  EXPECT_DOUBLE_EQ(parse_time("2003-10-17T12:30:30-0700").unix_utc, expected);
  EXPECT_DOUBLE_EQ(parse_time("2003-10-17 12:30:30-07").unix_utc, expected);
  EXPECT_DOUBLE_EQ(parse_time("2003-10-17T19:30:30Z").unix_utc, expected);
  EXPECT_DOUBLE_EQ(parse_time("2003-10-18T01:00:30+05:30").unix_utc, expected);
  EXPECT_DOUBLE_EQ(parse_time("2003-10-17T19:30:30.25Z").unix_utc, expected + 0.25);
  EXPECT_DOUBLE_EQ(parse_time("2003-10-17Z").unix_utc, seconds_from_civil({{2003, 10, 17}}));
  EXPECT_DOUBLE_EQ(parse_time("2003-10-17T24:00Z").unix_utc, seconds_from_civil({{2003, 10, 18}}));
  EXPECT_EQ(parse_time("2003-10-17T12:30:30-07:00").utc_offset_s, -7 * 3600.0);
}

TEST(TimeParse, IanaZonesWithDaylightSaving) {
  const ParsedTime summer = parse_time("2024-06-21T12:00 Europe/Athens");
  EXPECT_DOUBLE_EQ(summer.unix_utc, seconds_from_civil({{2024, 6, 21}, 9}));
  EXPECT_EQ(summer.utc_offset_s, 3 * 3600.0);
  EXPECT_EQ(summer.zone, "Europe/Athens");
  const ParsedTime winter = parse_time("2024-01-15T12:00", "Europe/Athens");  // zone from --tz
  EXPECT_DOUBLE_EQ(winter.unix_utc, seconds_from_civil({{2024, 1, 15}, 10}));
  EXPECT_EQ(winter.utc_offset_s, 2 * 3600.0);
  EXPECT_DOUBLE_EQ(parse_time("2024-06-21 12:00 America/Denver").unix_utc, seconds_from_civil({{2024, 6, 21}, 18}));
  EXPECT_DOUBLE_EQ(parse_time("2024-06-21T12:00 UTC").unix_utc, seconds_from_civil({{2024, 6, 21}, 12}));
  // 03:30 happens twice on 2024-10-27 in Athens: the earlier (EEST, +03:00) is chosen.
  const ParsedTime twice = parse_time("2024-10-27T03:30 Europe/Athens");
  EXPECT_DOUBLE_EQ(twice.unix_utc, seconds_from_civil({{2024, 10, 27}, 0, 30}));
  EXPECT_TRUE(twice.ambiguous);
  EXPECT_EQ(twice.utc_offset_s, 3 * 3600.0);
  EXPECT_FALSE(parse_time("2024-10-27T04:30 Europe/Athens").ambiguous);
  EXPECT_FALSE(summer.ambiguous);
  // 03:30 never happens on 2024-03-31 in Athens.
  EXPECT_THROW(parse_time("2024-03-31T03:30 Europe/Athens"), Error);
  EXPECT_EQ(utc_offset_s("Asia/Kolkata", 0.0), 5.5 * 3600.0);
  const std::vector<double> offsets = utc_offsets_s("Europe/Athens", {winter.unix_utc, summer.unix_utc});
  EXPECT_EQ(offsets, (std::vector<double>{7200.0, 10800.0}));
}

TEST(TimeParse, ExtremeYears) {
  EXPECT_DOUBLE_EQ(parse_time("-2000-01-01T00:00Z").unix_utc, seconds_from_civil({{-2000, 1, 1}}));
  EXPECT_DOUBLE_EQ(parse_time("6000-12-31T23:59:59Z").unix_utc, seconds_from_civil({{6000, 12, 31}, 23, 59, 59}));
  EXPECT_DOUBLE_EQ(parse_time("+0800-06-01T00:00Z").unix_utc, seconds_from_civil({{800, 6, 1}}));
  EXPECT_THROW(parse_time("6001-01-01T00:00Z"), Error);
  EXPECT_THROW(parse_time("-2001-12-31T00:00Z"), Error);
  EXPECT_EQ(format_iso_utc(seconds_from_civil({{-2000, 1, 1}, 6})), "-2000-01-01T06:00:00Z");
  EXPECT_EQ(format_iso_utc(seconds_from_civil({{6000, 2, 29}})), "6000-02-29T00:00:00Z");
  EXPECT_EQ(format_iso_local(seconds_from_civil({{2003, 10, 17}, 19, 30, 30}), -7 * 3600.0),
            "2003-10-17T12:30:30-07:00");
  EXPECT_EQ(format_iso_utc(59.9996, 3), "1970-01-01T00:01:00.000Z");
}

TEST(TimeParse, BadInputIsOneLineError) {
  for (const char* bad :
       {"", "2023-02-29T00:00Z", "1900-02-29Z", "2024-13-01Z", "2024-01-01T25:00Z", "2024-01-01T12:60Z", "2024-1-01Z",
        "yesterday", "2024-01-01T12:00+19:00", "2024-01-01T12:00", "2024-01-01T12:00 Mars/Olympus",
        "2024-01-01T12:00 ../etc/passwd", "2024-01-01T12:00Z Europe/Athens", "2024-01-01T12:00Zjunk"}) {
    try {
      parse_time(bad);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
  }
  EXPECT_NO_THROW(parse_time("2024-02-29T00:00Z"));
  EXPECT_NO_THROW(parse_time("2000-02-29T00:00Z"));
}

// Second 60 exists only in a leap second, at the end of 30 June or 31 December UTC, wherever the
// clock that shows it is.
TEST(TimeParse, SecondSixtyOnlyInALeapSecond) {
  EXPECT_DOUBLE_EQ(parse_time("2016-12-31T23:59:60Z").unix_utc, seconds_from_civil({{2017, 1, 1}}));
  EXPECT_DOUBLE_EQ(parse_time("2015-06-30T23:59:60.5Z").unix_utc, seconds_from_civil({{2015, 7, 1}}) + 0.5);
  EXPECT_DOUBLE_EQ(parse_time("2017-01-01T00:59:60+01:00").unix_utc, seconds_from_civil({{2017, 1, 1}}));
  EXPECT_NO_THROW(parse_time("2017-01-01T00:59:60 Europe/Paris"));
  for (const char* bad : {"2016-12-30T23:59:60Z", "2016-12-31T23:58:60Z", "2016-12-31T23:59:60+01:00",
                          "2016-06-30T12:30:60 Europe/Paris"}) {
    try {
      parse_time(bad);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("leap second"), std::string::npos) << e.what();
    }
  }
}

TEST(TimeParse, Durations) {
  EXPECT_EQ(parse_duration_s("1h"), 3600.0);
  EXPECT_EQ(parse_duration_s("30m"), 1800.0);
  EXPECT_EQ(parse_duration_s("15min"), 900.0);
  EXPECT_EQ(parse_duration_s("1.5h"), 5400.0);
  EXPECT_EQ(parse_duration_s("90"), 90.0);
  EXPECT_EQ(parse_duration_s("1d"), 86400.0);
  EXPECT_THROW(parse_duration_s("0h"), Error);
  EXPECT_THROW(parse_duration_s("-1h"), Error);
  EXPECT_THROW(parse_duration_s("1 week"), Error);
  EXPECT_THROW(parse_duration_s("h"), Error);
}
