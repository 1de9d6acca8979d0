#pragma once
// A sensor file becomes a Chain: one stage per section, evaluated in the order
//   platform -> source -> atmosphere -> target -> optics -> detector -> criteria.*
// run() evaluates it forward, then performs the [[solve]] entries (Boost.Math toms748 on the named criterion's
// margin), then checks the [expected] references.
//
// Both phases are incremental. A change of parameter through set() marks its stage: the next evaluate() re-runs
// the spectral phase (prepare) from the first stage whose spectral parameter changed, and the scalar phase from
// the first stage whose parameter changed, each from the light as it was before that stage. A sweep over the
// aperture therefore re-runs optics, detector and criteria, never the Sun's spectral integrals.
// A parameter is spectral when its schema says so (affects_spectrum), or in this chain when a later stage's
// spectral phase reads a result that follows from it (Context::set_in_spectral_phase, read_in_spectral_phase:
// an earth_orbit platform's roll where an airmass_lut atmosphere takes its view airmass from the view zenith).
#include "radchain/config.hpp"
#include "radchain/light.hpp"
#include "radchain/plugin.hpp"
#include "radchain/results.hpp"
#include "radchain/schema.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace radchain {

struct StageSlot {
  std::string section;  // "optics", "criteria.detection"
  std::string plugin;   // info->name
  const PluginInfo* info = nullptr;
  std::unique_ptr<Params> params;
  std::unique_ptr<Stage> stage;
  StageMemo memo;                      // what the stage declared and looked up at its last spectral phase
  SpectralExchange exchange;           // what its last spectral phase set for later ones and read from earlier ones
  std::vector<std::string> spectral_warnings, scalar_warnings;  // Context::warn of its last phase of each kind
  bool informational = false;          // a criterion whose failure is reported but does not fail the run
};

// A numeric parameter of one stage, found once by name ("optics.aperture"); Chain::set() through it marks what
// the next evaluation must re-run.
class ParameterRef {
 public:
  double value() const { return *value_; }
  std::size_t stage() const { return stage_; }
  // Changing it re-runs the spectral phase from its stage: its schema's affects_spectrum, or in this chain a later
  // stage's spectral phase reads a result that follows from it (as of the chain's last spectral phase).
  bool spectral() const { return spectral_; }
  Scaling scaling() const { return scaling_; }

 private:
  friend class Chain;
  double* value_ = nullptr;
  std::size_t stage_ = 0;
  bool spectral_ = false;
  Scaling scaling_ = Scaling::none;
};

// How a [[solve]] is performed: auto inverts in closed form where the chain declares it can (solver.cpp) and
// checks the margin there, else brackets the root; root always brackets (--solver root, to compare).
enum class SolverChoice { automatic, root };

// [[solve]] unknown = "optics.aperture"  criterion = "energy"  bracket = ["1 cm", "2 m"]
// With several criteria (criterion = ["energy", "matching"]) each margin is driven to zero in turn, and the
// value at which every listed margin is ≥ 0 is kept: that criterion binds.
struct SolveSpec {
  std::string unknown;                  // "<section>.<parameter>", a quantity or number parameter
  std::vector<std::string> criteria;    // names under [criteria.<name>]; "criteria.<name>.margin" is driven to 0
  double lo = 0, hi = 0;  // bracket in SI; from the file, else the parameter's range
  SourceLocation where;
};

// [expected] "optics.focal_length" = { value = "832 mm", tolerance = "1 mm", source = "Kolobrodov 1996, p. 4" }
//            "optics.aperture" = { value = "206 mm", follows = "65.0 mm", tolerance = "0.5 mm", source = "..." }
struct Expectation {
  std::string result;
  double value_si = 0;
  double tolerance_si = 0;      // absolute
  double rel_tolerance = 0;     // relative (either or both)
  std::string as_written;       // "832 mm"
  // An erratum: the value that follows from the paper's own formula and inputs (docs/ explain the difference).
  // When given, the check is against it; the printed value is still shown beside it.
  std::optional<double> follows_si;
  std::string follows_as_written;
  std::string display_unit;     // the unit it was written in ("" = the result's display unit)
  // What the reference is: "published" (the instrument's datasheet, calibration or measured figure), "peer" (another
  // tool's computation from the same inputs), "paper" (a paper's worked example), "internal" (radchain against
  // itself: a closed form, another path); "" when the file does not say.
  std::string kind;
  std::string source;
  SourceLocation where;
};

