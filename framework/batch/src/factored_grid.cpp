// Limiting magnitudes over a Cartesian grid, factored by axis: the plan (chain evaluations along the axes, over the
// noise floor's sub-grid, and the checks) and the per-point additions. The reasoning is in factored_grid.hpp.
#include "radchain/batch/factored_grid.hpp"

#include "radchain/batch/sweep.hpp"
#include "radchain/error.hpp"
#include "radchain/physics/detection.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace radchain {
namespace {

// How far a quantity may move along an axis and still count as not depending on it: rounding of n² − S.
constexpr double floor_tolerance = 1e-12;
// How far lg S_end may stray from the product of its axis factors at a corner (log10 units: 2.3e-11 relative).
constexpr double separation_tolerance = 1e-11;
// The plan against the per-point solve, relative (the two paths must agree to 1e-10).
constexpr double check_tolerance = 1e-11;
// A root this close to a bracket end is solved on its own (the per-point solver decides there).
constexpr double end_margin = 1e-9;
// An axis of more steps than this whose parameter declares a power law gets its signal from the law (checked).
constexpr std::size_t power_law_line_steps = 64;
// Spread points checked besides the corners.
constexpr std::size_t spread_checks = 64;

std::string stage_name(const StageSlot& s) { return fmt::format("{} (plugin \"{}\")", s.section, s.plugin); }

bool is_criterion(const StageSlot& s) { return s.section.rfind("criteria.", 0) == 0; }

// The steps at which an axis is tested: first, middle, last (fewer for a short axis).
std::vector<std::size_t> test_steps(std::size_t steps) {
  std::vector<std::size_t> at{0, (steps - 1) / 2, steps - 1};
  at.erase(std::unique(at.begin(), at.end()), at.end());
  return at;
}

// A run of points along the last axis, the other axes fixed: rows of the axis values and the magnitude.
struct Run {
  double* rows;
  char* ok;
  std::size_t count, n_columns;
  const double* outer_values;  // the axes before the last
  const double* values;        // the last axis's, from the run's first step
  const double* inner;         // its B terms
  const double* floor;         // P from the run's first step, stepping floor_step
  std::size_t floor_step;
  double outer, low, high;
};

// N > 0: N axes known when compiled; N = 0: `n_axes` of them.
template <std::size_t N>
void fill_run(const Run& r, std::size_t n_axes = N) {
  const std::size_t axes = N > 0 ? N : n_axes, last = axes - 1;
  for (std::size_t i = 0; i < r.count; ++i) {
    double* row = r.rows + i * r.n_columns;
    for (std::size_t a = 0; a < last; ++a) row[a] = r.outer_values[a];
    row[last] = r.values[i];
    const double m = r.outer + r.inner[i] + r.floor[i * r.floor_step];
    row[axes] = m;
    r.ok[i] = m >= r.low && m <= r.high;  // (false for NaN)
  }
}

}  // namespace

