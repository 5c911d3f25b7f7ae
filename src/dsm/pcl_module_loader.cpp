// Finds and loads the PCL module once per process (see pcl_module.h for why it is a module).
#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>

#include "pcl_module.h"
#include "skyview/core/error.h"

namespace skyview::detail {
namespace {

constexpr const char* kModuleFile = "libskyview_pcl.so";
constexpr const char* kNeeds = "point clouds in PLY or PCD and the point filters need skyview's PCL module";

// Folders to look in, in order (see pcl_module.h); `chosen` when the user named the one folder.
std::vector<std::filesystem::path> module_folders(bool& chosen) {
  std::vector<std::filesystem::path> folders;
  const char* dir = std::getenv("SKYVIEW_MODULE_DIR");
  chosen = dir && *dir;
  if (chosen) {
    folders.emplace_back(dir);
    return folders;  // asked for: no other folder may stand in for it
  }
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    folders.push_back(exe.parent_path());
    folders.push_back(exe.parent_path().parent_path() / "lib" / "skyview");
  }
#ifdef SKYVIEW_MODULE_INSTALL_DIR
  folders.emplace_back(SKYVIEW_MODULE_INSTALL_DIR);
#endif
  return folders;
}

// The module in the first folder that holds one; a file there that does not load, or comes from
// another build, is an error, not a reason to look further (it would hide a broken install).
const PclModule* load() {
  bool chosen = false;
  std::string tried;
  for (const std::filesystem::path& folder : module_folders(chosen)) {
    const std::filesystem::path file = folder / kModuleFile;
    tried += (tried.empty() ? "" : ", ") + folder.string();
    std::error_code ec;
    if (!std::filesystem::exists(file, ec)) continue;
    void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      const char* e = dlerror();
      throw Error(std::string(kNeeds) + ": " + file.string() + " does not load (" + (e ? e : "no reason given") + ")");
    }
    using Entry = const PclModule* (*)();
    const auto entry = reinterpret_cast<Entry>(dlsym(handle, "skyview_pcl_module"));
    const PclModule* module = entry ? entry() : nullptr;
    if (module && module->build == PclModuleBuild{}) return module;  // kept loaded for the process
    dlclose(handle);
    throw Error(std::string(kNeeds) + ": " + file.string() + " is from another build of skyview");
  }
  throw Error(std::string(kNeeds) + ": no " + kModuleFile + " in " + tried +
              (chosen ? " (SKYVIEW_MODULE_DIR names it)" : " (set SKYVIEW_MODULE_DIR to the folder that holds it)"));
}

}  // namespace

const PclModule& pcl_module() {
  // Loaded once; a failure is kept too, so every later call reports the same error.
  static std::once_flag once;
  static const PclModule* module = nullptr;
  static std::string error;
  std::call_once(once, [] {
    try {
      module = load();
    } catch (const Error& e) {
      error = e.what();
    }
  });
  if (!module) throw Error(error);
  return *module;
}

}  // namespace skyview::detail