// [[table]] vary = "detector.integration_time"  values = ["1 s", "10 s", "30 s"]  results = ["target.magnitude"]:
// the [[solve]] entries (and the named results) again at each value of one parameter — the per-instrument table
// downstream tools store (limiting magnitude vs exposure). run() fills it and then puts the chain back.
struct TableSpec {
  std::string name;                         // a title ("limiting magnitude vs exposure"); default: "<results> vs <vary>"
  std::string vary;                         // "<section>.<parameter>", numeric
  std::vector<double> values_si;
  std::vector<std::string> values_written;  // as written: "30 s"
  std::vector<std::string> results;         // result names; default: the solved unknowns
  SourceLocation where;
};

struct SolveOutcome {
  SolveSpec spec;
  double value_si = 0;
  int iterations = 0;
  bool converged = false;
  std::string message;  // why not, when not
  std::string binding;  // the criterion whose root was kept
  std::vector<std::pair<std::string, double>> roots;  // each criterion's own root (SI)
  std::string method;    // how the binding criterion's root was found: "closed form (noise equation)", "root (TOMS 748)"
  std::string fallback;  // why auto bracketed instead ("" when it did not, or --solver root)
};

// A [[solve]] in lanes: one root per lane (Chain::solve_lanes).
struct LaneSolveOutcome {
  Lanes value;                                  // SI; NaN where the lane's solve failed
  std::array<bool, lane_count> converged{};
  std::array<std::string, lane_count> message;  // why not, where not
  int passes = 0;                               // lane evaluations
  int closed_form = 0;                          // lanes whose root came from the closed form
  // Input: what the last evaluation at the roots computes. Detail::essential when only the solved values are read
  // (a sweep of limiting magnitudes): then no noise term's square root is taken for nothing.
  Detail final_detail = Detail::full;
  std::vector<Lanes> criterion_roots;           // scratch, reused between groups (no allocation per group)
};

struct ExpectationOutcome {
  Expectation spec;
  double computed_si = 0;
  bool found = false;
  bool passed = false;
};

// [uncertainty] "optics.transmittance" = "normal(0.56, 0.02)": an input's tolerance, kept with the design
// (radchain/distribution.hpp parses it; `radchain uncertainty` and `catalogue --uncertainty` sample it).
struct UncertaintySpec {
  std::string key;   // "<section>.<parameter>"
  std::string text;  // "normal(0.56, 0.02)"
  SourceLocation where;
};

// One [[table]] as computed: a row per value, a column per result (SI; NaN where that row's solve failed).
struct TableOutcome {
  TableSpec spec;
  std::vector<ResultInfo> columns;
  std::vector<std::vector<double>> rows;
  std::vector<std::string> notes;  // per row: "" or why a solve failed there
};

// A criterion as the run left it: its margin (achieved/required − 1: ≥ 0 holds) and whether it holds. The criterion
// a converged [[solve]] drove to 0 holds by construction (its margin is the solver's residual, ~1e-15).
struct CriterionOutcome {
  std::string section;       // "criteria.unsaturated"; "detector" for the detector's own saturation check
  double margin = 0;
  bool passed = true;
  bool informational = false;  // `informational = true`: reported, and the run still passes
  std::string reason;          // why it fails ("" when it holds)
};

struct Report {
  std::string sensor_file;
  std::string sensor_name;
  std::vector<ResultInfo> results;        // in declaration order
  std::vector<double> values;             // SI, NaN when not evaluated
  std::vector<SolveOutcome> solves;
  std::vector<ExpectationOutcome> expectations;
  std::vector<TableOutcome> tables;       // [[table]] entries (a failed row is reported, not a failed check)
  std::vector<CriterionOutcome> criteria; // every criterion, and the detector's saturation without one
  std::vector<std::string> warnings;      // located lines: results computed but physically suspect (Context::warn)
  // Every solve converged, every expectation passed, and every criterion not marked informational holds.
  bool all_passed() const;
  std::optional<double> value(const std::string& name) const;
};

class Chain {
 public:
  Chain() = default;
  Chain(Chain&&) = default;
  Chain& operator=(Chain&&) = default;

