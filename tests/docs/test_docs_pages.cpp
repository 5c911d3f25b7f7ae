// Every subcommand has a page docs/commands/<name>.md, and every long option its --help lists
// appears on that page: an option added without a word for its users fails here, by name.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <string>
#include <vector>

#include "docs_support.h"

using namespace skyview::test;

namespace {

// The subcommands `skyview --help` lists: the first word of each line under "Subcommands:".
std::vector<std::string> subcommands() {
  std::vector<std::string> names;
  bool in_list = false;
  for (const std::string& line : lines_of(skyview_output("--help"))) {
    if (line.rfind("Subcommands:", 0) == 0) {
      in_list = true;
      continue;
    }
    if (!in_list || line.size() < 3 || line[0] != ' ') continue;
    const std::size_t start = line.find_first_not_of(' ');
    if (start != 2) continue;  // a wrapped summary is indented further
    names.push_back(line.substr(start, line.find(' ', start) - start));
  }
  return names;
}

// The long options `skyview CMD --help` defines: from each line of its "Options:" section that
// starts with a dash ("  -b,--band INT=1", "  --no-early-exit{false}"), the names with two dashes,
// without --help. Options named in the descriptions are not taken: only those defined.
std::vector<std::string> long_options(const std::string& command) {
  std::vector<std::string> names;
  bool in_options = false;
  for (const std::string& line : lines_of(skyview_output(command + " --help"))) {
    if (line.rfind("Options:", 0) == 0) {
      in_options = true;
      continue;
    }
    if (!in_options) continue;
    if (!line.empty() && line[0] != ' ') break;  // the footer
    const std::size_t start = line.find_first_not_of(' ');
    if (start == std::string::npos || line[start] != '-') continue;
    const std::string spec = line.substr(start, line.find(' ', start) - start);  // "-b,--band" or "--of"
    std::size_t pos = 0;
    while ((pos = spec.find("--", pos)) != std::string::npos) {
      std::size_t end = pos + 2;
      while (end < spec.size() &&
             (std::isalnum(static_cast<unsigned char>(spec[end])) || spec[end] == '-' || spec[end] == '_'))
        ++end;
      const std::string name = spec.substr(pos, end - pos);
      if (name != "--help") names.push_back(name);
      pos = end;
    }
  }
  return names;
}

bool is_name_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_'; }

// Whether `page` names `option` ("--of") as a whole word; GDAL's single-dash spellings (-of, -co,
// -te, -tr, -t_srs, -s_srs), which skyview reads as the double-dash ones, count too.
bool page_names(const std::string& page, const std::string& option) {
  static const std::vector<std::string> gdal_style = {"--of", "--co", "--te", "--tr", "--t_srs", "--s_srs"};
  std::vector<std::string> spellings{option};
  if (std::find(gdal_style.begin(), gdal_style.end(), option) != gdal_style.end())
    spellings.push_back(option.substr(1));
  for (const std::string& s : spellings) {
    for (std::size_t pos = page.find(s); pos != std::string::npos; pos = page.find(s, pos + 1)) {
      // "-of" may follow a dash: "--of" is the same option.
      const bool starts = pos == 0 || !is_name_char(page[pos - 1]) || (s[1] != '-' && page[pos - 1] == '-');
      const bool ends = pos + s.size() == page.size() || !is_name_char(page[pos + s.size()]);
      if (starts && ends) return true;
    }
  }
  return false;
}

}  // namespace

// The parsing itself: a --help whose layout changed must not let every page pass on no options.
TEST(DocsPages, HelpIsParsed) {
  const std::vector<std::string> commands = subcommands();
  ASSERT_GE(commands.size(), 15u) << "skyview --help lists fewer subcommands than expected; its layout changed?";
  EXPECT_NE(std::find(commands.begin(), commands.end(), "svf"), commands.end());
  EXPECT_NE(std::find(commands.begin(), commands.end(), "fisheye-svf"), commands.end());
  const std::vector<std::string> svf = long_options("svf");
  for (const char* expected : {"--band", "--directions", "--no-early-exit", "--of", "--co", "--quiet", "--preview"})
    EXPECT_NE(std::find(svf.begin(), svf.end(), expected), svf.end()) << expected << " not parsed from svf --help";
  EXPECT_EQ(std::find(svf.begin(), svf.end(), "--help"), svf.end());
  EXPECT_TRUE(page_names("`-of GTiff`", "--of"));
  EXPECT_FALSE(page_names("`--offset`", "--of"));
  EXPECT_FALSE(page_names("`--early-exit`", "--no-early-exit"));
  EXPECT_FALSE(page_names("`--no-early-exit-now`", "--no-early-exit"));
}

TEST(DocsPages, EverySubcommandHasAPage) {
  for (const std::string& command : subcommands()) {
    const std::string page = source_file_text("docs/commands/" + command + ".md");
    EXPECT_FALSE(page.empty()) << "skyview " << command << " has no page: write docs/commands/" << command
                               << ".md (synopsis, description, options, outputs, examples, errors)";
    EXPECT_EQ(page.rfind("# skyview " + command + "\n", 0), 0u)
        << "docs/commands/" << command << ".md should start with '# skyview " << command << "'";
  }
}

TEST(DocsPages, EveryLongOptionIsOnItsPage) {
  for (const std::string& command : subcommands()) {
    const std::string page = source_file_text("docs/commands/" + command + ".md");
    if (page.empty()) continue;  // EverySubcommandHasAPage says so
    for (const std::string& option : long_options(command)) {
      EXPECT_TRUE(page_names(page, option)) << "docs/commands/" << command << ".md does not mention " << option
                                            << " (from skyview " << command << " --help): add it to the page's options";
    }
  }
}

TEST(DocsPages, IndexListsEverySubcommand) {
  const std::string index = source_file_text("docs/commands/index.md");
  ASSERT_FALSE(index.empty()) << "docs/commands/index.md is missing";
  for (const std::string& command : subcommands()) {
    EXPECT_NE(index.find("](" + command + ".md)"), std::string::npos)
        << "docs/commands/index.md has no line for skyview " << command << " (a link to " << command << ".md)";
  }
}
