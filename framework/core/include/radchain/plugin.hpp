#pragma once
// The plugin interface. A plugin is one .cpp file, plugins/<kind>/<name>.cpp, ending in
//   RADCHAIN_PLUGIN(StageClass, {.summary = "...", .reference = "...", .schema = schema,
//                                .publishes = {vocabulary::...}, .needs = {vocabulary::...}})
// The build gives the name and kind (RADCHAIN_PLUGIN_NAME, RADCHAIN_PLUGIN_KIND, from the file's path), so a
// plugin never restates them. The host reads the exported ABI number before it calls anything in the library.
#include "radchain/lanes.hpp"
#include "radchain/light.hpp"
#include "radchain/results.hpp"
#include "radchain/schema.hpp"
#include "radchain/spectral_limits.hpp"
#include "radchain/version.hpp"
#include "radchain/vocabulary.hpp"

#include <boost/config.hpp>
#include <boost/dll/alias.hpp>

#include <array>
#include <initializer_list>
#include <cstdint>
#include <optional>
#include <memory>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace radchain {

enum class Kind { platform, source, target, atmosphere, optics, detector, criterion };

// The one table of kinds. A kind's plugins live in plugins/<name>/ (source tree, build tree and install
// prefix alike) and fill the sensor file's [<section>] (criteria: [criteria.<name>]).
struct KindInfo {
  Kind kind;
  std::string_view name;     // "criterion": RADCHAIN_PLUGIN_KIND, the plugin folder, `radchain describe criterion`
  std::string_view section;  // "criteria"
};
inline constexpr std::array<KindInfo, 7> kinds{{
    {Kind::platform, "platform", "platform"},
    {Kind::source, "source", "source"},
    {Kind::target, "target", "target"},
    {Kind::atmosphere, "atmosphere", "atmosphere"},
    {Kind::optics, "optics", "optics"},
    {Kind::detector, "detector", "detector"},
    {Kind::criterion, "criterion", "criteria"},
}};
std::string to_string(Kind kind);                              // "source"
std::string kind_directory(Kind kind);                         // "source": plugins/source/
std::optional<Kind> kind_from_name(std::string_view name);     // a kind's name (or its folder), else nothing
// The kind of a sensor file's section: "optics" -> optics, "criteria.detection" -> criterion. Throws
// std::logic_error for a section that is no kind's.
Kind kind_of_section(std::string_view section);

// How much a scalar evaluation computes.
enum class Detail {
  full,       // every declared result: what a report, a sweep column or a comparison shows
  essential,  // what later stages and the criteria read (a solver's iterations): a stage may skip results that
              // only break a total down for the report (noise terms, echoes of inputs)
};

// What a stage declared and looked up at its last spectral phase, in order. The next spectral phase's same
// declarations and look-ups are then comparisons with this (the contract is checked once), and compare contiguous
// memory instead of the results' own strings: after a spectral phase's integrals have streamed their tables through
// the cache, every result's strings are cache misses.
// A term is a constant object, so the same term (the same address, from the same plugin) is the same name and
// unit. A text (a plain name, a unit, an equation) that was a string literal, i.e. lay in a segment a loaded object
// maps read-only, is the same text when the same address comes again; any other text is compared with the copy
// kept here: a plugin may build an equation in a buffer it reuses, and a changed one must reach the report.
// Results are never removed or renamed, so an id remembered for a name keeps it.
struct StageMemo {
  struct Declared {
    ResultId id = 0;
    const Term* term = nullptr;  // null: a plain name, whose name and unit lead its text
    std::uint32_t text_begin = 0;
    std::uint32_t name_size = 0, unit_size = 0, equation_size = 0;
    const char* literal[3] = {nullptr, nullptr, nullptr};  // name, unit, equation: the literal's address, or null
  };
  struct LookUp {
    ResultId id = SIZE_MAX;  // SIZE_MAX: not found (a miss stays a miss while no result is declared)
    const Term* term = nullptr;
    std::size_t results_then = 0;
  };
  std::vector<Declared> declarations;
  std::string text;  // the declarations' texts, back to back
  std::vector<LookUp> lookups;
};

// What one stage's spectral phase passed on to later stages' spectral phases through results, and what it took
// from earlier ones (Context::set_in_spectral_phase, read_in_spectral_phase); the chain keeps one per stage and
// makes the scalar parameters behind a result that a later spectral phase reads spectral in that chain.
struct SpectralExchange {
  struct Set {
    ResultId id = 0;
    double value = 0;
    std::vector<const double*> parameters;  // the producing stage's scalar parameters it follows from (handles)
  };
  std::vector<Set> set;        // in the order set
  std::vector<ResultId> read;  // results of earlier stages read in the spectral phase, in order
};

