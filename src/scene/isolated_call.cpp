#include "scene/isolated_call.h"

#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>

namespace skyview {
namespace {

bool write_all(int fd, const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    data += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

std::string seconds_text(double s) { return std::to_string(static_cast<long long>(s)); }

}  // namespace

IsolatedResult run_isolated(const std::function<std::string()>& work, double timeout_seconds) {
  IsolatedResult result;
  int fds[2];
  if (::pipe(fds) != 0) {
    result.failure = "cannot make a pipe (" + std::string(std::strerror(errno)) + ")";
    return result;
  }
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    result.failure = "cannot start a process (" + std::string(std::strerror(errno)) + ")";
    return result;
  }
  if (pid == 0) {
    ::close(fds[0]);
    // A crash ends the child quietly; the parent reports it. (Sanitizer and fuzzer handlers,
    // inherited from the parent, would report it as the parent's.)
    for (int s : {SIGSEGV, SIGBUS, SIGABRT, SIGFPE, SIGILL}) std::signal(s, SIG_DFL);
    const std::string bytes = work();
    const std::uint64_t size = bytes.size();
    const bool sent = write_all(fds[1], reinterpret_cast<const char*>(&size), sizeof size) &&
                      write_all(fds[1], bytes.data(), bytes.size());
    ::_exit(sent ? 0 : 3);
  }
  ::close(fds[1]);
  // Read until the child closes its end, or the time is up.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_seconds);
  std::string received;
  char buffer[1 << 16];
  bool timed_out = false;
  for (;;) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      timed_out = true;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(std::min<long long>(left.count(), 1000)));
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) continue;
    const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // the child closed its end (finished or died)
    received.append(buffer, static_cast<std::size_t>(n));
  }
  ::close(fds[0]);
  if (timed_out) ::kill(pid, SIGKILL);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (timed_out) {
    result.failure = "did not finish within " + seconds_text(timeout_seconds) + " s";
  } else if (WIFSIGNALED(status)) {
    result.failure = "crashed (signal " + std::to_string(WTERMSIG(status)) + ")";
  } else if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    result.failure = "failed (exit " + std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")";
  } else {
    std::uint64_t size = 0;
    if (received.size() >= sizeof size) std::memcpy(&size, received.data(), sizeof size);
    if (received.size() != sizeof size + size) {
      result.failure = "sent an incomplete result";
    } else {
      result.ok = true;
      result.bytes = std::move(received.erase(0, sizeof size));
    }
  }
  return result;
}

}  // namespace skyview
