// `radchain plugins`: the plugins on the search path.
#include "../commands.hpp"

#include "radchain/error.hpp"
#include "radchain/plugin_host.hpp"
#include "radchain/version.hpp"

#include <fmt/format.h>

namespace radchain::cli {

int plugins() {
  const auto found = PluginHost::instance().discover();
  fmt::print("radchain {}, plugin ABI {}\n", framework_version, plugin_abi_version);
  fmt::print("{:<20} {:<11} {:<8} {}\n", "name", "kind", "version", "file");
  for (const auto& f : found) {
    const PluginInfo& info = PluginHost::instance().load_file(f.path);
    fmt::print("{:<20} {:<11} {:<8} {}\n", info.name, to_string(info.kind), info.framework_version, f.path);
  }
  fmt::print("{} plugins (search path: {})\n", found.size(), join(PluginHost::instance().search_path(), ":"));
  return 0;
}

}  // namespace radchain::cli