// What a stage sees while the chain runs.
class Context {
 public:
  Context(Results& results, Light& light, const std::string& section, const std::string& plugin,
          Detail detail = Detail::full, StageMemo* memo = nullptr, SpectralExchange* exchange = nullptr,
          std::vector<std::string>* warnings = nullptr)
      : results(results), light(light), section(section), plugin(plugin), detail(detail), memo_(memo),
        exchange_(exchange), warnings_(warnings) {}

  Results& results;
  Light& light;
  const std::string& section;  // the stage being run: "optics", "criteria.detection"
  const std::string& plugin;   // (references: a Context is built per stage call and must cost nothing)
  const Detail detail;
  bool full_detail() const { return detail == Detail::full; }

  // Declares "<section>.<name>". A stage declares the same results in the same order at every spectral phase;
  // then this is a comparison with its StageMemo, not a look-up (cheapest with literal texts).
  // A result only this stage's report shows; a name of the vocabulary must be declared as its Term.
  ResultId declare(std::string_view name, std::string_view si_unit, std::string_view equation,
                   std::string_view display_unit = {});
  // A result of the vocabulary (its unit is the term's): the plugin must list it in `publishes`
  // (std::logic_error otherwise, naming plugin and term).
  ResultId declare(const Term& term, std::string_view equation, std::string_view display_unit = {});
  // A result another stage must have declared; a missing one is a chain that does not fit together
  // (InputError naming both). The plugin must list the term in `needs` (std::logic_error otherwise).
  ResultId require(const Term& term);
  // A result this stage reads if an earlier stage declared it. The plugin must list the term in `needs`,
  // usually as if_present(term) (std::logic_error otherwise).
  // (Like declare(): the same look-ups in the same order at every spectral phase are name comparisons, misses too.)
  std::optional<ResultId> find(const Term& term);
  // Spectral phase only. Sets a result now, so that a later stage's spectral phase can read it (the scalar phase
  // sets it again), and names the stage's scalar parameters it follows from (Params::handle pointers). In a chain
  // where a later stage reads it with read_in_spectral_phase(), those parameters are spectral (a change through
  // Chain::set re-runs the spectral phase from this stage; ParameterRef::spectral(), so never lanes); in any other
  // chain they stay scalar. A key marked affects_spectrum needs no naming. (std::logic_error outside prepare().)
  void set_in_spectral_phase(ResultId id, double value, std::initializer_list<const double*> scalar_parameters = {});
  // Spectral phase only: the value an earlier stage's spectral phase set (set_in_spectral_phase; the chain checks
  // that one did). A look-up alone (find, require) makes no such dependency: a stage that reads a result only in
  // its scalar phase leaves the producer's parameters scalar.
  double read_in_spectral_phase(ResultId id);
  // The incoming radiation has a form this stage cannot take.
  [[noreturn]] void refuse_form(const std::string& what, RadiationForm form) const;
  // A result that is computed but physically suspect (an equation used outside its fitted range, a table
  // extrapolated): the located line (Params::problem) reaches the report's warnings, in text and JSON. A warning of
  // the spectral phase lasts until the stage's next spectral phase, one of the scalar phase until its next
  // evaluation, so the report shows those of the values it prints.
  void warn(const InputError& warning);

 private:
  ResultId declare_result(const Term* term, std::string_view name, std::string_view si_unit, std::string_view equation,
                          std::string_view display_unit);
  void remember_declaration(ResultId id, const Term* term, std::string_view name, std::string_view si_unit,
                            std::string_view equation);
  std::optional<ResultId> look_up(const Term& term, bool required);

