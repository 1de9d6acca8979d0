#pragma once
// Finds and loads plugins. Search order: --plugin-path, RADCHAIN_PLUGIN_PATH, next to the executable
// (build tree: <exe dir>/plugins/<kind>/), the install prefix. A plugin is <dir>/<kind>/<name>.so; the first
// one found under a name wins and the host says so on stderr. Libraries stay loaded for the whole process.
#include "radchain/plugin.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace radchain {

struct PluginFile {
  std::string name;  // file stem
  Kind kind;
  std::string path;
};

class PluginHost {
 public:
  // The process-wide host (never destroyed, so no library is unloaded while objects from it live).
  static PluginHost& instance();

  // Replaces the search path: explicit (--plugin-path, colon-separated) first, then the defaults.
  void configure(const std::vector<std::string>& explicit_dirs);
  const std::vector<std::string>& search_path() const { return search_path_; }

  // All plugin files found, first-wins per name, in (kind, name) order. The folders are scanned once per
  // search path (again only after configure()).
  std::vector<PluginFile> discover() const;
  // Loads (once) and returns the plugin of this kind and name. Throws InputError listing the available
  // names of that kind when there is none, and when the library is broken (wrong ABI, no entry, not a
  // shared library, kind or name mismatch).
  const PluginInfo& load(Kind kind, const std::string& name);
  // Loads a library file directly (tests, `radchain describe ./x.so`).
  const PluginInfo& load_file(const std::string& path);
  // The plugin loaded under this name, if any (Context checks a stage's look-ups against its contract).
  const PluginInfo* loaded(std::string_view name) const;
  // Adds a plugin defined in the process, not in a library (a stage written in Python: radchain.register_stage,
  // docs/python.md). load() finds it before any library of that kind and name; adding the name again replaces it
  // for later look-ups (chains already built keep the one they have: nothing added is ever freed).
  const PluginInfo& add(PluginInfo info);

 private:
  PluginHost();
  const std::vector<PluginFile>& discovered() const;  // (with the lock held)
  const PluginInfo& load_file_locked(const std::string& path);
  struct Impl;
  Impl* impl_;
  std::vector<std::string> search_path_;
};

}  // namespace radchain
