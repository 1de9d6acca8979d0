// `radchain plugins`: the plugins on the search path.
#include "../commands.hpp"

#include "radchain/error.hpp"
#include "radchain/plugin_host.hpp"
#include "radchain/version.hpp"

#include <fmt/format.h>

#include <cstdio>

namespace radchain::cli {

int plugins() {
  const auto found = PluginHost::instance().discover();
  fmt::print("radchain {}, plugin ABI {}\n", framework_version, plugin_abi_version);
  fmt::print("{:<20} {:<11} {:<8} {}\n", "name", "kind", "version", "file");
  // Every library gets its line: one that cannot be used says why there, and the listing goes on.
  std::size_t unusable = 0;
  for (const auto& f : found) {
    try {
      const PluginInfo& info = PluginHost::instance().load_file(f.path);
      fmt::print("{:<20} {:<11} {:<8} {}\n", info.name, to_string(info.kind), info.framework_version, f.path);
    } catch (const InputError& error) {
      ++unusable;
      fmt::print("{:<20} {:<11} {:<8} {}: UNUSABLE: {}\n", f.name, to_string(f.kind), "-", f.path, error.problem());
    }
  }
  fmt::print("{} plugins (search path: {})\n", found.size() - unusable, join(PluginHost::instance().search_path(), ":"));
  if (unusable == 0) return 0;
  std::fflush(stdout);
  fmt::print(stderr, "radchain plugins: {} of {} libraries cannot be used (marked UNUSABLE above)\n", unusable, found.size());
  return static_cast<int>(ExitCode::bad_input);
}

}  // namespace radchain::cli