std::optional<FactoredGrid> FactoredGrid::plan(const Sweep& sweep, SweepWorker& worker, std::string& why_not) {
  Chain& chain = worker.chain();
  const auto inversion = chain.magnitude_inversion();
  if (!inversion) {
    why_not = chain.solves.empty() ? "no [[solve]]"
              : chain.solver == SolverChoice::root
                  ? "--solver root"
                  : "the solve is not a target's magnitude inverted in closed form through the noise equation";
    return std::nullopt;
  }
  const std::string& unknown = chain.solves[0].unknown;
  for (const auto& name : sweep.results())
    if (name != unknown) {
      why_not = "a result other than the solved " + unknown + " is read (" + name + ")";
      return std::nullopt;
    }
  const std::vector<SweepAxis>& axes = sweep.axes();
  const std::size_t n_axes = axes.size();
  // Corners of the other axes at which each axis is tested: all of them up to 7 axes, else the two extreme ones.
  const std::size_t corner_bits = n_axes - 1;
  const std::size_t corners = corner_bits <= 6 ? std::size_t{1} << corner_bits : 2;

  std::vector<ParameterRef> refs;
  std::vector<bool> in_floor(n_axes, false);  // J
  for (std::size_t a = 0; a < n_axes; ++a) {
    refs.push_back(chain.parameter(axes[a].key));
    const std::size_t first = refs[a].stage();
    if (refs[a].spectral()) {
      why_not = axes[a].key + " is spectral";
      return std::nullopt;
    }
    if (is_criterion(chain.stages[first])) {
      in_floor[a] = true;  // a criterion's parameter moves T
      continue;
    }
    for (std::size_t s = first; s < inversion->criterion_stage; ++s)
      if (!is_criterion(chain.stages[s]) && !chain.stages[s].stage->power_law()) {
        why_not = stage_name(chain.stages[s]) + " does not declare power-law results (swept: " + axes[a].key + ")";
        return std::nullopt;
      }
  }

  // A long axis whose parameter declares a power law (ParamSpec::scales) is not evaluated step by step: lg S_end is
  // linear in lg x along it, with the slope from its ends, checked at its quarters (a one-axis sweep of 10⁶ apertures
  // then costs a logarithm per step, not a chain evaluation).
  std::vector<bool> power_line(n_axes, false);
  std::size_t line_cost = 0, test_cost = 0;
  for (std::size_t a = 0; a < n_axes; ++a) {
    const SweepAxis& axis = axes[a];
    power_line[a] = refs[a].scaling() == Scaling::power_law && axis.steps > power_law_line_steps &&
                    axis.value_si(0) > 0 && axis.value_si(axis.steps - 1) > 0 && axis.from != axis.to;
    line_cost += power_line[a] ? 4 : axis.steps;
    test_cost += corners * test_steps(axis.steps).size();
  }
  // Factoring pays when the chain runs for a small part of the grid (the sub-grid of J is counted below; a check is a
  // per-point solve, two or three evaluations).
  const std::size_t check_cost = 3 * (std::min<std::size_t>(2 * corners, 64) + spread_checks);
  if (4 * (line_cost + test_cost + check_cost) > sweep.points()) {
    why_not = fmt::format("the grid's {} points are too few for factoring to pay", sweep.points());
    return std::nullopt;
  }

  // One chain evaluation at the faint end, the axes at the given steps.
  struct At {
    double lg_signal, signal, variance, threshold;
  };
  std::size_t evaluations = 0;
  auto at = [&](const std::vector<std::size_t>& step) {
    for (std::size_t a = 0; a < n_axes; ++a) {
      const double v = axes[a].value_si(step[a]);
      if (refs[a].value() != v) chain.set(refs[a], v);
    }
    if (inversion->unknown.value() != inversion->faint) chain.set(inversion->unknown, inversion->faint);
    chain.evaluate(Detail::essential);
    ++evaluations;
    const Results& r = chain.results();
    const double signal = r.value(inversion->signal), noise = r.value(inversion->noise);
    return At{std::log10(signal), signal, noise * noise, r.value(inversion->threshold)};
  };
  auto usable = [](const At& p) { return p.signal > 0 && std::isfinite(p.lg_signal) && p.variance > 0 && p.threshold > 0; };

  FactoredGrid grid;
  grid.bright_ = inversion->bright;
  grid.faint_ = inversion->faint;
  grid.steps_.resize(n_axes);
  grid.axis_values_.resize(n_axes);
  for (std::size_t a = 0; a < n_axes; ++a) {
    grid.steps_[a] = axes[a].steps;
    grid.axis_values_[a].resize(axes[a].steps);
    for (std::size_t i = 0; i < axes[a].steps; ++i) grid.axis_values_[a][i] = axes[a].value(i);
    grid.axis_columns_.push_back(grid.axis_values_[a]);
    if (sweep.options().si_columns)
      for (std::size_t i = 0; i < axes[a].steps; ++i) grid.axis_columns_[a][i] = axes[a].value_si(i);
  }
  std::vector<std::vector<double>> line(n_axes);  // lg S_end along each axis through x₀
  std::vector<std::size_t> step(n_axes, 0);
  try {
    const At base = at(step);
    if (!usable(base)) {
      why_not = "the signal or the noise is not positive at the grid's first point";
      return std::nullopt;
    }
    for (std::size_t a = 0; a < n_axes; ++a) {
      const std::size_t last = axes[a].steps - 1;
      auto along = [&](std::size_t i) {
        step.assign(n_axes, 0);
        step[a] = i;
        const At p = at(step);
        if (!usable(p)) why_not = fmt::format("the signal or the noise is not positive at {} step {}", axes[a].key, i);
        return p.lg_signal;
      };
      line[a].resize(axes[a].steps);
      line[a][0] = base.lg_signal;
      if (!power_line[a]) {
        for (std::size_t i = 1; i <= last && why_not.empty(); ++i) line[a][i] = along(i);
      } else {
        // (Natural logarithms: glibc's log costs a fraction of its log10, and the slope takes the factor.)
        // ln(x_i/x_0) from the values in the axis's unit: the unit's factor cancels.
        const double* values = grid.axis_values_[a].data();
        const double ln_first = std::log(values[0]), end = along(last);
        const double slope = (end - base.lg_signal) / (std::log(values[last]) - ln_first);
        for (std::size_t i = 1; i < last; ++i) line[a][i] = base.lg_signal + slope * (std::log(values[i]) - ln_first);
        line[a][last] = end;
        for (std::size_t i : {last / 4, last / 2, 3 * last / 4})
          if (why_not.empty() && !(std::abs(along(i) - line[a][i]) <= separation_tolerance))
            why_not = fmt::format("the signal is not the power law of {} that it declares", axes[a].key);
      }
      if (!why_not.empty()) return std::nullopt;
    }
    // Which axes the noise floor and T depend on, and whether the signal separates, at every corner of the others.
    for (std::size_t a = 0; a < n_axes && why_not.empty(); ++a) {
      if (in_floor[a]) continue;
      const std::vector<std::size_t> tested = test_steps(axes[a].steps);
      for (std::size_t corner = 0; corner < corners && why_not.empty(); ++corner) {
        for (std::size_t b = 0, bit = 0; b < n_axes; ++b) {
          if (b == a) continue;
          const bool high = corners == 2 ? corner == 1 : ((corner >> bit) & 1) != 0;
          step[b] = high ? axes[b].steps - 1 : 0;
          ++bit;
        }
        At first{};
        for (std::size_t t = 0; t < tested.size(); ++t) {
          step[a] = tested[t];
          const At p = at(step);
          if (!usable(p)) {
            why_not = fmt::format("the signal or the noise is not positive at a corner of the grid ({} step {})",
                                  axes[a].key, tested[t]);
            break;
          }
          if (t == 0) {
            first = p;
            continue;
          }
          const double expected = line[a][tested[t]] - line[a][0];
          if (!(std::abs((p.lg_signal - first.lg_signal) - expected) <= separation_tolerance)) {
            why_not = fmt::format("the signal is not a product of powers of the axes ({} at a corner of the grid)", axes[a].key);
            break;
          }
          const double floor = p.variance - p.signal, first_floor = first.variance - first.signal;
          if (!(std::abs(floor - first_floor) <= floor_tolerance * std::abs(first_floor)) || p.threshold != first.threshold)
            in_floor[a] = true;
        }
      }
    }
    if (!why_not.empty()) return std::nullopt;

    // The noise floor's sub-grid (the other axes at their first step), first axis outermost.
    std::size_t floor_points = 1;
    grid.floor_strides_.assign(n_axes, 0);
    for (std::size_t a = n_axes; a-- > 0;)
      if (in_floor[a]) grid.floor_strides_[a] = floor_points, floor_points *= axes[a].steps;
    if (4 * (evaluations + floor_points) > sweep.points()) {
      why_not = fmt::format("the noise floor varies with axes of {} points: too many for factoring to pay", floor_points);
      return std::nullopt;
    }
    grid.floor_terms_.resize(floor_points);
    step.assign(n_axes, 0);
    for (std::size_t j = 0; j < floor_points; ++j) {
      for (std::size_t a = 0; a < n_axes; ++a)
        if (in_floor[a]) step[a] = (j / grid.floor_strides_[a]) % axes[a].steps;
      const At p = at(step);
      // S* from this point's own c = n² − S and T; NaN (no root) leaves the points that use it to the per-point path.
      const double required = physics::signal_at_snr(p.threshold, p.variance, p.signal);
      grid.floor_terms_[j] = inversion->faint + 2.5 * base.lg_signal - 2.5 * std::log10(required);
    }
    grid.axis_terms_.resize(n_axes);
    for (std::size_t a = 0; a < n_axes; ++a) {
      grid.axis_terms_[a].resize(axes[a].steps);
      for (std::size_t i = 0; i < axes[a].steps; ++i) grid.axis_terms_[a][i] = 2.5 * (line[a][i] - base.lg_signal);
    }
  } catch (const InputError& error) {
    why_not = std::string("the chain refuses a point of the grid: ") + error.what();
    return std::nullopt;
  }
  for (const auto& name : sweep.results())
    grid.column_factors_.push_back(sweep.options().si_columns ? 1.0 : chain.results().info(*chain.results().find(name)).display_factor);

  // The plan against the per-point solve: the grid's corners and points spread over it.
  std::vector<std::size_t> checked;
  const std::size_t total = sweep.points();
  for (std::size_t corner = 0; corner < std::min<std::size_t>(corners * 2, 64); ++corner) {
    std::size_t point = 0;
    for (std::size_t a = 0; a < n_axes; ++a)  // (64 corners at most: the first six axes' ends)
      point = point * axes[a].steps + (a < 6 && ((corner >> a) & 1) != 0 ? axes[a].steps - 1 : 0);
    checked.push_back(point);
  }
  // k/64 of the way through the grid, moved by a pseudo-random part of a 64th, so the checks do not line up on an axis.
  const std::size_t part = std::max<std::size_t>(1, total / spread_checks);
  for (std::size_t k = 0; k < spread_checks; ++k) checked.push_back(k * part + (k * 7919) % part);
  std::sort(checked.begin(), checked.end());
  checked.erase(std::unique(checked.begin(), checked.end()), checked.end());
  const std::size_t n_columns = sweep.columns();
  std::vector<double> row(n_columns), reference(n_columns);
  std::size_t compared = 0;
  for (std::size_t point : checked) {
    if (point >= total) continue;
    char ok = 0;
    grid.evaluate(point, 1, 1, row.data(), &ok);
    if (!ok) continue;  // solved on its own anyway
    bool converged = false;
    try {
      converged = worker.evaluate(point, reference.data());
    } catch (const InputError& error) {
      why_not = std::string("the chain refuses a point of the grid: ") + error.what();
      return std::nullopt;
    }
    const double factored = row[n_axes], solved = reference[n_axes];
    if (!converged || !(std::abs(factored - solved) <= check_tolerance * std::max(1.0, std::abs(solved)))) {
      why_not = fmt::format("at grid point {} the factored magnitude {:.12g} differs from the per-point solve's {}", point,
                            factored, converged ? fmt::format("{:.12g}", solved) : worker.failure());
      return std::nullopt;
    }
    ++compared;
  }
  std::string floor_axes;
  for (std::size_t a = 0; a < n_axes; ++a)
    if (in_floor[a]) floor_axes += (floor_axes.empty() ? "" : ", ") + axes[a].key;
  grid.description_ = fmt::format(
      "closed form factored over the grid: the noise floor varies with {}; {} chain evaluations, {} points checked "
      "against the per-point solve",
      floor_axes.empty() ? "no axis" : floor_axes, evaluations, compared);
  return grid;
}

