#pragma once
// Runs a function in a child process and returns the bytes it made, so that a library that
// crashes, aborts or loops for ever on a malformed file takes down only the child. Assimp 5.2 (the
// Debian 12 package) does all three on broken PLY files, found by fuzz_mesh_reader within seconds.
#include <functional>
#include <string>

namespace skyview {

struct IsolatedResult {
  bool ok = false;
  std::string bytes;    // what `work` returned, when ok
  std::string failure;  // else why: "crashed (signal 11)", "did not finish within 30 s"
};

// Forks; the child runs `work` with the default handlers of crash signals and leaves with _exit,
// writing the result through a pipe; the parent waits at most `timeout_seconds` for it. `work`
// must not throw (catch inside and encode the failure in the bytes).
IsolatedResult run_isolated(const std::function<std::string()>& work, double timeout_seconds);

}  // namespace skyview
