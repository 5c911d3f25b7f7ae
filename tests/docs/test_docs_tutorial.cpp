// docs/tutorial.md stays true: every `skyview` command of its ```sh blocks runs, in order, in a
// folder holding the Gothenburg DSM it starts from, exits 0 and writes the files it names; the
// comparison it prints is the one the commands give.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <vector>

#include "docs_support.h"
#include "temp_dir.h"

using namespace skyview::test;
namespace fs = std::filesystem;

namespace {

// The commands of the ```sh blocks of `markdown` that start with "skyview", continuation lines
// joined.
std::vector<std::string> skyview_commands(const std::string& markdown) {
  std::vector<std::string> commands;
  bool in_sh = false;
  std::string pending;
  for (const std::string& line : lines_of(markdown)) {
    if (line.rfind("```", 0) == 0) {
      in_sh = !in_sh && line == "```sh";
      pending.clear();
      continue;
    }
    if (!in_sh) continue;
    std::string joined = pending + line;
    if (!joined.empty() && joined.back() == '\\') {
      pending = joined.substr(0, joined.size() - 1);
      continue;
    }
    pending.clear();
    const std::size_t start = joined.find_first_not_of(' ');
    if (start != std::string::npos && joined.compare(start, 8, "skyview ") == 0)
      commands.push_back(joined.substr(start));
  }
  return commands;
}

// The arguments of `command` that name files (by their extension), inputs and outputs alike.
std::vector<std::string> named_files(const std::string& command) {
  static const std::regex file(R"((^|\s)([A-Za-z0-9_./-]+\.(tif|png|json|nc|csv|gpkg|md))(?=\s|$))");
  std::vector<std::string> files;
  for (std::sregex_iterator it(command.begin(), command.end(), file), end; it != end; ++it) files.push_back((*it)[2]);
  return files;
}

int run_in(const std::string& dir, const std::string& command) {
  const std::string line = "cd '" + dir + "' && " + SKYVIEW_EXE + command.substr(7) + " >>'" + dir + "/log.txt' 2>&1";
  const int status = std::system(line.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
}

}  // namespace

TEST(DocsTutorial, CommandsAreFound) {
  const std::vector<std::string> commands = skyview_commands(source_file_text("docs/tutorial.md"));
  ASSERT_GE(commands.size(), 4u) << "docs/tutorial.md holds fewer skyview commands than it should";
  EXPECT_EQ(commands.front().rfind("skyview svf DSM_KRbig.tif", 0), 0u) << commands.front();
  EXPECT_EQ(named_files("skyview svf a.tif b.tif --preview c.png --max-error 0.02"),
            (std::vector<std::string>{"a.tif", "b.tif", "c.png"}));
}

TEST(DocsTutorial, EveryCommandRuns) {
  // The shared folder beside the source tree, or $SKYVIEW_SHARED_DIR (a git worktree has none beside it).
  const char* shared = std::getenv("SKYVIEW_SHARED_DIR");
  const fs::path sample =
      fs::path(shared && *shared ? shared : SKYVIEW_SHARED_DIR) / "sample_data/city_goteborg/DSM_KRbig.tif";
  if (!fs::exists(sample)) GTEST_SKIP() << "the Gothenburg sample is not at " << sample << "; the tutorial needs it";
  const std::string tutorial = source_file_text("docs/tutorial.md");
  const std::string dir = temp_dir("tutorial");
  for (const fs::path& p : {sample, fs::path(sample.string() + ".aux.xml")}) {
    if (fs::exists(p)) fs::copy_file(p, fs::path(dir) / p.filename());
  }
  for (const std::string& command : skyview_commands(tutorial)) {
    ASSERT_EQ(run_in(dir, command), 0) << "docs/tutorial.md: `" << command << "` failed; its output is in " << dir
                                       << "/log.txt";
    for (const std::string& file : named_files(command))
      EXPECT_TRUE(fs::exists(fs::path(dir) / file)) << "`" << command << "` did not write " << file;
  }
  // The statistics the tutorial quotes are those its commands give.
  const std::string json_path = dir + "/gbg_compare.json";
  ASSERT_TRUE(fs::exists(json_path)) << "the tutorial no longer writes gbg_compare.json";
  const nlohmann::json stats = nlohmann::json::parse(file_text(json_path));
  std::smatch m;
  ASSERT_TRUE(std::regex_search(tutorial, m, std::regex(R"(rmse ([0-9.]+)  bias ([-+0-9.]+)  p99 ([0-9.]+))")))
      << "docs/tutorial.md no longer quotes the comparison";
  EXPECT_NEAR(stats["rmse"].get<double>(), std::stod(m[1]), 5e-5);
  EXPECT_NEAR(stats["bias"].get<double>(), std::stod(m[2]), 5e-5);
  EXPECT_NEAR(stats["p99_abs"].get<double>(), std::stod(m[3]), 5e-5);
}
