#pragma once
// A sensor kept loaded between calls: what Python's radchain.Session is, and what any front end that sets values and
// runs again needs. One definition of loading with overrides, of a value set as text (the chain is rebuilt, so the
// messages are the command line's) or in SI (checked against the parameter's range, then Chain::set), of the values
// the solved unknowns start from, of a forward-only run, and of the point evaluator its sweeps reuse.
#include "radchain/batch/compare.hpp"
#include "radchain/batch/points.hpp"
#include "radchain/chain.hpp"

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace radchain {

class Session {
 public:
  // A sensor file (`text` empty), or a file's text named `path` (relative data files are looked for beside it).
  // Throws InputError.
  Session(std::string path, std::optional<std::string> text, std::vector<Override> overrides);

  const std::string& path() const { return path_; }
  const std::string& sensor_name() const { return chain_.sensor_name; }
  const std::string& description() const { return chain_.description; }
  std::vector<std::string> solved() const;  // the [[solve]] unknowns
  const std::vector<Override>& overrides() const { return overrides_; }                    // set as text
  const std::vector<std::pair<std::string, double>>& si_values() const { return si_; }   // set in SI

  // A value as TOML text ("25 cm"), applied as `--set` is: the chain is rebuilt. Nothing changes when it is refused.
  void set_text(const std::string& key, const std::string& value);
  // A numeric parameter in SI, checked against its range and set through Chain::set (nothing rebuilt). A solved
  // unknown set this way is where its solves start.
  void set_si(const std::string& key, double value);
  // The current value (SI) and the SI unit ("1" for a plain number) of a numeric parameter.
  double get(const std::string& key);
  std::string si_unit(const std::string& key);

  // Every result, the [[solve]] entries (unless forward only) and the [expected] checks, from the values as set;
  // the solved unknowns start from their set values: `radchain run [--no-solve] --set ...`.
  Report run(Solving solving = Solving::as_written);
  // A result of the last run (SI); InputError naming the nearest result when there is no such result.
  double value(const std::string& name) const;
  bool has_result(const std::string& name) const { return chain_.results().find(name).has_value(); }
  std::string no_such_result(const std::string& name) const;  // "no such result (did you mean \"…\"?)"

  // A fresh chain as the session builds it, and compare's input (radchain/batch/compare.hpp) from the session.
  Chain fresh_chain(Solving solving = Solving::as_written) const;
  CompareInput compare_input(bool solve);
  // The evaluator of points (radchain/batch/points.hpp) over `parameters` for `results`, built on the session's
  // values as set now; kept while the same job is asked again and nothing is set.
  PointsEvaluator& points(const std::vector<std::string>& parameters, const std::vector<std::string>& results,
                          bool no_solve);

 private:
  Chain build(const std::vector<Override>& overrides, const std::vector<std::pair<std::string, double>>& si,
              Solving solving = Solving::as_written) const;
  void remember_unknowns();
  void reset_unknowns();

  std::string path_;
  std::optional<std::string> text_;
  std::vector<Override> overrides_;
  std::vector<std::pair<std::string, double>> si_;
  Chain chain_;
  std::vector<std::pair<ParameterRef, double>> unknowns_;  // each solve's unknown and the value it starts from
  std::unique_ptr<PointsEvaluator> points_;
  std::string points_job_;
};

}  // namespace radchain
