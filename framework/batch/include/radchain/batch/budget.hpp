#pragma once
// `radchain budget`: sensitivities (an error budget) of named results to every numeric input of the chain.
//
// For every numeric input parameter of every stage (quantity or number, scalar, present, not spectral, not the
// unknown of a [[solve]]) and every requested result r, the derivative ∂r/∂x (SI), the elasticity
// ∂r/∂ln x = x ∂r/∂x (in r's unit: the change of r for a relative change of x) and, for r > 0, the
// dimensionless ∂ln r/∂ln x. Solved unknowns are re-solved at every perturbed point, so ∂m/∂D is the
// derivative of the limiting magnitude along the constraint SNR = T.
//
// Derivatives are Ridders' method (C. J. F. Ridders, "Accurate computation of F'(x) and F'(x)F''(x)",
// Adv. Eng. Software 4(2) 75-76, 1982; Press et al., Numerical Recipes 3rd ed. §5.7, dfridr): central
// differences over a sequence of steps shrinking by 1.4, extrapolated to zero step in a Neville tableau, each
// extrapolation's error estimated from its neighbours; the estimate with the smallest error is kept. A
// parameter whose ±step leaves its schema range (a value at its bound) gets the same extrapolation of a
// one-sided (forward or backward) difference. A parameter whose evaluation or solve fails at a perturbed point
// is reported with the reason, never as a zero.
#include "radchain/chain.hpp"
#include "radchain/batch/table.hpp"

#include <iosfwd>
#include <string>
#include <vector>

namespace radchain {

struct BudgetOptions {
  std::vector<std::string> results;  // result names ("target.magnitude"); at least one
  double rel_tolerance = 1e-6;       // an entry whose error estimate exceeds this (relative) is marked "uncertain"
  double initial_step = 0.02;        // first step, relative to |x| (x = 0: relative to the range width, else 1 SI unit)
};

enum class DifferenceKind { central, forward, backward };
std::string to_string(DifferenceKind kind);

// One (result, parameter) pair.
struct BudgetEntry {
  std::string result;            // "target.magnitude"
  std::string result_unit;       // SI unit of the result
  double result_si = 0;          // the result at the nominal point
  std::string parameter;         // "optics.aperture"
  std::string parameter_unit;    // SI unit of the parameter ("1" for a number)
  std::string as_written;        // the value as the file (or --set) gives it; "(default)" when defaulted
  double value_si = 0;           // x
  double derivative = 0;         // ∂r/∂x, SI (result unit per parameter unit)
  std::string derivative_unit;   // "1/m", "e-/s"
  double elasticity = 0;         // x ∂r/∂x, result unit; for a magnitude x, ∂r/∂ln F = −(2.5/ln 10) ∂r/∂x
  bool per_flux = false;         // x is a magnitude: the elasticity is by the flux F = 10^(−0.4 x) it stands for
  double log_elasticity = 0;     // (x/r) ∂r/∂x; NaN when r ≤ 0
  double error = 0;              // Ridders' error estimate of ∂r/∂x (absolute)
  double step = 0;               // the first step h (SI)
  DifferenceKind kind = DifferenceKind::central;
  bool ok = true;                // false: `failure` says why (no derivative)
  bool accurate = true;          // error ≤ rel_tolerance × max(|∂r/∂x|, |r|/s), s = |x| (or the step scale)
  std::string failure;           // why there is no derivative
  std::size_t rank = 0;          // 1 = largest |elasticity| for this result (failed entries last)
};

struct Budget {
  std::string sensor_file, sensor_name;
  std::vector<std::string> results;      // as requested
  std::vector<double> nominal;           // each result at the nominal point (SI)
  std::vector<std::string> solved;       // the solved unknowns (re-solved at every point)
  std::vector<std::string> skipped;      // numeric parameters left out, with why ("detector.band_min (spectral)")
  std::size_t evaluations = 0;           // chain evaluations (each with its solves)
  std::vector<BudgetEntry> entries;      // grouped by result (in request order), ranked by |elasticity|
};

// Checks the result names against the chain (after a first evaluation with its solves). Throws InputError, one
// line: an unknown name (with the nearest result), a name that is an input parameter and not a result, a
// result that is not a finite number at the nominal point, no result at all.
void check_budget_results(Chain& chain, const std::vector<std::string>& results);

// The budget of `chain` as loaded (overrides applied; its solves, if any, re-run at every point). The chain's
// parameters are back at their nominal values when it returns. Throws InputError for bad result names, and
// std::runtime_error when the nominal point itself cannot be solved.
Budget compute_budget(Chain& chain, const BudgetOptions& options);

// The table: one row per entry. Columns: result, rank, parameter, value, unit, derivative, derivative_unit,
// elasticity, result_unit, log_elasticity, error, method, note.
TableLayout budget_layout();
TableData budget_table(const Budget& budget);  // the rows with their numbers as they are (Python binds these)
void write_budget(const Budget& budget, TableFormat format, std::ostream& out);
// Text: a header (sensor, nominal results, what was skipped) and, per result, the ranked table.
std::string format_budget_text(const Budget& budget);

}  // namespace radchain
