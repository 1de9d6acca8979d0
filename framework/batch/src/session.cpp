// A sensor kept loaded between calls (radchain/batch/session.hpp).
#include "radchain/batch/session.hpp"

#include "radchain/error.hpp"
#include "radchain/results.hpp"
#include "radchain/sensor_file.hpp"

#include <fmt/format.h>

namespace radchain {

Session::Session(std::string path, std::optional<std::string> text, std::vector<Override> overrides)
    : path_(std::move(path)), text_(std::move(text)), overrides_(std::move(overrides)) {
  chain_ = build(overrides_, si_);
  remember_unknowns();
}

std::vector<std::string> Session::solved() const {
  std::vector<std::string> unknowns;
  for (const auto& s : chain_.solves) unknowns.push_back(s.unknown);
  return unknowns;
}

namespace {

Chain load(const std::string& path, const std::optional<std::string>& text, const std::vector<Override>& overrides,
           const std::vector<std::pair<std::string, double>>& si, Solving solving) {
  Chain chain = text ? load_sensor_text(*text, path, overrides, solving) : load_sensor(path, overrides, solving);
  for (const auto& [key, value] : si) chain.set(chain.parameter(key), value);
  return chain;
}

}  // namespace

Chain Session::build(const std::vector<Override>& overrides, const std::vector<std::pair<std::string, double>>& si,
                     Solving solving) const {
  return load(path_, text_, overrides, si, solving);
}

Chain Session::fresh_chain(Solving solving) const { return build(overrides_, si_, solving); }

void Session::remember_unknowns() {
  unknowns_.clear();
  for (const auto& s : chain_.solves) {
    const ParameterRef p = chain_.parameter(s.unknown);
    unknowns_.emplace_back(p, p.value());
  }
}

void Session::reset_unknowns() {
  for (const auto& [p, v] : unknowns_)
    if (p.value() != v) chain_.set(p, v);
}

void Session::set_text(const std::string& key, const std::string& value) {
  std::vector<Override> overrides = overrides_;
  bool replaced = false;
  for (auto& o : overrides)
    if (o.key == key) o.value = value, replaced = true;
  if (!replaced) overrides.push_back(Override{key, value});
  std::vector<std::pair<std::string, double>> si = si_;
  std::erase_if(si, [&](const auto& x) { return x.first == key; });
  chain_ = build(overrides, si);  // (throws before anything changes)
  overrides_ = std::move(overrides), si_ = std::move(si);
  remember_unknowns();
  points_.reset();
}

void Session::set_si(const std::string& key, double value) {
  const ParameterRef p = numeric_parameter(chain_, key, "set " + key);
  check_parameter_value(chain_, key, value, "set " + key, fmt::format("{} = {}", key, value));
  chain_.set(p, value);
  std::erase_if(overrides_, [&](const Override& o) { return o.key == key; });
  bool replaced = false;
  for (auto& x : si_)
    if (x.first == key) x.second = value, replaced = true;
  if (!replaced) si_.emplace_back(key, value);
  for (std::size_t i = 0; i < chain_.solves.size() && i < unknowns_.size(); ++i)
    if (chain_.solves[i].unknown == key) unknowns_[i].second = value;
  points_.reset();
}

double Session::get(const std::string& key) { return numeric_parameter(chain_, key, "get " + key).value(); }

std::string Session::si_unit(const std::string& key) { return numeric_parameter_si_unit(chain_, key, "set " + key); }

Report Session::run(Solving solving) {
  reset_unknowns();
  if (solving == Solving::as_written) return chain_.run();
  // Forward only, the session's solves kept for the next run.
  std::vector<SolveSpec> solves = std::move(chain_.solves);
  chain_.solves.clear();
  Report report;
  try {
    report = chain_.run();
  } catch (...) {
    chain_.solves = std::move(solves);
    throw;
  }
  chain_.solves = std::move(solves);
  return report;
}

double Session::value(const std::string& name) const {
  if (const auto id = chain_.results().find(name)) return chain_.results().value(*id);
  throw InputError(SourceLocation{"result", 0, 0}, "", name, no_such_result(name));
}

std::string Session::no_such_result(const std::string& name) const {
  std::vector<std::string> names;
  for (std::size_t i = 0; i < chain_.results().size(); ++i) names.push_back(chain_.results().info(i).name);
  return fmt::format("no such result{}", did_you_mean(name, names));
}

CompareInput Session::compare_input(bool solve) {
  const Solving solving = solve ? Solving::as_written : Solving::forward_only;
  CompareInput input;
  input.path = path_;
  input.chain = fresh_chain(solving);
  input.report = run(solving);
  input.sensor_name = input.report.sensor_name;
  return input;
}

PointsEvaluator& Session::points(const std::vector<std::string>& parameters, const std::vector<std::string>& results,
                                 bool no_solve) {
  std::string job = no_solve ? "no-solve\n" : "solve\n";
  for (const auto& k : parameters) job += "p " + k + "\n";
  for (const auto& r : results) job += "r " + r + "\n";
  if (!points_ || points_job_ != job) {
    points_.reset();
    PointsJob points;
    points.make_chain = [path = path_, text = text_, overrides = overrides_, si = si_](Solving solving) {
      return load(path, text, overrides, si, solving);
    };
    points.parameters = parameters;
    points.results = results;
    points.no_solve = no_solve;
    points_ = std::make_unique<PointsEvaluator>(std::move(points));
    points_job_ = job;
  }
  return *points_;
}

}  // namespace radchain
