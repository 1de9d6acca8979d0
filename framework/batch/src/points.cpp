// A sensor evaluated at arbitrary points (values in SI per point), on all cores: Python's Session.sweep().
#include "radchain/batch/points.hpp"

#include "radchain/batch/catalogue.hpp"
#include "radchain/batch/point_engine.hpp"
#include "radchain/batch/thread_pool.hpp"
#include "radchain/error.hpp"
#include "parameter_lookup.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>

namespace radchain {
namespace {
using batch_detail::is_numeric;

const ParamSpec& spec_of(Chain& chain, const std::string& key) {
  const auto dot = key.rfind('.');
  return *chain.slot(key.substr(0, dot)).params->entry(key.substr(dot + 1)).spec;
}

}  // namespace

ParameterRef numeric_parameter(Chain& chain, const std::string& key, const std::string& where) {
  const SourceLocation location{where, 0, 0};
  const auto dot = key.rfind('.');
  if (dot == std::string::npos || dot == 0 || dot + 1 == key.size())
    throw InputError(location, "", key, "expected <section>.<key>, e.g. optics.aperture");
  const batch_detail::ParameterLookup found = batch_detail::look_up_parameter(chain, key.substr(0, dot), key.substr(dot + 1));
  const Params::Entry* entry = found.entry;
  if (entry && !is_numeric(entry->spec->type))
    throw InputError(location, "", key,
                     fmt::format("not a number ({}): set it as TOML text, e.g. set(\"{}\", \"...\")",
                                 entry->spec->expected_text().substr(std::string("expected ").size()), key));
  if (!entry) throw InputError(location, "", key, found.problem);
  return chain.parameter(key);
}

std::string numeric_parameter_si_unit(Chain& chain, const std::string& key, const std::string& where) {
  numeric_parameter(chain, key, where);
  const ParamSpec& spec = spec_of(chain, key);
  return spec.type == ParamType::quantity ? spec.si_unit : "1";
}

void check_parameter_value(Chain& chain, const std::string& key, double value_si, const std::string& where,
                           const std::string& subject) {
  const ParamSpec& spec = spec_of(chain, key);
  const std::string unit = spec.type == ParamType::quantity && spec.si_unit != "1" ? " " + spec.si_unit : "";
  if (!spec.in_range(value_si) || std::isnan(value_si))
    throw InputError(SourceLocation{where, 0, 0}, "", subject,
                     fmt::format("{:g}{} is out of range: accepted {}", value_si, unit, spec.range_text()));
  if (spec.type == ParamType::integer && value_si != std::round(value_si))
    throw InputError(SourceLocation{where, 0, 0}, "", subject, fmt::format("{} is an integer, not {:g}", key, value_si));
}

// --- PointsEvaluator::Worker ---------------------------------------------------------------------------------

// One thread's point engine, fed points from the job's arrays.
class PointsEvaluator::Worker {
 public:
  explicit Worker(const PointsEvaluator& owner)
      : owner_(owner),
        engine_(owner.job_.make_chain(owner.job_.no_solve ? Solving::forward_only : Solving::as_written),
                owner.job_.parameters, owner.results_, PointEngine::Scale::si,
                [this](std::size_t k) { return point_name(first_ + k); }) {
    lanes_.resize(owner.job_.parameters.size());
  }

  // Points [begin, end) of a run of `count` points; the first failure's message into `failure` (if empty).
  std::size_t evaluate(const double* const* values, std::size_t count, std::size_t begin, std::size_t end, double* out,
                       char* ok, std::string& failure) {
    values_ = values;
    std::size_t failed = 0;
    const std::size_t n_parameters = lanes_.size();
    for (std::size_t i = begin; i < end; i += lane_count) {
      const std::size_t n = std::min<std::size_t>(lane_count, end - i);
      // A short group repeats its last point in the unused lanes.
      for (std::size_t p = 0; p < n_parameters; ++p)
        for (int lane = 0; lane < lane_count; ++lane)
          lanes_[p](lane) = values[p][i + std::min<std::size_t>(static_cast<std::size_t>(lane), n - 1)];
      first_ = i;
      engine_.evaluate_group(lanes_, n, PointEngine::Output{out + i, 1, count}, ok + i);
      for (std::size_t k = 0; k < n; ++k) {
        if (ok[i + k]) continue;
        ++failed;
        if (failure.empty()) failure = engine_.failure(k);
      }
    }
    return failed;
  }

