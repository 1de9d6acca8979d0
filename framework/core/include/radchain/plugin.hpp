#pragma once
// The plugin interface. A plugin is one .cpp file ending in RADCHAIN_PLUGIN(info_function), where
// info_function returns a PluginInfo: ABI version, kind, name, schema and factory. The host reads the
// exported ABI number before it calls anything in the library and refuses a mismatch.
#include "radchain/lanes.hpp"
#include "radchain/light.hpp"
#include "radchain/results.hpp"
#include "radchain/schema.hpp"
#include "radchain/version.hpp"

#include <boost/config.hpp>
#include <boost/dll/alias.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace radchain {

enum class Kind { platform, source, target, atmosphere, optics, detector, criterion };
std::string to_string(Kind kind);           // "source"
std::string kind_directory(Kind kind);      // "sources"
std::optional<Kind> kind_from_directory(const std::string& directory);

// How much a scalar evaluation computes.
enum class Detail {
  full,       // every declared result: what a report, a sweep column or a comparison shows
  essential,  // what later stages and the criteria read (a solver's iterations): a stage may skip results that
              // only break a total down for the report (noise terms, echoes of inputs)
};

// What a stage sees while the chain runs.
class Context {
 public:
  Context(Results& results, Light& light, const std::string& section, const std::string& plugin,
          Detail detail = Detail::full, std::vector<ResultId>* declarations = nullptr,
          std::vector<ResultId>* lookups = nullptr)
      : results(results), light(light), section(section), plugin(plugin), detail(detail), declarations_(declarations),
        lookups_(lookups) {}

  Results& results;
  Light& light;
  const std::string& section;  // the stage being run: "optics", "criteria.detection"
  const std::string& plugin;   // (references: a Context is built per stage call and must cost nothing)
  const Detail detail;
  bool full_detail() const { return detail == Detail::full; }

  // Declares "<section>.<name>". A stage declares the same results in the same order at every spectral phase;
  // then this is a comparison of names, not a look-up.
  ResultId declare(std::string_view name, std::string_view si_unit, std::string_view equation,
                   std::string_view display_unit = {});
  // A result another stage must have declared; a missing one is a chain that does not fit together
  // (InputError naming both).
  ResultId require(std::string_view qualified_name);
  // (Like declare(): the same look-ups in the same order at every spectral phase are name comparisons.)
  std::optional<ResultId> find(std::string_view qualified_name);
  // The incoming radiation has a form this stage cannot take.
  [[noreturn]] void refuse_form(const std::string& what, RadiationForm form) const;

 private:
  std::vector<ResultId>* declarations_;  // this stage's declarations at its last spectral phase, in order
  std::size_t next_declaration_ = 0;
  std::vector<ResultId>* lookups_;       // the results it found, in order
  std::size_t next_lookup_ = 0;
};

// What a stage's scalar phase sees when it evaluates one point (a view of Context).
class ScalarAccess {
 public:
  using Value = double;
  explicit ScalarAccess(Context& context)
      : results_(context.results), light_(context.light), full_detail_(context.full_detail()) {}

  double param(const double* handle) const { return *handle; }
  bool varies(const double*) const { return false; }
  double value(ResultId id) const { return results_.value(id); }
  void set(ResultId id, double value) { results_.set(id, value); }
  double& illumination_scale() { return light_.illumination_scale; }
  double& signal_scale() { return light_.signal.scale; }
  double& background_scale() { return light_.background.scale; }
  double& up_path_scale() { return light_.up_path_scale; }
  const Light& light() const { return light_; }  // forms and spectra (set in the spectral phase)
  bool full_detail() const { return full_detail_; }

 private:
  Results& results_;
  Light& light_;
  bool full_detail_;
};

class Stage {
 public:
  virtual ~Stage();
  // Spectral phase: runs when the chain is built and whenever a parameter marked affects_spectrum changes.
  // Declare results here and do every spectral integral here.
  virtual void prepare(Context& context);
  // Scalar phase: runs at every evaluation that one of the stage's parameters, or an earlier stage, changed.
  // Read scalar parameters through Params::handle() pointers. Under Detail::essential, results no later stage
  // reads may be left unset (they keep their last values).
  virtual void evaluate(Context& context) = 0;
  // The scalar phase for lane_count points at once (radchain/lanes.hpp). Returns false when the stage has no
  // lane form; the chain then runs evaluate() once per lane.
  virtual bool evaluate_lanes(LaneContext& context);
};

// A stage whose scalar phase is one template, `template <class Access> void compute(Access&)` (radchain/lanes.hpp),
// run for one point (ScalarAccess) and for lane_count points (LaneContext):
//   class Telescope final : public LaneStage<Telescope> { public: template <class Access> void compute(Access&); };
template <class Derived>
class LaneStage : public Stage {
 public:
  void evaluate(Context& context) final {
    ScalarAccess access(context);
    static_cast<Derived*>(this)->compute(access);
  }
  bool evaluate_lanes(LaneContext& context) final {
    static_cast<Derived*>(this)->compute(context);
    return true;
  }
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
