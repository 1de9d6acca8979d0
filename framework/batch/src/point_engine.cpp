// One point engine for every job that evaluates a sensor at many points (radchain/batch/point_engine.hpp).
#include "radchain/batch/point_engine.hpp"

#include "radchain/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>

namespace radchain {

PointEngine::PointEngine(Chain chain, const std::vector<std::string>& parameters, const std::vector<std::string>& results,
                         Scale scale, PointName name)
    : chain_(std::move(chain)), name_(std::move(name)) {
  for (const auto& key : parameters) parameters_.push_back(chain_.parameter(key));
  for (const auto& s : chain_.solves) {
    const ParameterRef p = chain_.parameter(s.unknown);
    unknowns_.emplace_back(p, p.value());
  }
  std::vector<ResultId> asked;
  for (const auto& result : results) {
    const ResultId id = *chain_.results().find(result);
    bool solved = false;
    for (const auto& s : chain_.solves) solved = solved || s.unknown == result;
    columns_.push_back(Column{id, scale == Scale::display ? chain_.results().info(id).display_factor : 1.0, solved});
    asked.push_back(id);
  }
  chain_.focus(asked);
  lanes_ = chain_.solves.size() <= 1 && (chain_.solves.empty() || chain_.lanes_can_solve());
  for (const ParameterRef& p : parameters_) lanes_ = lanes_ && !p.spectral();
  // Only solved values read (limiting magnitudes): the evaluation at the roots needs no noise breakdown.
  if (std::all_of(columns_.begin(), columns_.end(), [](const Column& c) { return c.solved; }))
    lane_outcome_.final_detail = Detail::essential;
  scalar_values_.resize(parameters_.size());
}

// "<where>: the solve for target.magnitude failed: <why>".
std::string PointEngine::solve_failure(std::size_t k, const std::string& unknown, const std::string& why) const {
  return fmt::format("{}: the solve for {} failed: {}", name_(k), unknown, why);
}

bool PointEngine::evaluate(const double* values, Output out) { return evaluate_point(values, out, 0); }

bool PointEngine::evaluate_point(const double* values, Output out, std::size_t k) {
  for (std::size_t p = 0; p < parameters_.size(); ++p)
    if (parameters_[p].value() != values[p]) chain_.set(parameters_[p], values[p]);
  // Every point starts from the solved unknowns' values as built; only what moves is marked for re-evaluation.
  for (const auto& [parameter, initial] : unknowns_)
    if (parameter.value() != initial) chain_.set(parameter, initial);
  bool converged = true;
  failures_[k].clear();
  try {
    if (chain_.solves.empty()) {
      chain_.evaluate();
    } else {
      chain_.solve_all(outcomes_);
      for (const auto& o : outcomes_) {
        if (o.converged) continue;
        if (converged) failures_[k] = solve_failure(k, o.spec.unknown, o.message);
        converged = false;
      }
    }
  } catch (const InputError& error) {
    throw error.with_context(fmt::format("{}, {}", name_(k), error.context()));
  }
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    const Column& column = columns_[c];
    out.at(k, c) = (column.solved && !converged) ? std::numeric_limits<double>::quiet_NaN()
                                                 : chain_.results().value(column.id) * column.factor;
  }
  return converged;
}

void PointEngine::evaluate_group(const std::vector<Lanes>& values, std::size_t count, Output out, char* ok) {
  if (!lanes_) {
    for (std::size_t k = 0; k < count; ++k) {
      for (std::size_t p = 0; p < parameters_.size(); ++p) scalar_values_[p] = values[p](static_cast<int>(k));
      ok[k] = evaluate_point(scalar_values_.data(), out, k) ? 1 : 0;
    }
    return;
  }
  chain_.clear_lanes();
  for (std::size_t p = 0; p < parameters_.size(); ++p) chain_.set_lanes(parameters_[p], values[p]);
  std::fill(ok, ok + count, 1);
  try {
    if (chain_.solves.empty()) chain_.evaluate_lanes(Detail::full);
    else chain_.solve_lanes(lane_outcome_);
  } catch (const InputError&) {
    // Which of the lanes' points: one at a time through the scalar path, which names it.
    chain_.clear_lanes();
    for (std::size_t k = 0; k < count; ++k) {
      for (std::size_t p = 0; p < parameters_.size(); ++p) scalar_values_[p] = values[p](static_cast<int>(k));
      evaluate_point(scalar_values_.data(), out, k);
    }
    throw;  // not reached unless the lanes and the scalar path disagree
  }
  for (std::size_t k = 0; k < count; ++k) {
    failures_[k].clear();
    if (chain_.solves.empty() || lane_outcome_.converged[k]) continue;
    ok[k] = 0;
    failures_[k] = solve_failure(k, chain_.solves[0].unknown, lane_outcome_.message[k]);
  }
  for (std::size_t k = 0; k < count; ++k)
    for (std::size_t c = 0; c < columns_.size(); ++c) {
      const Column& column = columns_[c];
      out.at(k, c) = (column.solved && !ok[k]) ? std::numeric_limits<double>::quiet_NaN()
                                               : chain_.lane_result(column.id)(static_cast<int>(k)) * column.factor;
    }
}

}  // namespace radchain
