#include "command.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>

#include "skyview/core/error.h"
#include "skyview/core/lowercase.h"

#include <sys/resource.h>

#include <chrono>

namespace skyview::cli {

std::vector<Command>& commands() {
  static std::vector<Command> list;
  return list;
}

Registration::Registration(const char* name, const char* summary, Setup setup) {
  commands().push_back({name, summary, setup});
}

namespace {
std::string& stored_command_line() {
  static std::string line;
  return line;
}
}  // namespace

const std::string& command_line() { return stored_command_line(); }

void set_command_line(int argc, char** argv) {
  std::string& line = stored_command_line();
  line.clear();
  for (int i = 0; i < argc; ++i) {
    if (i) line += ' ';
    line += argv[i];
  }
}

void add_output_options(CLI::App& app, OutputOptions& o) {
  app.add_option("--of", o.format, "Output format, a GDAL driver short name (-of)")->capture_default_str();
  app.add_option("--co", o.creation_options,
                 "Creation option KEY=VALUE, repeatable (-co); GTiff defaults: "
                 "TILED=YES COMPRESS=DEFLATE PREDICTOR=3")
      ->allow_extra_args(false)  // one KEY=VALUE a time, as GDAL's -co: `-co A=1 IN OUT` leaves IN and OUT positional
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  app.add_flag("--overwrite", o.overwrite, "Replace an existing output");
  app.add_flag("-q,--quiet", o.quiet, "No progress or summary on stderr (warnings and errors still)");
  app.add_option("--threads", o.threads, "Worker threads (0 = all cores)")->check(non_negative_number());
}

void refuse_unused(const CLI::App& app, const std::string& option, bool used, const std::string& where) {
  if (!used && app.count(option) > 0) throw UsageError(option + " applies only to " + where);
}

void require_extension(const std::string& path, const std::vector<std::string>& extensions, const std::string& what) {
  const std::string ext = lowercase_extension(path);
  if (std::find(extensions.begin(), extensions.end(), ext) != extensions.end()) return;
  std::string list;
  for (const std::string& e : extensions) list += (list.empty() ? "" : ", ") + e;
  throw UsageError(what + " '" + path + "' must end in " + (extensions.size() > 1 ? "one of " : "") + list +
                   " (the format it is written in)");
}

ParsedTime parse_time_option(const std::string& text, const std::string& zone) {
  const ParsedTime t = as_usage_error([&] { return parse_time(text, zone); });
  if (t.ambiguous) {
    std::fprintf(stderr,
                 "Warning: '%s' occurs twice in %s (clocks set back); taken as the earlier, %s; give a UTC offset "
                 "to choose\n",
                 text.c_str(), t.zone.c_str(), format_iso_local(t.unix_utc, t.utc_offset_s).c_str());
  }
  return t;
}

namespace {

// A number option checked by `ok`, with `message` for anything else (text, NaN, or out of range).
CLI::Validator number_check(std::function<bool(double)> ok, const std::string& message, const std::string& name) {
  return CLI::Validator(
      [ok = std::move(ok), message](std::string& text) -> std::string {
        double x = 0;
        return CLI::detail::lexical_cast(text, x) && ok(x) ? "" : message;
      },
      name);
}

}  // namespace

const CLI::Validator& positive_number() {
  static const CLI::Validator v =
      number_check([](double x) { return x > 0 && std::isfinite(x); }, "must be a positive number", "POSITIVE");
  return v;
}

const CLI::Validator& non_negative_number() {
  static const CLI::Validator v =
      number_check([](double x) { return x >= 0 && std::isfinite(x); }, "must be zero or positive", "NONNEGATIVE");
  return v;
}

const CLI::Validator& finite_number() {
  static const CLI::Validator v =
      number_check([](double x) { return std::isfinite(x); }, "must be a finite number", "NUMBER");
  return v;
}

CLI::Validator number_in(double lo, double hi) {
  const std::string range = CLI::detail::to_string(lo) + " to " + CLI::detail::to_string(hi);
  return number_check([lo, hi](double x) { return x >= lo && x <= hi; }, "must be a number from " + range,
                      "[" + range + "]");
}

CLI::Validator number_above(double lo, double hi) {
  const std::string a = CLI::detail::to_string(lo), b = CLI::detail::to_string(hi);
  return number_check([lo, hi](double x) { return x > lo && x <= hi; },
                      "must be a number above " + a + " and at most " + b, "(" + a + " to " + b + "]");
}

namespace {

double now_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

RunSummary::RunSummary(std::string command) : command_(std::move(command)), started_(now_seconds()) {}

double RunSummary::seconds() const { return now_seconds() - started_; }

void RunSummary::print(const std::string& what, bool quiet) const {
  if (quiet) return;
  std::fprintf(stderr, "skyview %s: %s; %.2f s, peak %.2f GB\n", command_.c_str(), what.c_str(), seconds(),
               static_cast<double>(peak_memory_bytes()) / 1e9);
}

double parse_duration_option(const std::string& text) {
  return as_usage_error([&] { return parse_duration_s(text); });
}

std::size_t peak_memory_bytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<std::size_t>(usage.ru_maxrss) * 1024;  // kilobytes on Linux
}

}  // namespace skyview::cli
