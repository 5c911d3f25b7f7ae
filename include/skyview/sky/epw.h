#pragma once
// EnergyPlus weather (EPW) files: the location and the hourly solar irradiances the measured
// skies need. Each record carries the UTC instant its irradiance refers to (see docs/sky.md):
// the middle of the hour for TMY3/IWEC files (local standard time, hour h covers h−1..h), and for
// PVGIS files (hours in UTC, "Irradiance Time Offset" comment) the stated offset instant.
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace skyview {

struct EpwLocation {
  std::string city;
  double latitude_deg = 0.0;   // north positive
  double longitude_deg = 0.0;  // east positive
  double time_zone_h = 0.0;    // standard time offset from UTC
  double elevation_m = 0.0;
};

struct EpwRecord {
  int year = 0, month = 0, day = 0, hour = 0;  // as stored; hour 1..24
  double time_utc = 0.0;                       // instant the irradiance refers to (Unix seconds)
  // Hourly energies (Wh/m²), i.e. mean irradiances over the hour (W/m²); missing codes, values
  // that are not numbers, negative or above 1600 W/m² are read as 0 and counted in
  // EpwFile::missing_solar_values.
  double global_horizontal = 0.0;
  double direct_normal = 0.0;
  double diffuse_horizontal = 0.0;
  // Ground albedo (field 33), NaN where the file has none (999) or it is not within 0 .. 1.
  double albedo = std::numeric_limits<double>::quiet_NaN();
};

struct EpwFile {
  EpwLocation location;
  bool hours_in_utc = false;               // PVGIS convention
  double irradiance_time_offset_h = -0.5;  // instant relative to the end of the hour
  int missing_solar_values = 0;
  // Hours of the one data period DATA PERIODS declares (a 365-day year: 8760 for 1/1 to 12/31); 0
  // where it declares several or none readable. A file holding fewer records is truncated.
  int declared_hours = 0;
  std::vector<EpwRecord> records;
};

// Throws skyview::Error (one line, naming the file and line) for an unreadable file, a missing or
// malformed LOCATION line, no DATA PERIODS line before the records, no data records, or a record
// with too few fields or a bad date.
EpwFile read_epw(const std::string& path);

// The file's ground albedo: its hours' albedo fields weighted by their global horizontal
// irradiance (what the reflected light scales with); nullopt where no sunlit hour has one.
std::optional<double> mean_albedo(const EpwFile& file);

}  // namespace skyview
