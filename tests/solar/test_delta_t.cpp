// Delta T policy: observed table, 69.2 s after it, Espenak-Meeus polynomials outside; checked
// against the table and against pvlib's polynomial column in shared/data/spa.
#include <gtest/gtest.h>

#include "skyview/solar/civil_time.h"
#include "skyview/solar/delta_t.h"
#include "skyview/solar/solar_position.h"
#include "skyview/solar/time_parse.h"

using namespace skyview;

TEST(SolarDeltaT, ObservedTableAndRecentConstant) {
  EXPECT_NEAR(automatic_delta_t_s(1950.0), 29.150, 1e-9);
  EXPECT_NEAR(automatic_delta_t_s(2020.0), 69.3612, 1e-9);
  EXPECT_NEAR(automatic_delta_t_s(2003.0 + 9.5 / 12.0), 64.55, 0.1);  // the README's "about 64.5 s" in 2003
  EXPECT_EQ(automatic_delta_t_s(2024.5), 69.2);
  EXPECT_EQ(automatic_delta_t_s(2049.9), 69.2);
  EXPECT_NEAR(automatic_delta_t_s(2050.0), espenak_meeus_delta_t_s(2050.0), 1e-12);
}

// pvlib's calculate_deltat evaluates the same polynomials at year + (month - 0.5) / 12.
TEST(SolarDeltaT, EspenakMeeusMatchesPvlibColumn) {
  EXPECT_NEAR(espenak_meeus_delta_t_s(1950.0 + 0.5 / 12.0), 29.087, 5e-4);
  EXPECT_NEAR(espenak_meeus_delta_t_s(1951.0 + 6.5 / 12.0), 29.689, 5e-4);
  EXPECT_NEAR(espenak_meeus_delta_t_s(2019.0 + 11.5 / 12.0), 71.576, 5e-4);
  EXPECT_NEAR(espenak_meeus_delta_t_s(2020.0 + 1.5 / 12.0), 71.667, 5e-4);
}

TEST(SolarDeltaT, DistantYears) {
  EXPECT_NEAR(espenak_meeus_delta_t_s(-2000.0), -20.0 + 32.0 * 38.2 * 38.2, 1e-6);
  EXPECT_NEAR(espenak_meeus_delta_t_s(1000.0), 1574.2, 1e-9);
  EXPECT_NEAR(espenak_meeus_delta_t_s(3000.0), -20.0 + 32.0 * 11.8 * 11.8, 1e-6);
  // The polynomial pieces meet within a few seconds at their boundaries.
  for (double y : {-500.0, 500.0, 1600.0, 1700.0, 1800.0, 1860.0, 1900.0, 1920.0, 1941.0, 1961.0, 1986.0, 2005.0,
                   2050.0, 2150.0}) {
    EXPECT_NEAR(espenak_meeus_delta_t_s(y - 1e-9), espenak_meeus_delta_t_s(y), 5.0) << y;
  }
}

TEST(SolarDeltaT, SolarPositionRecordsTheValueUsed) {
  Site site;  // automatic Delta T
  EXPECT_NEAR(solar_position(parse_time("2003-10-17T12:30:30-07:00").unix_utc, site).delta_t_s, 64.55, 0.1);
  EXPECT_EQ(solar_position(parse_time("2024-06-21T12:00Z").unix_utc, site).delta_t_s, 69.2);
  EXPECT_GT(solar_position(parse_time("-1500-06-21T12:00Z").unix_utc, site).delta_t_s, 30000.0);
  site.delta_t_s = 67.0;
  EXPECT_EQ(solar_position(parse_time("2024-06-21T12:00Z").unix_utc, site).delta_t_s, 67.0);
}
