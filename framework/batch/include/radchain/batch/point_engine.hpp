#pragma once
// How a sensor is evaluated at a point: one definition for every job that evaluates many (`radchain sweep`'s grid,
// Python's Session.sweep over arrays, the factored grid's checks).
//
// An engine owns one Chain, built once as every point starts from. A point gives each varying parameter a value in
// SI; the chain re-runs only what those values affect (Chain::set) and only the stages the asked results or the
// [[solve]] margins need (Chain::focus). Before each point the solved unknowns go back to their values in the chain
// as built, so a point's result does not depend on which points the engine ran before it: a job's output is the same
// for any thread count, block size or shard.
// Points go eight at a time through the lanes (Chain::set_lanes, evaluate_lanes, solve_lanes) when no varying
// parameter is spectral and the chain has at most one [[solve]] that lanes can run; else one at a time
// (Chain::set, solve_all / evaluate). Both give the same numbers to the solver's tolerance (tests/core/lanes_test).
#include "radchain/chain.hpp"
#include "radchain/lanes.hpp"

#include <array>
#include <cstddef>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace radchain {

class PointEngine {
 public:
  // Where a point's results go: result c of the k-th point of a call at first[k * row_stride + c * column_stride].
  struct Output {
    double* first;
    std::size_t row_stride, column_stride;
    double& at(std::size_t k, std::size_t c) const { return first[k * row_stride + c * column_stride]; }
  };
  // What a point is called in messages ("at optics.aperture = 20 cm", "point 17 (optics.aperture = 0.2)"): the
  // k-th point of the current call. Asked only when something goes wrong there.
  using PointName = std::function<std::string(std::size_t k)>;
  enum class Scale { si, display };  // results in SI or in their display units (a sweep's columns)

  // `results` must be the chain's result names (the job checked them). Throws what Chain::parameter throws.
  PointEngine(Chain chain, const std::vector<std::string>& parameters, const std::vector<std::string>& results,
              Scale scale, PointName name);

  // One point: parameter p takes values[p] (SI). Writes its results at row 0 of `out`; false where a solve failed
  // (the solved unknown's cell is NaN; failure(0) says where and why). A point the chain refuses (a look past the
  // horizon) throws InputError with the point named.
  bool evaluate(const double* values, Output out);
  // Up to lane_count points: parameter p of point k is values[p](k) (SI); a short group's unused lanes repeat its
  // last point. Rows 0..count of `out`, ok[k]; failure(k) where ok[k] is 0. Each point's results are the same
  // whichever points share its group.
  void evaluate_group(const std::vector<Lanes>& values, std::size_t count, Output out, char* ok);
  const std::string& failure(std::size_t k) const { return failures_[k]; }

  Chain& chain() { return chain_; }
  const Chain& chain() const { return chain_; }

 private:
  struct Column {
    ResultId id;
    double factor;  // to the output's unit
    bool solved;    // a solved unknown: NaN where its solve failed
  };
  bool evaluate_point(const double* values, Output out, std::size_t k);  // k: the point's index in the call
  std::string solve_failure(std::size_t k, const std::string& unknown, const std::string& why) const;

  Chain chain_;
  PointName name_;
  std::vector<ParameterRef> parameters_;
  std::vector<std::pair<ParameterRef, double>> unknowns_;  // solved parameters and their values as built
  std::vector<Column> columns_;
  std::vector<SolveOutcome> outcomes_;
  LaneSolveOutcome lane_outcome_;
  std::array<std::string, lane_count> failures_;
  std::vector<double> scalar_values_;  // one point of a group (the scalar path naming a refused point)
  bool lanes_ = false;
};

}  // namespace radchain
