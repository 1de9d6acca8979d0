#pragma once
// A sensor evaluated at arbitrary points, on all cores: every point gives each listed parameter a value in SI (one
// array per parameter, point i reads values[p][i]), and the chain is evaluated there, its [[solve]] entries re-run
// unless no_solve. What Python's Session.sweep() calls (python/); `radchain sweep` (sweep.hpp) steps
// from:to:steps ranges instead, through the same engine.
//
// Every worker thread owns a point engine (radchain/batch/point_engine.hpp: how a point is evaluated, lanes or one at
// a time, solved unknowns reset before each point) whose Chain `make_chain` builds once (so a chain may come from a
// file, from text, or carry values set in SI). The output is the same for any thread count.
#include "radchain/chain.hpp"

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace radchain {

// The numeric parameter "<section>.<key>" of `chain`, or InputError located at `where` (e.g. "set optics.aperture")
// naming the sections, or the section's numeric keys and the nearest one.
ParameterRef numeric_parameter(Chain& chain, const std::string& key, const std::string& where);
// The SI unit of a numeric parameter ("m", "s"; "1" for a number without one); the key as numeric_parameter takes it.
std::string numeric_parameter_si_unit(Chain& chain, const std::string& key, const std::string& where);
// InputError unless `value_si` is accepted by the parameter `key` of `chain` (its range; a whole number for an
// integer parameter). `subject` names the value in the message ("optics.aperture[17] = 0.001").
void check_parameter_value(Chain& chain, const std::string& key, double value_si, const std::string& where,
                           const std::string& subject);

struct PointsJob {
  // The sensor as every point starts from, its [[solve]] entries performed or dropped (no_solve) as asked; called
  // concurrently, once per thread.
  std::function<Chain(Solving)> make_chain;
  std::vector<std::string> parameters;  // numeric parameters given per point, e.g. "optics.aperture"
  std::vector<std::string> results;     // result names; empty: every result
  bool no_solve = false;                // forward only (a solved unknown may then be a parameter)
};

class PointsEvaluator {
 public:
  // Builds one chain to check the parameters and the result names. Throws InputError.
  explicit PointsEvaluator(PointsJob job);
  ~PointsEvaluator();
  PointsEvaluator(const PointsEvaluator&) = delete;
  PointsEvaluator& operator=(const PointsEvaluator&) = delete;

  const std::vector<std::string>& results() const { return results_; }
  const std::vector<std::string>& result_units() const { return units_; }  // SI units of the results
  // InputError for the first value that a parameter does not accept ("optics.aperture[17] = -0.1: ..."), among the
  // points [begin, end) (the arrays are the whole ones).
  void check(const double* const* values, std::size_t begin, std::size_t end) const;
  void check(const double* const* values, std::size_t count) const { check(values, 0, count); }
  // Evaluates `count` points: values[p][i] is parameter p at point i (SI). Writes result r at point i (SI) to
  // out[r * count + i] and ok[i] (0 where a solve failed: the solved unknown's column is NaN there). Returns the
  // number of points whose solve failed; `failure` gets the first one's message. Values are not checked (check()).
  std::size_t run(const double* const* values, std::size_t count, double* out, char* ok, std::string* failure = nullptr) {
    return run_range(values, count, 0, count, out, ok, failure);
  }
  // The same for the points [begin, end) only (the arrays are the whole ones): a caller can run a long sweep in
  // blocks and check for an interrupt between them (Python's Ctrl-C). `begin` is a multiple of lane_count.
  std::size_t run_range(const double* const* values, std::size_t count, std::size_t begin, std::size_t end, double* out,
                        char* ok, std::string* failure = nullptr);

 private:
  class Worker;
  PointsJob job_;
  std::vector<std::string> results_, units_;
  Chain checker_;  // the chain that check() validates against
  std::vector<std::unique_ptr<Worker>> workers_;  // one per thread slot, kept between runs
};

}  // namespace radchain