 private:
  // "point 17 (optics.aperture = 0.2)"
  std::string point_name(std::size_t i) const {
    std::string at;
    for (std::size_t p = 0; p < lanes_.size(); ++p)
      at += fmt::format("{}{} = {:.17g}", p ? ", " : "", owner_.job_.parameters[p], values_[p][i]);
    return fmt::format("point {} ({})", i, at);
  }

  const PointsEvaluator& owner_;
  PointEngine engine_;
  std::vector<Lanes> lanes_;
  const double* const* values_ = nullptr;  // the current run's arrays
  std::size_t first_ = 0;                  // the current group's first point
};

// --- PointsEvaluator ----------------------------------------------------------------------------------------

PointsEvaluator::PointsEvaluator(PointsJob job)
    : job_(std::move(job)), checker_(job_.make_chain(job_.no_solve ? Solving::forward_only : Solving::as_written)) {
  for (std::size_t p = 0; p < job_.parameters.size(); ++p) {
    const std::string& key = job_.parameters[p];
    const std::string where = "sweep " + key;
    for (std::size_t q = 0; q < p; ++q)
      if (job_.parameters[q] == key) throw InputError(SourceLocation{where, 0, 0}, "", key, "the parameter is given twice");
    (void)numeric_parameter(checker_, key, where);
    for (const auto& s : checker_.solves)
      if (s.unknown == key)
        throw InputError(SourceLocation{where, 0, 0}, "", key,
                         "a [[solve]] determines " + key + " at every point: sweep another parameter (or solve=False)");
  }
  const Results& results = checker_.results();
  std::vector<std::string> all;
  for (std::size_t i = 0; i < results.size(); ++i) all.push_back(results.info(i).name);
  results_ = job_.results.empty() ? all : job_.results;
  for (const auto& name : results_) {
    const auto id = results.find(name);
    if (!id) {
      throw InputError(SourceLocation{"results", 0, 0}, "", name,
                       fmt::format("no such result{}; Session.run() lists them",
                                   did_you_mean(name, all)));
    }
    units_.push_back(results.info(*id).si_unit);
  }
}

PointsEvaluator::~PointsEvaluator() = default;

void PointsEvaluator::check(const double* const* values, std::size_t begin, std::size_t end) const {
  Chain& chain = const_cast<Chain&>(checker_);  // (only read: the parameters' specs)
  for (std::size_t p = 0; p < job_.parameters.size(); ++p) {
    const std::string& key = job_.parameters[p];
    const ParamSpec& spec = spec_of(chain, key);
    for (std::size_t i = begin; i < end; ++i) {
      const double v = values[p][i];
      if (spec.in_range(v) && !std::isnan(v) && (spec.type != ParamType::integer || v == std::round(v))) continue;
      check_parameter_value(chain, key, v, "sweep " + key, fmt::format("{}[{}] = {:.17g}", key, i, v));
    }
  }
}

std::size_t PointsEvaluator::run_range(const double* const* values, std::size_t count, std::size_t begin, std::size_t end,
                                       double* out, char* ok, std::string* failure) {
  end = std::min(end, count);
  if (begin >= end) return 0;
  if (begin % lane_count != 0) throw std::logic_error("PointsEvaluator::run_range: begin must be a multiple of the lane count");
  preload_plugins();  // workers then only read the host's tables
  if (workers_.size() < worker_slots()) workers_.resize(worker_slots());
  std::mutex mutex;
  std::size_t first_failed = std::numeric_limits<std::size_t>::max();
  std::string first_message;
  std::atomic<std::size_t> failed{0};
  // Chunks of 4096 points: a multiple of the lane count, so that no group straddles two chunks.
  parallel_chunks(end - begin, 4096, [&](std::size_t slot, std::size_t from, std::size_t to) {
    auto& worker = workers_[slot];
    if (!worker) worker = std::make_unique<Worker>(*this);
    std::string message;
    const std::size_t n = worker->evaluate(values, count, begin + from, begin + to, out, ok, message);
    if (n == 0) return;
    failed += n;
    std::lock_guard lock(mutex);
    if (begin + from < first_failed) first_failed = begin + from, first_message = message;
  });
  if (failure && failed > 0) *failure = first_message;
  return failed;
}

}  // namespace radchain