  std::string sensor_file, sensor_name, description;
  std::vector<StageSlot> stages;
  std::vector<SolveSpec> solves;
  std::vector<Expectation> expected;
  std::vector<TableSpec> tables;
  std::vector<UncertaintySpec> uncertainties;
  SolverChoice solver = SolverChoice::automatic;

  // What changed since the last evaluation: the spectral phase from the first stage with a changed spectral
  // parameter, then the scalar phase from the first stage with any change. Detail::essential (a solver's
  // iterations) lets stages skip results that only break totals down; a later Detail::full evaluation
  // recomputes them.
  void evaluate(Detail detail = Detail::full);
  // Every result again (the spectral phase only where something spectral changed) + solves + expectations +
  // tables.
  Report run();
  // Work only for these results and the [[solve]] margins: a stage after the last one that publishes any of them,
  // and a criterion that publishes none of them, is not evaluated (a sweep of detector.snr integrates no GIQE
  // criterion's MTF budget). The skipped stages' results are then stale; focus({}) (and run()) evaluates every
  // stage again, re-running the ones that were skipped.
  void focus(const std::vector<ResultId>& wanted);
  bool skips(std::size_t stage) const { return stage < skip_.size() && skip_[stage]; }
  // One [[table]]: per value, the parameter set, solve_all(), the columns read; then the parameter and the solved
  // unknowns are put back as they were and the chain re-evaluated.
  TableOutcome tabulate(const TableSpec& table);

  // Lanes (radchain/lanes.hpp): the scalar phase for lane_count points at once. set_lanes() gives a non-spectral
  // parameter a value per lane (it keeps its scalar value for evaluate()); evaluate_lanes() runs from the first
  // stage with such a parameter, taking earlier stages' results from the scalar phase, and lane_result() reads.
  void set_lanes(const ParameterRef& parameter, const Lanes& values);
  void clear_lanes() { lane_parameters_.clear(), lane_slots_.clear(); }
  void evaluate_lanes(Detail detail = Detail::full);
  const Lanes& lane_result(ResultId id) const { return lane_results_[id]; }
  // The chain's one [[solve]] for each lane's point (the lane parameters as set), in lockstep: Dekker's method
  // (secant or bisection, bracketing) on log2(1 + margin), to solve_all()'s tolerance (bracket ≤ 2^-47
  // relative). TOMS 748 (solve_all()) keeps per-point state a lockstep loop cannot share; both bracket the same
  // root. Ends with a Detail::full lane evaluation at the roots. Needs lanes_can_solve().
  bool lanes_can_solve() const;  // exactly one [[solve]], on a non-spectral unknown
  void solve_lanes(LaneSolveOutcome& outcome);

  // A numeric parameter "<section>.<key>". Throws std::out_of_range for an unknown section or a key that is
  // not numeric, and the schema's std::logic_error for an unknown key.
  ParameterRef parameter(const std::string& qualified_key);
  StageSlot& slot(const std::string& section);
  // Sets a parameter (SI) and marks its stage for the next evaluation.
  void set(const ParameterRef& parameter, double value_si);
  void set(const std::string& qualified_key, double value_si) { set(parameter(qualified_key), value_si); }
  // Marks both phases of every stage for the next evaluation (after a spectral parameter was replaced; the
  // cold cost that benchmarks measure).
  void invalidate_spectra();
  // The [[solve]] entries exactly as run() performs them (passes until no unknown moves; each solve ends with a
  // full evaluation at its root), without a Report: what a sweep point costs. `outcomes` is reused.
  void solve_all(std::vector<SolveOutcome>& outcomes);
  // Resolves each solve's unknown and margins once, and the results that echo the solved values, in the order
  // of `solves` (load_sensor).
  void resolve_solves(const std::vector<ResultId>& echo_ids);
  // Forward only from now on (`--no-solve`, Solving::forward_only): the [[solve]] entries are dropped, every unknown
  // keeps the value it has (the file's, or --set's) and its result still echoes it; no criterion is driven to zero.
  void drop_solves();

