#pragma once
// `radchain compare A B`: two sensor files, or saved results (`radchain run --format json`), side by side:
// every result (signal, each noise term, SNR, geometry, solved unknowns ...) with B − A in A's display unit
// and in percent, and, for sensor files, what differs in the inputs: the validated parameters section by
// section (as written, and in SI), the [[solve]] entries and the [expected] references.
// With a tolerance it is a regression test: exit 1 when a result moved by more than it. Without one, moves
// within rounding_tolerance are reported "ok", not "differs": two runs of the same physics reached by other
// arithmetic (a unit written differently, a solve started elsewhere) agree only to ~1e-12.
#include "radchain/chain.hpp"
#include "radchain/batch/table.hpp"

#include <optional>
#include <string>
#include <vector>

namespace radchain {

// Relative moves up to this count as rounding when no --tolerance is given. The solver stops within 2^-47
// (7e-15) of the root; the chain's results downstream of it move by a few times that, far below any physics.
inline constexpr double rounding_tolerance = 1e-9;

struct CompareInput {
  std::string path;
  std::string sensor_name;
  bool results_file = false;      // a saved `radchain run --format json` (no inputs to compare)
  Report report;
  std::optional<Chain> chain;     // a sensor file: its validated parameters
};

// A path ending in .json is a results file, anything else a sensor file (loaded and run, its solves included
// unless `solve` is false). Throws InputError.
CompareInput load_compare_input(const std::string& path, const std::vector<Override>& overrides = {}, bool solve = true);

struct InputDifference {
  std::string name;              // "optics.aperture", "optics.plugin", "solve[1].bracket", "expected.optics.aperture.value"
  std::string a, b;              // as written: "15 cm", "(default) 0.56", "(absent)"
  double a_value = 0, b_value = 0;  // numbers in `unit` (NaN when not a number)
  std::string unit;              // display unit: the one written in A (else B, else the schema example's)
  double a_si = 0, b_si = 0;     // SI (NaN when not a number)
  std::string si_unit;
};

struct ResultDifference {
  std::string name;
  std::string unit;        // display unit (A's)
  double factor = 1;       // display = SI × factor
  double a_si = 0, b_si = 0;
  bool in_a = false, in_b = false;
  double delta() const;     // (B − A) in the display unit
  double relative() const;  // (B − A) / |A| (NaN when A = 0 and B ≠ 0... infinite)
  bool same() const;        // equal bit for bit (or both NaN)
  // |B − A| > tolerance × max(|A|, |B|, floor), a NaN on one side only, or a result on one side only. The floor is 1
  // for a criterion's margin (achieved/required − 1: its scale is 1, and at a solved root it is 0 by construction,
  // ~1e-15, so relative to itself any two roots differ by 100 %), else 0.
  bool exceeds(double rel_tolerance) const;
  double scale_floor() const;
  // What `radchain compare` prints: "same", "ok", "differs" (beyond rounding) or, with a tolerance, "EXCEEDS";
  // "only in A/B" (EXCEEDS with a tolerance).
  std::string status(std::optional<double> rel_tolerance) const;
};

struct Comparison {
  std::string a_path, b_path, a_name, b_name;
  bool inputs_compared = false;  // both are sensor files
  std::vector<InputDifference> inputs;   // only what differs
  std::vector<ResultDifference> results; // every result: the solved unknowns first, then A's order, then B's own
  std::vector<std::string> solves;       // one line per solve: converged? binding criterion? in A and B
};

Comparison compare(const CompareInput& a, const CompareInput& b);
std::size_t count_exceeding(const Comparison& comparison, double rel_tolerance);

// "1e-6", "0.1%": a relative tolerance. Throws InputError.
double parse_tolerance(const std::string& text);

// Text: the inputs that differ, then every result side by side, then a summary line. Status of a result:
// same (bit for bit), ok (within the tolerance, else within rounding_tolerance), differs (no tolerance given)
// or EXCEEDS (the tolerance given).
std::string format_comparison_text(const Comparison& comparison, std::optional<double> tolerance = {});
// CSV / JSON: one table, columns kind (input/result), name, a, b, unit, delta, delta_pct, status.
void write_comparison(const Comparison& comparison, TableFormat format, std::ostream& out,
                      std::optional<double> tolerance = {});

}  // namespace radchain
