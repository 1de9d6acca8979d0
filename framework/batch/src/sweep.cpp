// `radchain sweep`: a grid of parameter values, the chain's solves re-run at each point, on all cores.
#include "radchain/batch/sweep.hpp"
#include "radchain/strings.hpp"

#include "radchain/batch/catalogue.hpp"
#include "radchain/batch/factored_grid.hpp"
#include "radchain/batch/run_batch.hpp"
#include "radchain/batch/shard.hpp"
#include "radchain/batch/table.hpp"
#include "radchain/batch/thread_pool.hpp"
#include "radchain/error.hpp"
#include "radchain/units.hpp"
#include "parameter_lookup.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <limits>
#include <mutex>
#include <optional>

namespace radchain {
namespace {
using strings::split;
using strings::trimmed;
using strings::unquoted;


using batch_detail::is_numeric;

std::string column_name(const std::string& name, const std::string& unit) {
  if (unit.empty() || unit == "1") return name;
  std::string suffix = unit;
  std::replace(suffix.begin(), suffix.end(), ' ', '_');
  return name + "_" + suffix;
}

}  // namespace

double SweepAxis::value(std::size_t i) const {
  if (steps <= 1 || i == 0) return from;
  if (i + 1 >= steps) return to;
  // (to - from) i first: "15 cm:30 cm:16" gives 20 exactly, as --set optics.aperture="20 cm" does.
  return from + (to - from) * static_cast<double>(i) / static_cast<double>(steps - 1);
}

double SweepAxis::value_si(std::size_t i) const {
  if (i == 0) return from_si;
  if (i + 1 >= steps) return to_si_value;
  return units::to_si(value(i), to_si);
}

bool is_sweep_range(const std::string& value) { return value.find(':') != std::string::npos; }

SweepAxis parse_sweep_axis(Chain& chain, const std::string& key, const std::string& range) {
  const SourceLocation where{"--set " + key, 0, 0};
  auto fail = [&](const std::string& problem) { return InputError(where, "", range, problem); };
  const auto dot = key.rfind('.');
  if (dot == std::string::npos || dot == 0 || dot + 1 == key.size())
    throw fail("expected <section>.<key>=from:to:steps, e.g. optics.aperture=\"15 cm:30 cm:16\"");
  const batch_detail::ParameterLookup found = batch_detail::look_up_parameter(chain, key.substr(0, dot), key.substr(dot + 1));
  const Params::Entry* entry = found.entry;
  if (entry && !is_numeric(entry->spec->type))
    throw fail(fmt::format("{} is not a number ({}): only numeric parameters can be swept", key,
                           entry->spec->expected_text().substr(std::string("expected ").size())));
  if (!entry) throw fail(found.problem);
  for (const auto& s : chain.solves)
    if (s.unknown == key)
      throw fail("a [[solve]] determines " + key + " at every point: sweep another parameter (or remove the solve)");
  const ParamSpec& spec = *entry->spec;
  std::string example = fmt::format("{}=\"{}:{}:16\"", key, unquoted(spec.example), unquoted(spec.example));
  try {
    const units::ParsedQuantity q = units::split_quantity(unquoted(spec.example));
    const std::string u = q.unit.empty() ? "" : " " + q.unit;
    example = fmt::format("{}=\"{:g}{}:{:g}{}:16\"", key, q.number, u, 2 * q.number, u);
  } catch (const std::invalid_argument&) {
  }

  const std::vector<std::string> parts = split(range, ':');
  if (parts.size() != 3) throw fail("expected from:to:steps, e.g. " + example);
  SweepAxis axis;
  axis.key = key;
  axis.range = range;
  const std::string steps_text = trimmed(parts[2]);
  char* end = nullptr;
  errno = 0;
  const long long steps = std::strtoll(steps_text.c_str(), &end, 10);
  if (steps_text.empty() || *end != '\0' || steps < 1)
    throw fail(fmt::format("steps \"{}\" must be a whole number >= 1, e.g. {}", steps_text, example));
  // An overflowing count (strtoll clamps it) or more steps than a whole grid may have: refused before any work.
  if (errno == ERANGE || static_cast<double>(steps) > SweepOptions::max_points)
    throw fail(fmt::format("steps \"{}\" is more than {:g}: use fewer steps", steps_text, SweepOptions::max_points));
  axis.steps = static_cast<std::size_t>(steps);

  const bool dimensionless = spec.type != ParamType::quantity || units::dimension_of(spec.si_unit) == "1";
  const std::string expected = dimensionless ? std::string("a plain number")
                                             : fmt::format("{}, e.g. {}", units::dimension_name(spec.si_unit), example);
  double ends[2] = {0, 0};
  std::string ends_unit[2];
  units::ParsedQuantity written[2];
  for (int i = 0; i < 2; ++i) {
    const std::string text = trimmed(parts[static_cast<std::size_t>(i)]);
    units::ParsedQuantity q;
    try {
      q = units::split_quantity(text);
    } catch (const std::invalid_argument&) {
      throw fail(fmt::format("\"{}\" does not start with a number: expected {}", text, expected));
    }
    if (q.unit.empty() && !dimensionless)
      throw fail(fmt::format("\"{}\" has no unit: expected {}", text, expected));
    ends[i] = q.number;
    ends_unit[i] = q.unit;
    written[static_cast<std::size_t>(i)] = q;
  }
  axis.unit = ends_unit[0].empty() ? ends_unit[1] : ends_unit[0];
  try {
    const std::string si = spec.type == ParamType::quantity ? spec.si_unit : std::string("1");
    axis.si_unit = si;
    axis.to_si = units::conversion(axis.unit.empty() ? "1" : axis.unit, si).factor;
    // `to` in the unit of `from`, so that the steps are even in the unit written first.
    const double to_factor = units::conversion(ends_unit[1].empty() ? "1" : ends_unit[1], si).factor;
    axis.from = ends[0];
    axis.to = ends[1] * to_factor / axis.to_si;
    // The ends in SI as a file would read them (units::to_si of the text): a one-point sweep is the file's value.
    axis.from_si = units::to_si(written[0], axis.to_si);
    axis.to_si_value = units::to_si(written[1], to_factor);
  } catch (const std::invalid_argument&) {
    throw fail(fmt::format("unknown unit: expected {}", expected));
  } catch (const std::domain_error&) {
    // Steps even in e-/DN would be uneven in the key's DN/e-.
    if (units::reciprocal_conversion(axis.unit, axis.si_unit))
      throw fail("a sweep of a system gain is stated in DN/e- (its steps are even in the unit written; e-/DN would make "
                 "them uneven in the gain K)");
    throw fail("wrong unit: expected " + expected);
  }
  // The values are a linear ramp, so its ends decide the range; integers are checked on the first 1024 steps and the
  // last (a ramp whose first steps land on whole numbers has a whole step). Never a loop over 10^10 steps.
  for (std::size_t i = 0; i < axis.steps; i = (i + 1 < 1024 || i + 1 == axis.steps) ? i + 1 : axis.steps - 1) {
    const double v = axis.value_si(i);
    if (!spec.in_range(v))
      throw fail(fmt::format("{:g}{} is out of range: accepted {}", axis.value(i), axis.unit.empty() ? "" : " " + axis.unit,
                             spec.range_text()));
    if (spec.type == ParamType::integer && v != std::round(v))
      throw fail(fmt::format("{} is an integer, but the range gives {:g}: choose steps that land on whole numbers", key, v));
  }
  return axis;
}

// --- Sweep -------------------------------------------------------------------------------------------------

namespace {

// "optics.aperture = 20 cm, target.magnitude = 15" (axis values as written in the row).
std::string point_text(const std::vector<SweepAxis>& axes, const double* row) {
  std::string at;
  for (std::size_t a = 0; a < axes.size(); ++a)
    at += fmt::format("{}{} = {:g}{}", a ? ", " : "", axes[a].key, row[a], axes[a].unit.empty() ? "" : " " + axes[a].unit);
  return at;
}

std::vector<std::string> axis_keys(const std::vector<SweepAxis>& axes) {
  std::vector<std::string> keys;
  for (const auto& a : axes) keys.push_back(a.key);
  return keys;
}

// The sensor as every point starts from: fixed overrides applied, solves dropped with --no-solve.
Chain load_swept_sensor(const SweepOptions& options) {
  Chain chain = load_sensor(options.sensor_file, options.overrides,
                            options.no_solve ? Solving::forward_only : Solving::as_written);
  chain.solver = options.solver;
  return chain;
}

}  // namespace


Sweep::Sweep(SweepOptions options) : options_(std::move(options)) {
  Chain chain = load_swept_sensor(options_);
  for (const auto& [key, range] : options_.axes) {
    for (const auto& a : axes_)
      if (a.key == key)
        throw InputError(SourceLocation{"--set " + key, 0, 0}, "", range, "the parameter is swept twice (one range per key)");
    axes_.push_back(parse_sweep_axis(chain, key, range));
  }
  const Results& results = chain.results();
  std::vector<std::string> all;
  for (std::size_t i = 0; i < results.size(); ++i) all.push_back(results.info(i).name);
  results_ = options_.results.empty() ? all : options_.results;
  for (std::size_t i = 0; i < results_.size(); ++i) {
    const std::string& name = results_[i];
    // Two columns of one name make a table that numpy.load refuses ("name already used").
    if (std::find(results_.begin(), results_.begin() + static_cast<std::ptrdiff_t>(i), name) != results_.begin() + static_cast<std::ptrdiff_t>(i))
      throw InputError(SourceLocation{"--results", 0, 0}, "", name, "is listed twice (one column per result)");
    const auto id = results.find(name);
    if (!id) {
      throw InputError(SourceLocation{"--results", 0, 0}, "", name,
                       fmt::format("no such result{}; `radchain run {}` lists them",
                                   did_you_mean(name, all), options_.sensor_file));
    }
    units_.push_back(results.info(*id).display_unit);
    si_units_.push_back(results.info(*id).si_unit);
  }
  // A swept parameter is also a result (optics.aperture): its column is the axis's, once; two columns of one name
  // make a table that numpy.load refuses.
  for (std::size_t i = results_.size(); i-- > 0;)
    for (const auto& a : axes_)
      if (options_.si_columns ? results_[i] == a.key : column_name(results_[i], units_[i]) == column_name(a.key, a.unit)) {
        results_.erase(results_.begin() + static_cast<std::ptrdiff_t>(i));
        units_.erase(units_.begin() + static_cast<std::ptrdiff_t>(i));
        si_units_.erase(si_units_.begin() + static_cast<std::ptrdiff_t>(i));
        break;
      }
  constexpr double max_points = SweepOptions::max_points;
  double points = 1;
  for (const auto& a : axes_) points *= static_cast<double>(a.steps);
  if (points > max_points)
    throw InputError(SourceLocation{"sweep", 0, 0}, "", "",
                     fmt::format("the grid has {:g} points: more than {:g} (split it, or use fewer steps)", points, max_points));
  if (points > SweepOptions::large_points && !options_.allow_large)
    throw InputError(SourceLocation{"sweep", 0, 0}, "", "",
                     fmt::format("the grid has {:g} points: more than {:g}, hours of work and gigabytes of output; "
                                 "give --allow-large to run it",
                                 points, SweepOptions::large_points));
  points_ = static_cast<std::size_t>(points);
}

TableLayout Sweep::layout() const {
  TableLayout layout;
  layout.kind = "sweep";
  for (const auto& a : axes_) layout.columns.push_back(options_.si_columns ? a.key : column_name(a.key, a.unit));
  for (std::size_t i = 0; i < results_.size(); ++i)
    layout.columns.push_back(options_.si_columns ? results_[i] : column_name(results_[i], units_[i]));
  layout.numeric.assign(layout.columns.size(), true);
  return layout;
}

std::string Sweep::job() const {
  std::string job = "sweep\nfile " + options_.sensor_file + "\n";
  for (const auto& o : options_.overrides) job += "set " + o.key + "=" + o.value + "\n";
  for (const auto& [key, range] : options_.axes) job += "axis " + key + "=" + range + "\n";
  for (const auto& r : results_) job += "result " + r + "\n";
  if (options_.no_solve) job += "no-solve\n";
  if (options_.solver == SolverChoice::root) job += "solver root\n";
  if (options_.si_columns) job += "si columns\n";
  return job;
}

std::vector<std::string> Sweep::column_units() const {
  std::vector<std::string> units;
  for (const auto& a : axes_) units.push_back(options_.si_columns ? a.si_unit : a.unit.empty() ? "1" : a.unit);
  for (std::size_t i = 0; i < results_.size(); ++i) units.push_back(options_.si_columns ? si_units_[i] : units_[i]);
  return units;
}

std::vector<std::size_t> Sweep::indices(std::size_t point) const {
  std::vector<std::size_t> index(axes_.size());
  for (std::size_t a = axes_.size(); a-- > 0;) {
    index[a] = point % axes_[a].steps;
    point /= axes_[a].steps;
  }
  return index;
}

int Sweep::run(TableWriter& writer, std::string* failure,
               const std::function<void(std::size_t, const double*)>& observer) {
  const PointRange range = shard_points(options_.shard, points_);
  const std::size_t n_columns = columns();
  std::vector<std::unique_ptr<SweepWorker>> workers(worker_slots());
  std::mutex failure_mutex;
  std::size_t first_failed = std::numeric_limits<std::size_t>::max();
  std::string first_message;
  auto note_failure = [&](std::size_t point, const std::string& message) {
    std::lock_guard lock(failure_mutex);
    if (point < first_failed) first_failed = point, first_message = message;
  };

  // A grid of limiting magnitudes factored by axis where the chain allows it (factored_grid.hpp), planned on this
  // thread with the worker that then serves slot 0; else every point solved on its own.
  workers[0] = std::make_unique<SweepWorker>(*this);
  std::string why_not;
  const std::optional<FactoredGrid> factored =
      options_.no_solve || axes_.empty() ? std::nullopt : FactoredGrid::plan(*this, *workers[0], why_not);
  method_ = factored                 ? factored->description()
            : options_.no_solve      ? std::string("forward evaluation at every point (--no-solve)")
                                     : "per point: " + why_not;
  std::vector<std::string> left_out;
  const Chain& chain = workers[0]->chain();
  for (std::size_t k = 0; k < chain.stages.size(); ++k)
    if (chain.skips(k)) left_out.push_back(chain.stages[k].section);
  if (!left_out.empty()) method_ += "; not evaluated (no asked result or solve needs them): " + join(left_out);

  // Blocks bound the memory (values and formatted cells) of long sweeps.
  constexpr std::size_t block = 16384;
  std::vector<double> values(std::min(block, range.count) * n_columns);
  std::vector<char> ok(std::min(block, range.count));
  // Formatted on the worker threads (whole CSV lines where the writer takes them), unless the writer stores the
  // numbers as they are (.npy).
  const bool values_only = writer.takes_values(), lines_only = !values_only && writer.takes_lines();
  std::vector<std::vector<std::string>> cells(values_only || lines_only ? 0 : std::min(block, range.count));
  std::vector<std::string> lines(lines_only ? std::min(block, range.count) : 0);
  run_batch(
      range.count, block, 64,
      [&](std::size_t slot, std::size_t begin, std::size_t end) {
        auto& worker = workers[slot];
        if (!worker) worker = std::make_unique<SweepWorker>(*this);
        if (factored) {
          factored->evaluate(range[begin], end - begin, range.stride, &values[(begin % block) * n_columns], &ok[begin % block]);
          for (std::size_t i = begin; i < end; ++i) {
            const std::size_t at = i % block;
            if (ok[at]) continue;  // a root outside the bracket or at its end: the per-point solver decides
            ok[at] = worker->evaluate(range[i], &values[at * n_columns]) ? 1 : 0;
            if (!ok[at]) note_failure(range[i], worker->failure());
          }
        } else {
          std::size_t group[lane_count];
          for (std::size_t i = begin; i < end; i += lane_count) {
            const std::size_t count = std::min<std::size_t>(lane_count, end - i);
            const std::size_t at = i % block;  // position within the block's buffers
            for (std::size_t k = 0; k < count; ++k) group[k] = range[i + k];
            worker->evaluate_group(group, count, &values[at * n_columns], &ok[at]);
            for (std::size_t k = 0; k < count; ++k)
              if (!ok[at + k]) note_failure(group[k], worker->failure_of(k));
          }
        }
        for (std::size_t i = begin; i < end && !values_only; ++i) {
          const std::size_t at = i % block;
          if (lines_only) {
            TableWriter::csv_line(&values[at * n_columns], n_columns, lines[at]);
            continue;
          }
          std::vector<std::string>& row = cells[at];
          row.clear();
          row.reserve(n_columns);
          for (std::size_t c = 0; c < n_columns; ++c) row.push_back(writer.number(values[at * n_columns + c]));
        }
        if (options_.progress) options_.progress->fetch_add(end - begin, std::memory_order_relaxed);
      },
      [&](std::size_t i) {
        const std::size_t at = i % block;
        if (observer) observer(range[i], &values[at * n_columns]);
        if (values_only) writer.row_values(range[i], &values[at * n_columns]);
        else if (lines_only) writer.row_line(range[i], lines[at]);
        else writer.row(range[i], cells[at]);
      });
  if (first_failed == std::numeric_limits<std::size_t>::max()) return 0;
  if (failure) *failure = first_message;
  return 1;
}

// --- SweepWorker -------------------------------------------------------------------------------------------

SweepWorker::SweepWorker(const Sweep& sweep)
    : sweep_(sweep),
      engine_(load_swept_sensor(sweep.options()), axis_keys(sweep.axes()), sweep.results(),
              sweep.options().si_columns ? PointEngine::Scale::si : PointEngine::Scale::display,
              [this](std::size_t k) { return "at " + point_text(sweep_.axes(), rows_ + k * sweep_.columns()); }) {
  index_.resize(sweep.axes().size());
  axis_values_.resize(sweep.axes().size());
  values_.resize(sweep.axes().size());
  scalar_.resize(sweep.axes().size());
}

const SweepWorker::AxisValue& SweepWorker::axis_value(std::size_t axis) {
  AxisValue& v = axis_values_[axis];
  if (v.step != index_[axis]) {
    const SweepAxis& a = sweep_.axes()[axis];
    const double value_si = a.value_si(index_[axis]);
    v = AxisValue{index_[axis], sweep_.options().si_columns ? value_si : a.value(index_[axis]), value_si};
  }
  return v;
}

void SweepWorker::locate(std::size_t point) {
  const auto& axes = sweep_.axes();
  for (std::size_t a = axes.size(); a-- > 0;) {
    index_[a] = point % axes[a].steps;
    point /= axes[a].steps;
  }
}

void SweepWorker::place(double* row, int lane) {
  for (std::size_t a = 0; a < index_.size(); ++a) {
    const AxisValue& v = axis_value(a);
    values_[a](lane) = v.value_si;
    if (row) row[a] = v.value;
  }
}

void SweepWorker::evaluate_group(const std::size_t* points, std::size_t count, double* out, char* ok) {
  const auto& axes = sweep_.axes();
  const std::size_t n_columns = sweep_.columns();
  // Each axis's value per lane; a short group repeats its last point in the unused lanes.
  for (int lane = 0; lane < lane_count; ++lane) {
    const std::size_t k = std::min<std::size_t>(static_cast<std::size_t>(lane), count - 1);
    if (lane > 0 && k == static_cast<std::size_t>(lane) && points[k] == points[k - 1] + 1) {
      // The next point (the usual case): the innermost index steps, with a carry; no integer divisions.
      for (std::size_t a = axes.size(); a-- > 0 && ++index_[a] == axes[a].steps;) index_[a] = 0;
    } else if (lane == 0 || k == static_cast<std::size_t>(lane)) {
      locate(points[k]);
    }  // (else a short group's unused lane: index_ still holds its last point)
    place(static_cast<std::size_t>(lane) < count ? out + k * n_columns : nullptr, lane);
  }
  rows_ = out;
  engine_.evaluate_group(values_, count, PointEngine::Output{out + axes.size(), n_columns, 1}, ok);
}

bool SweepWorker::evaluate(std::size_t point, double* out) {
  locate(point);
  place(out, 0);
  for (std::size_t a = 0; a < values_.size(); ++a) scalar_[a] = values_[a](0);
  rows_ = out;
  return engine_.evaluate(scalar_.data(), PointEngine::Output{out + sweep_.axes().size(), sweep_.columns(), 1});
}

}  // namespace radchain
