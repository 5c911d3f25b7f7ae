#pragma once
// Running the skyview executable from a test: its exit code and stderr, and the check that a bad
// input gives one error line.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <fstream>
#include <iterator>
#include <string>

namespace skyview::test {

struct RunResult {
  int exit_code;
  std::string err;
};

// Runs the executable `exe` with `args` and -q, stderr into `dir`; with `max_file_bytes` > 0 no file
// it writes may grow beyond that (RLIMIT_FSIZE with SIGXFSZ ignored, so a write fails with EFBIG the
// way a full disk fails it).
inline RunResult run_executable(const std::string& exe, const std::string& args, const std::string& dir,
                                rlim_t max_file_bytes = 0) {
  const std::string err_file = dir + "/stderr.txt";
  const std::string cmd = exe + " " + args + " -q 2>" + err_file + " >/dev/null";
  const pid_t pid = fork();
  if (pid == 0) {
    if (max_file_bytes > 0) {
      const rlimit limit{max_file_bytes, max_file_bytes};
      setrlimit(RLIMIT_FSIZE, &limit);
      std::signal(SIGXFSZ, SIG_IGN);
    }
    execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  std::ifstream in(err_file);
  std::string all((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), all};
}

// The same for the skyview executable this build made.
inline RunResult run_skyview(const std::string& args, const std::string& dir, rlim_t max_file_bytes = 0) {
  return run_executable(SKYVIEW_EXE, args, dir, max_file_bytes);
}

// Exit 1 for bad data or files, 2 for a bad command line.
inline void expect_one_line_error(const RunResult& r, const std::string& fragment, int exit_code = 1) {
  EXPECT_EQ(r.exit_code, exit_code) << r.err;
  EXPECT_NE(r.err.find("error: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

}  // namespace skyview::test
