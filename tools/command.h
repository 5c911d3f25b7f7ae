#pragma once
// Each tools/cmd_*.cpp registers one subcommand of the `skyview` executable with a static
// Registration, so adding a command touches no shared file. A command's setup adds its
// options to the CLI11 subcommand and returns the function that runs it after parsing.
#include <CLI/CLI.hpp>

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "skyview/core/thread_limit.h"
#include "skyview/solar/time_parse.h"

namespace skyview::cli {

using Runner = std::function<int()>;
using Setup = Runner (*)(CLI::App& app);

struct Registration {
  Registration(const char* name, const char* summary, Setup setup);
};

struct Command {
  std::string name, summary;
  Setup setup;
};
std::vector<Command>& commands();

// The command line as typed, for output metadata.
const std::string& command_line();
void set_command_line(int argc, char** argv);

// Options every raster-writing command shares, GDAL-style.
struct OutputOptions {
  std::string format = "GTiff";
  std::vector<std::string> creation_options;
  bool overwrite = false;
  bool quiet = false;
  int threads = 0;  // 0 = all cores
};
void add_output_options(CLI::App& app, OutputOptions& o);

// "must be a positive number" for options that need one (CLI11's own check prints its numeric
// range up to 1.8e308).
const CLI::Validator& positive_number();
const CLI::Validator& non_negative_number();
// Any number but NaN and infinities (CLI11 parses both).
const CLI::Validator& finite_number();
// A number in [lo, hi]; NaN fails (CLI::Range lets it through: every comparison with it is false).
CLI::Validator number_in(double lo, double hi);
// A finite number in (lo, hi].
CLI::Validator number_above(double lo, double hi);

// Errors in options throw skyview::UsageError (exit 2, as CLI11's own), errors in the data or files
// skyview::Error (exit 1): an option's message starts with its name.
//
// Throws when `option` was given on the command line but the run will not use it (`used` is
// false): "OPTION applies only to WHERE". A batch job would otherwise get the answer to another
// question than the one it asked, without a word.
void refuse_unused(const CLI::App& app, const std::string& option, bool used, const std::string& where);

// Throws unless `path` ends in one of `extensions` (".png", compared without case): the file's
// format is fixed by what writes it, and a name saying otherwise would mislead every reader.
void require_extension(const std::string& path, const std::vector<std::string>& extensions, const std::string& what);

// parse_time, warning on stderr (even under -q) when a local time occurs twice and the earlier
// instant is taken.
// Throws UsageError for a time that cannot be read.
ParsedTime parse_time_option(const std::string& text, const std::string& zone);

// parse_duration_s ("30m", "1h"), throwing UsageError for a duration that cannot be read.
double parse_duration_option(const std::string& text);

// The one line every command ends with on stderr (unless -q): "skyview CMD: WHAT; S s, peak M GB",
// with the wall time since the summary was made and the process's peak resident memory.
class RunSummary {
 public:
  explicit RunSummary(std::string command);
  // Seconds since construction.
  double seconds() const;
  // Prints the line unless `quiet`.
  void print(const std::string& what, bool quiet) const;

 private:
  std::string command_;
  double started_;
};

// The process's peak resident memory so far, in bytes (getrusage).
std::size_t peak_memory_bytes();

}  // namespace skyview::cli
