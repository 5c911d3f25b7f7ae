// The `skyview` executable: parses GDAL-style options and dispatches to a subcommand.
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "command.h"
#include "skyview/core/error.h"
#include "skyview/raster/raster_io.h"
#include "skyview/raster/temporary_outputs.h"
#include "skyview/core/version.h"

namespace {

// CLI11 reads "-of" as "-o f"; GDAL users type single-dash long options, so map them.
std::vector<std::string> gdal_style_arguments(int argc, char** argv) {
  static const char* long_single_dash[] = {"-of", "-co", "-te", "-tr", "-t_srs", "-s_srs", "-ot", "-srcnodata", "-dstnodata"};
  std::vector<std::string> args;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    for (const char* name : long_single_dash) {
      if (a == name) a = std::string("-") + name;
    }
    args.push_back(a);
  }
  return args;
}

// Errors are one line: GDAL's own messages (quoted in ours) may break lines.
std::string one_line(const char* message) {
  std::string out;
  for (const char* c = message; *c; ++c) {
    const bool space = *c == '\n' || *c == '\r' || *c == '\t' || *c == ' ';
    if (space) {
      if (!out.empty() && out.back() != ' ') out += ' ';
    } else {
      out += *c;
    }
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace skyview;
  cli::set_command_line(argc, argv);
  remove_temporary_outputs_on_signals();  // a run stopped by Ctrl-C or a scheduler leaves no hidden file
  CLI::App app{"skyview " + version() + ": horizon angles, sky-view factor and solar exposure from elevation rasters",
               "skyview"};
  app.set_version_flag("--version", "skyview " + version());
  app.require_subcommand(1);
  std::string active;
  std::vector<std::pair<CLI::App*, cli::Runner>> runners;
  for (const auto& cmd : cli::commands()) {
    CLI::App* sub = app.add_subcommand(cmd.name, cmd.summary);
    runners.emplace_back(sub, cmd.setup(*sub));
  }
  std::vector<std::string> args = gdal_style_arguments(argc, argv);
  // CLI11 would say "A subcommand is required" for a misspelt one.
  std::string known;
  bool is_known = false;
  for (const auto& cmd : cli::commands()) {
    known += (known.empty() ? "" : ", ") + std::string(cmd.name);
    is_known = is_known || (!args.empty() && args.front() == cmd.name);
  }
  if (!args.empty() && !args.front().empty() && args.front()[0] != '-' && !is_known) {
    std::fprintf(stderr, "skyview: error: unknown subcommand '%s' (%s; see --help)\n", args.front().c_str(),
                 known.c_str());
    return 2;
  }
  std::reverse(args.begin(), args.end());  // CLI11 parses a reversed vector
  try {
    app.parse(args);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);  // --help, --version
    // Usage errors, like every other error, are one line naming the subcommand.
    std::string name = "skyview";
    std::string greedy;  // options given that take every value after them, as lists do
    for (const auto& [sub, run] : runners) {
      if (!sub->parsed()) continue;
      name += " " + sub->get_name();
      for (const CLI::Option* opt : sub->get_options()) {
        if (opt->count() > 0 && opt->get_items_expected_max() > 1 && opt->get_allow_extra_args())
          greedy += (greedy.empty() ? "" : ", ") + opt->get_name();
      }
    }
    // A missing file after a list option is the list having taken it: say so.
    const std::string hint =
        dynamic_cast<const CLI::RequiredError*>(&e) && !greedy.empty()
            ? "; " + greedy + " takes every value after it, so give the files first (or end the list with --)"
            : "";
    std::fprintf(stderr, "%s: error: %s%s (see --help)\n", name.c_str(), one_line(e.what()).c_str(), hint.c_str());
    return 2;
  }
  init_gdal();
  for (auto& [sub, run] : runners) {
    if (!sub->parsed()) continue;
    try {
      return run();
    } catch (const Error& e) {
      std::fprintf(stderr, "skyview %s: error: %s\n", sub->get_name().c_str(), one_line(e.what()).c_str());
      return 1;
    } catch (const std::bad_alloc&) {
      std::fprintf(stderr, "skyview %s: error: out of memory\n", sub->get_name().c_str());
      return 1;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "skyview %s: error: %s\n", sub->get_name().c_str(), one_line(e.what()).c_str());
      return 1;
    }
  }
  return 1;
}
