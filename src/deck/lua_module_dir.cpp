#include "deck/lua_module_dir.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>

#include "core/mesh.hpp"
#include "tirefe/install_paths.hpp"
#include "tirefe/source_paths.hpp"

namespace tirefe::macros {

namespace fs = std::filesystem;

namespace {

/// A folder holds the modules if it has the shared tire helper.
bool holds_modules(const fs::path& dir) {
  std::error_code error;
  return fs::is_regular_file(dir / "tire_on_road.lua", error);
}

bool is_shared_library(const fs::path& file) { return file.filename().string().find(".so") != std::string::npos; }

/// The file this code was loaded from: libtirefe.so, or the executable linking tirefe_lib
/// (which the loader may name only as it was started, so the kernel's name for it).
fs::path loaded_file() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&lua_module_dir), &info) != 0 && info.dli_fname && *info.dli_fname) {
    std::error_code error;
    const fs::path file = fs::canonical(info.dli_fname, error);
    if (!error && is_shared_library(file)) return file;
  }
  std::error_code error;
  return fs::read_symlink("/proc/self/exe", error);
}

bool inside(const fs::path& file, const fs::path& dir) {
  const fs::path relative = file.lexically_relative(dir);
  return !relative.empty() && *relative.begin() != "..";
}

std::string find_module_dir() {
  const fs::path file = loaded_file();
  const fs::path installed =
      (file.parent_path() / (is_shared_library(file) ? TIREFE_LUA_FROM_LIBDIR : TIREFE_LUA_FROM_BINDIR))
          .lexically_normal();
  if (holds_modules(installed)) return installed.string();
  // An FMU's binary (binaries/<platform>/) carries its modules in the FMU's resources/.
  const fs::path fmu_resources = (file.parent_path() / "../../resources/lua").lexically_normal();
  if (is_shared_library(file) && holds_modules(fmu_resources)) return fmu_resources.string();
  std::error_code error;
  const fs::path build_tree = fs::weakly_canonical(TIREFE_BINARY_DIR, error);
  if (!error && inside(file, build_tree) && holds_modules(TIREFE_LUA_DIR)) return TIREFE_LUA_DIR;
  throw ModelError("cannot find tirefe's Lua modules: not in '" + installed.string() + "' (next to " + file.string() +
                   "); set TIREFE_LUA_PATH to the folder holding tire_on_road.lua");
}

}  // namespace

std::string lua_module_dir() {
  if (const char* path = std::getenv("TIREFE_LUA_PATH"); path && *path) return path;
  static const std::string found = find_module_dir();  // where the code is does not change
  return found;
}

}  // namespace tirefe::macros
