#pragma once
// Limiting magnitudes over a Cartesian grid, factored by axis (docs/performance.md, "Factored grids").
//
// A sweep whose one [[solve]] is a target's magnitude that the chain inverts in closed form through the noise
// equation (solver.cpp's one-end form) has at every point x
//   m(x) = m_end − 2.5 lg(S*(x) / S_end(x)),   S* = (T² + √(T⁴ + 4T²c))/2   (Pan 2010 eq. (11)),
// with S_end the signal at the faint bracket end m_end, c = n² − S the variance that does not scale with it and T the
// criterion's threshold. When every stage from a swept parameter to the detector declares power-law results
// (Stage::power_law(): each result a product of powers of the stage's inputs and parameters, each noise variance a
// sum of such terms), S_end is a product of powers of the axes and c a sum of such products, so
//   lg S_end(x) = lg S_end(x₀) + Σ_a [lg S_end(x₀ with axis a at x_a) − lg S_end(x₀)]
// exactly (x₀ the grid's first point), and c and T depend only on the axes J they vary with. A sum of products of
// powers with positive coefficients is strictly convex in the logarithm of each variable it depends on, so it cannot
// take one value at three points of an axis unless it does not depend on that axis at all: the plan evaluates c and
// T at the first, middle and last step of each axis, at every corner of the other axes, and puts the axis in J where
// they move (by more than 1e-12 relative: rounding). The chain is then evaluated along each axis through x₀ (a long
// axis whose parameter declares a power law: at its ends, the law between them checked at its quarters) and over
// the sub-grid of J, and a point costs additions:
//   m(x) = P[x_J] + Σ_a B_a[x_a],  P = m_end + 2.5 lg S_end(x₀) − 2.5 lg S*(c, T),  B_a = 2.5 [lg S_end(.., x_a, ..) − lg S_end(x₀)].
// A sky in the pixel (or an airmass, a seeing: stages that declare no power law) puts every axis into J. The floor is
// then still a sum over noise sources, c = Σ_k c_k, and where the detector publishes the sources
// (vocabulary::floor_variances: sky, dark, read, fixed pattern) each is typically a product of one factor per axis
// (n_eff(seeing, X) × sky(m_sky) × t for the sky). The plan reads the terms at every point it evaluates, checks
// that they add up to n² − S there (PRNU, which grows with S, is no floor) and that each separates like lg S_end at
// every corner, and a point then costs the closed form itself:
//   c(x) = Σ_k Π_a F_ka[x_a],   m(x) = m_end + 2.5 lg S_end(x₀) + Σ_a B_a[x_a] − 2.5 lg S*(c(x), T).
// This separation is verified where the chain was evaluated, not proven from declarations as the power laws are.
// A sweep with no [[solve]] that reads only the detector's SNR, signal or noise factors the same way: the signal a sum
// of per-axis products (the surface's electrons, the path radiance's), the floor another, n = √(S + c), SNR = S/n.
// Nothing is taken on trust: the plan also checks that lg S_end separates at those corners, and the whole plan
// against the per-point solve (SweepWorker::evaluate) at the grid's corners and 64 points spread over it, to 1e-11
// relative; anything that does not fit leaves every point to the per-point path, which says why
// (Sweep::method()). Points whose root lies outside the bracket or within 1e-9 of an end are solved on their own,
// so a failed point reports the per-point solver's text.
#include "radchain/chain.hpp"

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace radchain {

class Sweep;
class SweepWorker;

class FactoredGrid {
 public:
  // The plan for `sweep`'s whole grid (shards included: a shard's points get the values the whole sweep gives them),
  // built with `worker`'s chain and checked against its per-point solves. Nothing, and why not in `why_not`, where
  // the grid does not factor or is too small for factoring to pay.
  static std::optional<FactoredGrid> plan(const Sweep& sweep, SweepWorker& worker, std::string& why_not);

  // Points first, first + stride, … (`count` of them) into consecutive rows of `out` (Sweep::columns() each): the
  // axes in their units, then the result columns (each the solved magnitude in its display unit). ok[k] = 0 where
  // the point must be solved on its own (SweepWorker::evaluate): its row's result cells then mean nothing.
  void evaluate(std::size_t first, std::size_t count, std::size_t stride, double* out, char* ok) const;

  // "closed form factored over the grid: the noise floor varies with detector.integration_time; 436 chain
  // evaluations, 72 points checked against the per-point solve"
  const std::string& description() const { return description_; }

 private:
  FactoredGrid() = default;
  std::vector<std::size_t> steps_;                 // per axis
  std::vector<std::vector<double>> axis_values_;   // per axis, each step's value in the axis's unit
  std::vector<std::vector<double>> axis_columns_;  // per axis, each step's value as its column holds it (unit or SI)
  std::vector<std::vector<double>> axis_terms_;    // B_a per step
  std::vector<double> floor_terms_;                // P over the sub-grid of J, first axis outermost
  std::vector<std::size_t> floor_strides_;         // per axis: its stride in floor_terms_ (0 for an axis not in J)
  // Or the floor as a sum of per-axis products: term t's factor along axis a at [t * axes + a][step] (axis 0's
  // the term itself along its line, the others' ratios to its value at x₀), with the grid's one T.
  std::size_t term_count_ = 0;
  std::vector<std::vector<double>> term_factors_;
  double threshold_ = 0, base_ = 0;                // T; m_end + 2.5 lg S_end(x₀)
  // Forward results (no [[solve]]): the first signal_terms_ of the terms are the signal's, the rest the floor's;
  // per result column 0 SNR, 1 signal, 2 noise.
  bool forward_ = false;
  std::size_t signal_terms_ = 0;
  std::vector<int> result_kinds_;
  // steps_, axis_values_, axis_columns_ and column_factors_ (SI to each result column's unit) of `sweep`.
  void set_columns(const Sweep& sweep, const Results& results);
  static std::optional<FactoredGrid> plan_forward(const Sweep& sweep, SweepWorker& worker, std::string& why_not);
  void fill_forward(double* rows, char* ok, std::size_t run, const std::vector<std::size_t>& index,
                    std::vector<double>& outer_values, std::size_t i0) const;
  std::vector<double> column_factors_;             // per result column: SI to its column's unit (display or SI)
  double bright_ = 0, faint_ = 0;                  // the bracket (magnitudes)
  std::string description_;
};

}  // namespace radchain
