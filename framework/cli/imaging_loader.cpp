// render, validate and mtf: the imaging module (imaging_module.hpp) loaded on first use. It is looked for next
// to the executable (build tree) and in <exe dir>/RADCHAIN_IMAGING_MODULE_DIR (installed: ../lib/radchain).
#include "commands.hpp"
#include "imaging_module.hpp"

#include "radchain/error.hpp"

#include <fmt/format.h>

#include <dlfcn.h>

#include <atomic>
#include <filesystem>
#include <string>
#include <vector>

#if defined(__SANITIZE_ADDRESS__)
// Under AddressSanitizer only: GCC 12's LeakSanitizer crashes at exit ("Tracer caught signal 11", a DTLS block at
// a garbage address). The module pulls in GnuTLS through OpenImageIO's dependencies; GnuTLS's destructor touches its
// dynamic TLS during exit (_dl_fini), and the sanitizer records that block with bounds it cannot read under Debian
// 12's glibc: a fault of the sanitizer runtime, not a leak. A process that loaded the module therefore skips the
// exit-time leak check (LeakSanitizer's documented hook); ASan still checks every access, and the imaging
// library's leaks are checked in radchain_imaging_tests, which link it without dlopen.
namespace {
std::atomic<bool> imaging_module_opened{false};
}
extern "C" __attribute__((visibility("default"), used)) int __lsan_is_turned_off() {
  return imaging_module_opened.load() ? 1 : 0;
}
#endif

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
#if defined(__SANITIZE_ADDRESS__)
      imaging_module_opened = true;
#endif
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
