#pragma once
// The plugin interface. A plugin is one .cpp file ending in RADCHAIN_PLUGIN(info_function), where
// info_function returns a PluginInfo: ABI version, kind, name, schema and factory. The host reads the
// exported ABI number before it calls anything in the library and refuses a mismatch.
#include "radchain/light.hpp"
#include "radchain/results.hpp"
#include "radchain/schema.hpp"
#include "radchain/version.hpp"

#include <boost/config.hpp>
#include <boost/dll/alias.hpp>

#include <cstdint>
#include <memory>
#include <string>

namespace radchain {

enum class Kind { platform, source, target, atmosphere, optics, detector, criterion };
std::string to_string(Kind kind);           // "source"
std::string kind_directory(Kind kind);      // "sources"
std::optional<Kind> kind_from_directory(const std::string& directory);

// What a stage sees while the chain runs.
class Context {
 public:
  Results& results;
  Light& light;
  const std::string& section;  // the stage being run: "optics", "criteria.detection"
  const std::string& plugin;   // (references: a Context is built per stage call and must cost nothing)

  // Declares "<section>.<name>".
  ResultId declare(const std::string& name, const std::string& si_unit, const std::string& equation,
                   const std::string& display_unit = {});
  // A result another stage must have declared; a missing one is a chain that does not fit together
  // (InputError naming both).
  ResultId require(const std::string& qualified_name) const;
  std::optional<ResultId> find(const std::string& qualified_name) const { return results.find(qualified_name); }
  // The incoming radiation has a form this stage cannot take.
  [[noreturn]] void refuse_form(const std::string& what, RadiationForm form) const;
};

class Stage {
 public:
  virtual ~Stage();
  // Spectral phase: runs when the chain is built and whenever a parameter marked affects_spectrum changes.
  // Declare results here and do every spectral integral here.
  virtual void prepare(Context& context);
  // Scalar phase: runs at every evaluation. Read scalar parameters through Params::handle() pointers.
  virtual void evaluate(Context& context) = 0;
};

struct PluginInfo {
  std::uint32_t abi_version;
  const char* framework_version;
  Kind kind;
  const char* name;      // equals the file stem and the TOML plugin = "..." value
  const char* summary;   // one line
  const char* reference; // where the physics comes from
  const Schema& (*schema)();
  std::unique_ptr<Stage> (*create)(const Params& params);
};

}  // namespace radchain

// Declares the plugin's entry. Use once, at the bottom of the plugin's .cpp file.
#define RADCHAIN_PLUGIN(info_function)                                                            \
  extern "C" BOOST_SYMBOL_EXPORT const std::uint32_t radchain_plugin_abi_version;                  \
  extern "C" BOOST_SYMBOL_EXPORT const std::uint32_t radchain_plugin_abi_version =                 \
      ::radchain::plugin_abi_version;                                                              \
  BOOST_DLL_ALIAS(info_function, radchain_plugin_info)
