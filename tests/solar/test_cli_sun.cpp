// `skyview sun` end to end: the SPA test case in CSV, events, help, and one-line errors.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "temp_dir.h"

namespace {

struct SunRun {
  int exit_code;
  std::string out, err;
};

SunRun run_sun(const std::string& args) {
  const std::string base = skyview::test::temp_dir("sun") + "/run";
  const std::string cmd = std::string(SKYVIEW_EXE) + " sun " + args + " >" + base + ".out 2>" + base + ".err";
  const int status = std::system(cmd.c_str());
  auto slurp = [](const std::string& path) {
    std::string all;
    if (FILE* f = std::fopen(path.c_str(), "r")) {
      char buffer[4096];
      for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, f)) > 0;) all.append(buffer, n);
      std::fclose(f);
    }
    return all;
  };
  return {WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), slurp(base + ".out"), slurp(base + ".err")};
}

const char* kGolden =
    "--lat 39.742476 --lon -105.1786 --elevation 1830.14 --pressure 820 --temperature 11 --delta-t 67 ";

}  // namespace

TEST(SunCli, CsvOfTheSpaTestCase) {
  const SunRun r = run_sun(std::string(kGolden) + "--time 2003-10-17T12:30:30-07:00 --csv --facade-azimuth 180");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("time_utc,zenith_deg,azimuth_deg,elevation_deg,", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("\n2003-10-17T19:30:30Z,50.111622,194.340241,39.888378,2003-10-17T12:30:30-07:00,"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find(",hsa_deg,vsa_deg,sun_on_facade"), std::string::npos);
}

TEST(SunCli, PeriodRowsAndEvents) {
  SunRun r = run_sun(
      "--lat 37.98 --lon 23.73 --from '2024-06-21T00:00' --to '2024-06-22T00:00' --step 1h "
      "--tz Europe/Athens --csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1 + 25);
  EXPECT_NE(r.out.find("2024-06-20T21:00:00Z"), std::string::npos);  // midnight +03:00
  r = run_sun(std::string(kGolden) + "--time 2003-10-17T12:30:30-07:00 --events --csv --convention spa");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("2003-10-17T06:12:43-07:00"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("2003-10-16T17:20:19-07:00"), std::string::npos) << r.out;
  r = run_sun("--lat 78 --lon 15 --time 2024-12-21T12:00Z --events");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("polar_night"), std::string::npos) << r.out;
}

// A local time that happens twice is taken as the earlier and said so; second 60 outside a leap
// second is refused.
TEST(SunCli, AmbiguousLocalTimeIsSaid) {
  SunRun r = run_sun("--lat 37.98 --lon 23.73 --time '2024-10-27T03:30 Europe/Athens' --csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\n2024-10-27T00:30:00Z,"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("Warning: '2024-10-27T03:30 Europe/Athens' occurs twice in Europe/Athens (clocks set back); "
                       "taken as the earlier, 2024-10-27T03:30:00+03:00"),
            std::string::npos)
      << r.err;
  r = run_sun("--lat 37.98 --lon 23.73 --time '2024-10-27T05:30 Europe/Athens' --csv");
  EXPECT_EQ(r.err, "");
  r = run_sun("--lat 37.98 --lon 23.73 --time 2024-10-27T12:30:60Z");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("exists only in a leap second"), std::string::npos) << r.err;
}

TEST(SunCli, HelpWorks) {
  const SunRun r = run_sun("--help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("--facade-azimuth"), std::string::npos);
}

TEST(SunCli, BadInputIsOneLine) {
  // Bad usage (an option's value or a combination of options) exits 2, as CLI11's own errors do.
  for (const char* args :
       {"--lat 95 --lon 0 --time 2024-01-01T00:00Z", "--lat 45 --lon 0 --time 7000-01-01T00:00Z",
        "--lat 45 --lon 0 --time '2024-01-01T00:00 Mars/Olympus'", "--lat x --lon 0 --time 2024-01-01Z",
        "--lat 45 --lon 0", "--lat 45 --lon 0 --from 2024-01-02Z --to 2024-01-01Z",
        "--lat 45 --lon 0 --time 2024-01-01Z --step 0h --from 2024-01-01Z",
        "--lat 45 --lon 0 --from 2024-01-01Z --to 2024-01-02Z --step 1y",
        // Options the run would not use (they were ignored until Dec 3).
        "--lat 45 --lon 0 --time 2024-01-01T12:00Z --events --facade-azimuth 180",
        "--lat 45 --lon 0 --time 2024-01-01T12:00Z --events --slope 30",
        "--lat 45 --lon 0 --from 2024-01-01Z --to 2024-12-31Z --events --step 1s",
        "--lat 45 --lon 0 --time 2024-01-01T12:00Z --step 1h",
        "--lat 45 --lon 0 --time 2024-01-01T12:00Z --convention spa",
        // Below -1e8 the library's sentinel for "automatic": it was taken as that.
        "--lat 45 --lon 0 --time 2024-01-01T12:00Z --delta-t -5e8", "--lat 45 --lon 0 --time 2024-01-01T12:00+18:59"}) {
    const SunRun r = run_sun(args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
    EXPECT_NE(r.err.find("skyview sun: error: "), std::string::npos) << r.err;
  }
  // A period that ends outside the SPA's years fails before any row is printed.
  const SunRun late = run_sun("--lat 40 --lon 0 --from 5999-12-31T20:00Z --to 6000-12-31T23:00-05:00 --step 1h --csv");
  EXPECT_EQ(late.exit_code, 1);
  EXPECT_EQ(late.out, "");
}

// The date column of events before year 0, a date a zone skipped, and local mean time's seconds.
TEST(SunCli, EventDatesAndOffsetsSayWhatTheyMean) {
  SunRun r = run_sun("--lat 40 --lon 0 --from -1999-01-01T00:00Z --to -1999-01-02T00:00Z --events --csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\n-1999-01-01,"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\n-1999-01-02,"), std::string::npos) << r.out;
  // Samoa went from 29 to 31 December 2011: no row may be dated 30 December, and 31 December once.
  r = run_sun(
      "--lat -13.83 --lon -171.76 --tz Pacific/Apia --from 2011-12-29T00:00 --to 2011-12-31T00:00 --events --csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.find("\n2011-12-30,"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\n2011-12-29,"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\n2011-12-31,"), std::string::npos) << r.out;
  // Amsterdam kept local mean time (+00:19:32, +01:19:32 in summer) until 1937.
  r = run_sun("--lat 52.37 --lon 4.89 --time '1930-06-21T12:00:00 Europe/Amsterdam' --csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("1930-06-21T10:40:28Z"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("1930-06-21T12:00:00+01:19:32"), std::string::npos) << r.out;
  r = run_sun("--lat 52.37 --lon 4.89 --time 1930-06-21T12:00:00+01:19:32 --csv");  // read back
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("1930-06-21T10:40:28Z"), std::string::npos) << r.out;
}
