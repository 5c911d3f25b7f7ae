#include "skyview/raster/temporary_outputs.h"

#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <string_view>

namespace skyview {
namespace {

// A signal handler may call only async-signal-safe functions (unlink, signal, raise) and read only
// lock-free atomics: the names wait in fixed slots. A slot is claimed, its name written, and only
// then published to the handler.
constexpr int kSlots = 64;
constexpr std::size_t kNameBytes = 4096;
struct Slot {
  std::atomic<bool> claimed{false}, published{false};
  char name[kNameBytes];
};
Slot slots[kSlots];

void remember(const std::string& name) {
  if (name.size() >= kNameBytes) return;
  for (Slot& s : slots) {
    if (s.claimed.exchange(true, std::memory_order_acq_rel)) continue;
    std::memcpy(s.name, name.c_str(), name.size() + 1);
    s.published.store(true, std::memory_order_release);
    return;
  }
}

// GDAL's side files beside an output (.aux.xml, .msk) and ENVI's header in place of its extension.
constexpr const char* kSideSuffixes[] = {".aux.xml", ".msk"};
std::string header_of(const std::string& tmp) { return std::filesystem::path(tmp).replace_extension(".hdr").string(); }

void on_signal(int signal) {
  for (Slot& s : slots) {
    if (s.published.load(std::memory_order_acquire)) ::unlink(s.name);
  }
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

}  // namespace

std::string temporary_output_name(const std::string& path) {
  const std::filesystem::path p(path);
  std::ostringstream name;
  name << "." << p.stem().string() << ".skyview-tmp-" << ::getpid() << p.extension().string();
  const std::string tmp = (p.parent_path() / name.str()).string();
  remember(tmp);
  for (const char* side : kSideSuffixes) remember(tmp + side);
  remember(header_of(tmp));
  return tmp;
}

void forget_temporary(const std::string& temporary) {
  const std::string header = header_of(temporary);
  for (Slot& s : slots) {
    if (!s.published.load(std::memory_order_acquire)) continue;
    const std::string_view name(s.name);
    if (name.substr(0, temporary.size()) == temporary || name == header) {
      s.published.store(false, std::memory_order_release);
      s.claimed.store(false, std::memory_order_release);
    }
  }
}

void name_final_output(std::string& text, const std::string& temporary, const std::string& final_path) {
  for (std::size_t at = text.find(temporary); at != std::string::npos;
       at = text.find(temporary, at + final_path.size()))
    text.replace(at, temporary.size(), final_path);
}

void remove_temporary_outputs_on_signals() {
  for (const int signal : {SIGINT, SIGTERM, SIGHUP}) std::signal(signal, on_signal);
}

}  // namespace skyview