  // The one [[solve]] when its unknown is a target's magnitude and its one criterion inverts through the noise
  // equation from the faint bracket end (solver.cpp): what that closed form reads. A sweep factors a grid of such
  // limiting magnitudes by axis (radchain/batch/factored_grid.hpp). Nothing with --solver root or for another solve.
  struct MagnitudeInversion {
    ParameterRef unknown;
    std::size_t criterion_stage = 0;    // index in `stages`
    ResultId signal = 0, noise = 0;     // the detector's S and n (electrons)
    ResultId threshold = 0;             // the criterion's T
    double faint = 0, bright = 0;       // the bracket's ends: the larger magnitude and the smaller
  };
  std::optional<MagnitudeInversion> magnitude_inversion() const;

  Results& results() { return results_; }
  const Results& results() const { return results_; }
  double result(const std::string& name) const;  // throws std::out_of_range when unknown

 private:
  // The light's scalars, saved before each stage's evaluate() so that the scalar phase can restart there.
  struct Scales {
    double illumination = 1, signal = 1, background = 1, up_path = 1;
  };
  void prepare_from(std::size_t first);
  // The scalar parameters behind results that a later stage's spectral phase read (StageSlot::exchange), after a
  // spectral phase; and whether a parameter is one of them.
  void find_spectral_reads();
  bool read_in_spectral_phase(const double* parameter) const;
  void evaluate_from(std::size_t first, Detail detail);
  void evaluate_lane_by_lane(StageSlot& slot, Detail detail);  // a stage without evaluate_lanes()
  std::vector<CriterionOutcome> criterion_outcomes(const std::vector<SolveOutcome>& solves) const;

  Results results_;
  Light light_;
  std::vector<Light> light_before_;    // per stage: the light its prepare() started from (shared spectra)
  std::vector<Scales> scales_before_;  // per stage: the scales its evaluate() started from
  std::vector<double> saved_values_;   // scratch of evaluate_lane_by_lane()
  std::size_t spectral_from_ = 0;      // first stage whose prepare() must re-run (stages.size(): none)
  std::vector<const double*> read_spectrally_;  // scalar parameters a later spectral phase depends on (find_spectral_reads)
  std::size_t scalar_from_ = 0;        // first stage whose evaluate() must re-run
  std::vector<char> skip_;             // per stage: not evaluated (focus); empty: none
  std::size_t essential_from_ = SIZE_MAX;  // first stage last evaluated with Detail::essential
  std::uint64_t scalar_version_ = 0;       // counts scalar evaluations (lanes copy their results when it moves)
  // Lanes: the varying parameters (with their stages), each result and the light's scalars per lane.
  struct LaneSlot {
    double* address;
    std::size_t stage;
  };
  std::vector<LaneParameter> lane_parameters_;
  std::vector<LaneSlot> lane_slots_;  // parallel to lane_parameters_
  std::vector<Lanes> lane_results_;
  std::uint64_t lane_base_version_ = UINT64_MAX;  // the scalar evaluation lane_results_ were copied from
  LaneScales lane_scales_;
  // Each [[solve]] resolved once: its unknown, its criteria's margins, the result that echoes the solved value.
  // Per criterion: its closed-form inverse, if the chain allows one (else why not).
  struct Inversion {
    InverseForm form = InverseForm::none;
    std::string why_not;
    ResultId signal = SIZE_MAX, noise = SIZE_MAX;  // noise_equation: the detector's S and n
    ResultId threshold = SIZE_MAX;                 // noise_equation: the criterion's T, where it publishes one
    bool through_signal = false;                   // a target's magnitude: it acts only through the flux
  };
  struct ResolvedSolve {
    ParameterRef unknown;
    std::vector<ResultId> margins;
    std::vector<Inversion> inversions;  // parallel to margins
    ResultId echo = SIZE_MAX;
  };
  Inversion inversion_for(const ParameterRef& unknown, const std::string& criterion);
  void solve(std::size_t index, SolveOutcome& outcome);
  std::vector<ResolvedSolve> resolved_;
};

// One `--set key=value` override: "optics.aperture=20 cm", "target.magnitude=15".
struct Override {
  std::string key;
  std::string value;
};

// What a loaded chain does with its [[solve]] entries: performs them, or evaluates forward only (`--no-solve`:
// Chain::drop_solves()).
enum class Solving { as_written, forward_only };

// Parses, validates and builds. Throws InputError for any bad input (file, line, key, what is accepted).
Chain load_sensor(const std::string& path, const std::vector<Override>& overrides = {},
                  Solving solving = Solving::as_written);

}  // namespace radchain