void FactoredGrid::evaluate(std::size_t first, std::size_t count, std::size_t stride, double* out, char* ok) const {
  const std::size_t n_axes = steps_.size(), n_results = column_factors_.size(), n_columns = n_axes + n_results;
  const std::size_t last = n_axes - 1;
  std::vector<std::size_t> index(n_axes);
  std::vector<double> outer_values(n_axes);  // the axes before the last, in their units
  const double low = bright_ + end_margin * std::max(1.0, std::abs(bright_));
  const double high = faint_ - end_margin * std::max(1.0, std::abs(faint_));
  const std::size_t floor_step = floor_strides_[last];
  std::size_t point = first;
  for (std::size_t k = 0; k < count;) {
    for (std::size_t a = n_axes, p = point; a-- > 0;) index[a] = p % steps_[a], p /= steps_[a];
    // The run of points along the last axis that share the others' values (one point for a strided shard).
    const std::size_t i0 = index[last];
    const std::size_t run = stride == 1 ? std::min(count - k, steps_[last] - i0) : 1;
    double outer = 0;             // Σ B_a over the axes before the last
    std::size_t floor_outer = 0;  // their offset in floor_terms_
    for (std::size_t a = 0; a < last; ++a) {
      outer += axis_terms_[a][index[a]];
      floor_outer += index[a] * floor_strides_[a];
      outer_values[a] = axis_columns_[a][index[a]];
    }
    const double* inner = axis_terms_[last].data() + i0;
    const double* values = axis_columns_[last].data() + i0;
    const double* floor = floor_terms_.data() + floor_outer + i0 * floor_step;
    double* rows = out + k * n_columns;
    const Run r{rows, ok + k, run, n_columns, outer_values.data(), values, inner, floor, floor_step, outer, low, high};
    switch (n_axes) {  // one pass over the rows, unrolled for the usual number of axes
      case 1: fill_run<1>(r); break;
      case 2: fill_run<2>(r); break;
      case 3: fill_run<3>(r); break;
      case 4: fill_run<4>(r); break;
      default: fill_run<0>(r, n_axes);
    }
    for (std::size_t c = n_results; c-- > 0;)  // the columns' display units (a magnitude's factor is 1); column 0 last
      if (c > 0 || column_factors_[c] != 1.0)
        for (std::size_t i = 0; i < run; ++i) rows[i * n_columns + n_axes + c] = rows[i * n_columns + n_axes] * column_factors_[c];
    k += run;
    point += run * stride;
  }
}

}  // namespace radchain
