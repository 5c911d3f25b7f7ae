// EPW reading, including the PVGIS file's quirks and UTC convention.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "sky_test_support.h"
#include "skyview/solar/civil_time.h"
#include "skyview/sky/epw.h"
#include "skyview/core/error.h"
#include "temp_dir.h"

namespace skyview {
namespace {

TEST(Epw, ReadsTmy3WithMidHourLocalStandardTime) {
  SKYVIEW_REQUIRE_SHARED(path, "weather/chicago.epw");
  const EpwFile f = read_epw(path);
  EXPECT_EQ(f.records.size(), 8760u);
  EXPECT_NEAR(f.location.latitude_deg, 41.98, 1e-6);
  EXPECT_NEAR(f.location.longitude_deg, -87.92, 1e-6);
  EXPECT_EQ(f.location.time_zone_h, -6.0);
  EXPECT_FALSE(f.hours_in_utc);
  // Hour 1 of 1 January covers 00:00-01:00 CST: mid-hour 00:30 CST = 06:30 UTC.
  const EpwRecord& r = f.records.front();
  EXPECT_NEAR(r.time_utc, days_from_civil(CivilDate{r.year, 1, 1}) * 86400.0 + 6.5 * 3600.0, 1e-6);
  double ghi = 0;
  for (const auto& rec : f.records) ghi += rec.global_horizontal;
  EXPECT_GT(ghi / 1000, 1200);  // kWh/m² per year, Chicago ≈ 1.3–1.5 MWh/m²
  EXPECT_LT(ghi / 1000, 1700);
}

TEST(Epw, ReadsPvgisQuirksAndUtcOffset) {
  SKYVIEW_REQUIRE_SHARED(path, "weather/pvgis_tmy_45N_8E.epw");
  const EpwFile f = read_epw(path);
  EXPECT_EQ(f.records.size(), 8760u);
  EXPECT_TRUE(f.hours_in_utc);
  EXPECT_NEAR(f.irradiance_time_offset_h, -0.8239, 1e-12);
  EXPECT_EQ(f.location.city, "unknown");
  EXPECT_NEAR(f.location.latitude_deg, 45.0, 1e-9);
  EXPECT_EQ(f.missing_solar_values, 0);
  // EPW hour 1 of 2018-01-01 holds the record stamped 00:00 UTC, irradiance at 00:10:34 UTC.
  const EpwRecord& r = f.records.front();
  EXPECT_EQ(r.year, 2018);
  EXPECT_NEAR(r.time_utc, days_from_civil(CivilDate{2018, 1, 1}) * 86400.0 + 0.1761 * 3600.0, 1e-3);
  // Years change from month to month; the reader keeps each record's own.
  bool other_year = false;
  for (const auto& rec : f.records) other_year |= rec.year != 2018;
  EXPECT_TRUE(other_year);
}

// A byte-order mark (editors on Windows write one) is not a reason to refuse the file; an
// irradiance above any measured at the ground is a missing value, not a sunny hour.
TEST(Epw, ByteOrderMarkAndImpossibleIrradiance) {
  SKYVIEW_REQUIRE_SHARED(path, "weather/chicago.epw");
  const EpwFile original = read_epw(path);
  std::ifstream in(path, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // Line 21 holds record 13 (hour 13 of 1 January): its GHI field (the 14th) becomes 5000.
  std::size_t line_start = 0;
  for (int line = 0; line < 20; ++line) line_start = text.find('\n', line_start) + 1;
  std::size_t field = line_start;
  for (int comma = 0; comma < 13; ++comma) field = text.find(',', field) + 1;
  const std::size_t end = text.find(',', field);
  const double before = std::stod(text.substr(field, end - field));
  text.replace(field, end - field, "5000");
  const std::filesystem::path dir = skyview::test::temp_dir("epw-bom");
  const std::string edited = (dir / "bom.epw").string();
  std::ofstream(edited, std::ios::binary) << "\xEF\xBB\xBF" << text;
  const EpwFile f = read_epw(edited);
  EXPECT_EQ(f.records.size(), original.records.size());
  EXPECT_NEAR(f.location.latitude_deg, original.location.latitude_deg, 1e-12);
  EXPECT_EQ(f.missing_solar_values, original.missing_solar_values + (before > 1600.0 ? 0 : 1));
  EXPECT_EQ(f.records[12].global_horizontal, 0.0);
  std::filesystem::remove_all(dir);
}

// An EPW holds one year of hourly records: a repeated hour or sub-hourly records would each be
// counted as a whole hour, so both are refused with the line that shows it.
TEST(Epw, RepeatedHoursAndSubHourlyDataAreRefused) {
  SKYVIEW_REQUIRE_SHARED(path, "weather/chicago.epw");
  std::ifstream in(path, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::filesystem::path dir = skyview::test::temp_dir("epw-repeat");
  auto refused = [&](const std::string& edited_text, const std::string& fragment) {
    const std::string edited = (dir / "edited.epw").string();
    std::ofstream(edited, std::ios::binary) << edited_text;
    try {
      read_epw(edited);
      ADD_FAILURE() << "accepted a file that should show: " << fragment;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  // Line 9 is the first record (1 January, hour 1): append a copy of it at the end.
  std::size_t first = 0;
  for (int line = 0; line < 8; ++line) first = text.find('\n', first) + 1;
  const std::string record = text.substr(first, text.find('\n', first) + 1 - first);
  const int last_line = static_cast<int>(std::count(text.begin(), text.end(), '\n')) + 1;
  refused(text + record, ":" + std::to_string(last_line) + ": data record repeats month 1, day 1, hour 1 of line 9");
  std::string quarter_hours = text;
  const std::size_t periods = quarter_hours.find("DATA PERIODS,1,1,");
  ASSERT_NE(periods, std::string::npos);
  quarter_hours.replace(periods, 17, "DATA PERIODS,1,4,");
  refused(quarter_hours, "DATA PERIODS gives 4 records per hour");
  std::filesystem::remove_all(dir);
}

// A file cut short keeps what it holds but says how much its header declared; a file without its
// DATA PERIODS line is named for that, not for having no records (until Dec 3).
TEST(Epw, CutShortAndHeaderlessFilesSayWhatIsWrong) {
  SKYVIEW_REQUIRE_SHARED(path, "weather/chicago.epw");
  EXPECT_EQ(read_epw(path).declared_hours, 8760);
  const std::string athens = std::string(SKYVIEW_SHARED_DIR) + "/sample_data/city_athens/athens_2023.epw";
  if (std::filesystem::exists(athens)) {
    EXPECT_EQ(read_epw(athens).declared_hours, 8760) << "its period reads 2023/ 1/ 1 to 2023/12/31";
  }
  std::ifstream in(path, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::filesystem::path dir = skyview::test::temp_dir("epw-cut");
  std::size_t cut = 0;
  for (int line = 0; line < 100; ++line) cut = text.find('\n', cut) + 1;
  const std::string short_file = (dir / "short.epw").string();
  std::ofstream(short_file, std::ios::binary) << text.substr(0, cut);
  const EpwFile f = read_epw(short_file);
  EXPECT_EQ(f.records.size(), 92u);
  EXPECT_EQ(f.declared_hours, 8760);
  const std::size_t periods = text.find("DATA PERIODS");
  const std::string headless = (dir / "headless.epw").string();
  std::ofstream(headless, std::ios::binary) << text.substr(0, periods) + text.substr(text.find('\n', periods) + 1);
  try {
    read_epw(headless);
    ADD_FAILURE() << "accepted a file without DATA PERIODS";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no DATA PERIODS line"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(dir);
}

TEST(Epw, BadInputIsOneLineError) {
  const std::filesystem::path dir = skyview::test::temp_dir("epw-test");
  const std::string bad = (dir / "bad.epw").string();
  {
    std::ofstream out(bad);
    out << "LOCATION,x,-,x,x,0,north,8.0,1,250\nDATA PERIODS,1,1,Data,Sunday,1/1,12/31\n";
  }
  try {
    read_epw(bad);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("LOCATION"), std::string::npos);
  }
  EXPECT_THROW(read_epw((dir / "missing.epw").string()), Error);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace skyview