  StageMemo* memo_;  // this stage's last spectral phase (null in the scalar phase)
  std::size_t next_declaration_ = 0;
  std::size_t next_lookup_ = 0;
  SpectralExchange* exchange_;           // the spectral phase's (null in the scalar phase)
  std::vector<std::string>* warnings_;   // this stage's, of this phase (null: not kept, e.g. one lane of many)
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
  // True when, as configured, every result is a product of powers of the stage's inputs and parameters and every
  // noise variance a sum of such terms (no thresholds, no tables or PSF integrals over a scalar): a scaled unknown
  // upstream then stays a power law through it, and a [[solve]] across it may be inverted in closed form.
  virtual bool power_law() const { return false; }
  // True when every signal is a power of the signal scale the stage receives (the flux through which a target's
  // magnitude acts) times factors that do not depend on it, and every variance or pixel level a sum of such terms.
  // Weaker than power_law(): a PSF integral over the optics' f-number is allowed, since the flux does not move it.
  // A [[solve]] for a magnitude may then be inverted in closed form across the stage.
  virtual bool power_law_in_signal() const { return power_law(); }
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

// A result a plugin reads: required (Context::require), or read when present (if_present, Context::find).
struct Need {
  Term term;
  bool optional = false;
  constexpr Need(const Term& term, bool optional = false) : term(term), optional(optional) {}  // NOLINT: implicit
};
constexpr Need if_present(const Term& term) { return Need(term, true); }

// How a criterion's margin inverts in closed form when every stage between the unknown and it is a power law
// (solver.cpp): power_law — achieved/required is c·u^k in the unknown's variable u; noise_equation — the margin is
// SNR/T − 1 with SNR = S/n the detector's signal and noise electrons, S ∝ u^k and n² = b·S + c (shot noise of the
// signal plus what does not scale with it, or scales as it does), so S at SNR = T solves a quadratic.
enum class InverseForm { none, power_law, noise_equation };

// What a plugin file states about itself; the build supplies its name and kind.
struct PluginDescription {
  const char* summary = "";    // one line
  const char* reference = "";  // where the physics comes from
  const Schema& (*schema)() = nullptr;
  std::vector<Term> publishes = {};  // the vocabulary terms it declares (some only in some configurations)
  std::vector<Need> needs = {};      // the vocabulary terms it reads
  InverseForm inverse = InverseForm::none;  // a criterion: its margin's closed-form inverse
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
  std::vector<Term> publishes;
  std::vector<Need> needs;
  InverseForm inverse;

  bool publishes_term(const Term& term) const;
  const Need* need_of(const Term& term) const;
};

template <class StageType>
PluginInfo make_plugin_info(Kind kind, const char* name, PluginDescription d) {
  return PluginInfo{plugin_abi_version, framework_version, kind, name, d.summary, d.reference, d.schema,
                    [](const Params& p) -> std::unique_ptr<Stage> {
                      if constexpr (std::is_constructible_v<StageType, const Params&>) return std::make_unique<StageType>(p);
                      else return std::make_unique<StageType>();  // a stage without parameters
                    },
                    std::move(d.publishes), std::move(d.needs), d.inverse};
}

}  // namespace radchain

// Declares the plugin's entry: use once, at the bottom of the plugin's .cpp file, with the Stage class (built
// from `const Params&`) and a PluginDescription's designated initialisers:
//   RADCHAIN_PLUGIN(SnrThreshold, {.summary = "...", .reference = "...", .schema = schema,
//                                  .publishes = {vocabulary::criterion_margin}, .needs = {vocabulary::detector_snr}})
// radchain_add_plugin() defines RADCHAIN_PLUGIN_NAME ("snr_threshold") and RADCHAIN_PLUGIN_KIND (criterion) from
// the file's path. It exports two symbols: the ABI number and the Boost.DLL alias radchain_plugin_info.
// Outside radchain_add_plugin() the compiler's error names the fix.
#ifndef RADCHAIN_PLUGIN_NAME
#define RADCHAIN_PLUGIN_NAME radchain_plugin_name_is_defined_by_cmake_radchain_add_plugin
#endif
#ifndef RADCHAIN_PLUGIN_KIND
#define RADCHAIN_PLUGIN_KIND radchain_plugin_kind_is_defined_by_cmake_radchain_add_plugin
#endif
#define RADCHAIN_PLUGIN(StageType, ...)                                                                        \
  static const ::radchain::PluginInfo& radchain_plugin_entry() {                                               \
    static const ::radchain::PluginInfo info = ::radchain::make_plugin_info<StageType>(                        \
        ::radchain::Kind::RADCHAIN_PLUGIN_KIND, RADCHAIN_PLUGIN_NAME, ::radchain::PluginDescription __VA_ARGS__); \
    return info;                                                                                               \
  }                                                                                                            \
  extern "C" BOOST_SYMBOL_EXPORT const std::uint32_t radchain_plugin_abi_version;                              \
  extern "C" BOOST_SYMBOL_EXPORT const std::uint32_t radchain_plugin_abi_version = ::radchain::plugin_abi_version; \
  BOOST_DLL_ALIAS(radchain_plugin_entry, radchain_plugin_info)
