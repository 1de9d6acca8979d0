// render, validate and mtf: the imaging module (imaging_module.hpp) loaded on first use. It is looked for next
// to the executable (build tree) and in <exe dir>/RADCHAIN_IMAGING_MODULE_DIR (installed: ../lib/radchain).
#include "commands.hpp"
#include "imaging_module.hpp"

#include "radchain/error.hpp"

#include <fmt/format.h>

#include <dlfcn.h>

#include <filesystem>
#include <string>
#include <vector>

namespace radchain::cli {
namespace {
namespace fs = std::filesystem;

// Not a bad input file but a broken installation; main prints it as one line and exits 2.
[[noreturn]] void module_unavailable(const std::string& problem) {
  throw InputError({}, "", "", fmt::format("radchain: render, validate and mtf need {}: {}", imaging_module_file, problem));
}

void* open_module() {
  static void* handle = [] {
    std::error_code ec;
    const fs::path exe_dir = fs::read_symlink("/proc/self/exe", ec).parent_path();
    const std::vector<fs::path> candidates = {exe_dir / imaging_module_file,
                                              exe_dir / RADCHAIN_IMAGING_MODULE_DIR / imaging_module_file};
    std::vector<std::string> tried;
    for (const auto& path : candidates) {
      if (!fs::exists(path)) {
        tried.push_back(path.lexically_normal().string());
        continue;
      }
      void* h = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (!h) module_unavailable(::dlerror());  // there, but it does not load (a missing OpenImageIO, ...)
      auto build = reinterpret_cast<BuildEntry>(::dlsym(h, "radchain_imaging_module_build"));
      if (!build || build() != imaging_module_build())
        module_unavailable(fmt::format("{} was built from another radchain (module {}, executable {})", path.string(),
                                       build ? build() : "unknown", imaging_module_build()));
      return h;
    }
    module_unavailable("not found (looked for " + join(tried) + ")");
  }();
  return handle;
}

template <class Entry>
Entry entry(const char* name) {
  auto function = reinterpret_cast<Entry>(::dlsym(open_module(), name));
  if (!function) module_unavailable(fmt::format("it has no entry {} (an older module?)", name));
  return function;
}

}  // namespace

int render(const RenderCommand& options) { return entry<RenderEntry>("radchain_render")(options); }
int validate(const ValidateCommand& options) { return entry<ValidateEntry>("radchain_validate")(options); }
int mtf(const MtfCommand& options) { return entry<MtfEntry>("radchain_mtf")(options); }

}  // namespace radchain::cli
