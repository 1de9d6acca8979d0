// Limiting magnitudes over a Cartesian grid, factored by axis: the plan (chain evaluations along the axes, over the
// noise floor's sub-grid, and the checks) and the per-point additions. The reasoning is in factored_grid.hpp.
#include "radchain/batch/factored_grid.hpp"

#include "radchain/batch/sweep.hpp"
#include "radchain/error.hpp"
#include "radchain/physics/detection.hpp"
#include "radchain/vocabulary.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

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
// 2.5 / ln 10: a magnitude per natural logarithm of a flux ratio.
constexpr double magnitude_per_ln = 2.5 / std::numbers::ln10;
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

// The other axes at one corner of the grid, axis `a` left as it is: every corner up to 7 axes (`corners` = 2^(n−1)),
// else the two extreme ones.
void to_corner(std::vector<std::size_t>& step, std::size_t a, std::size_t corner, std::size_t corners,
               const std::vector<SweepAxis>& axes) {
  for (std::size_t b = 0, bit = 0; b < axes.size(); ++b) {
    if (b == a) continue;
    const bool high = corners == 2 ? corner == 1 : ((corner >> bit) & 1) != 0;
    step[b] = high ? axes[b].steps - 1 : 0;
    ++bit;
  }
}

// The points a plan is checked at against the per-point path: the grid's corners (the first six axes' ends), and
// k/64 of the way through the grid moved by a pseudo-random part of a 64th, so the checks do not line up on an axis.
// A spectral axis's value is snapped to one of 8 of its steps: each new value re-runs the spectral phase (~0.3 ms
// for a telescope's 5,000-node tables), and the line along that axis has already been evaluated at every step.
std::vector<std::size_t> checked_points(const std::vector<SweepAxis>& axes, const std::vector<ParameterRef>& refs,
                                        std::size_t corners, std::size_t total) {
  const std::size_t n_axes = axes.size();
  std::vector<std::size_t> checked;
  for (std::size_t corner = 0; corner < std::min<std::size_t>(corners * 2, 64); ++corner) {
    std::size_t point = 0;
    for (std::size_t a = 0; a < n_axes; ++a)
      point = point * axes[a].steps + (a < 6 && ((corner >> a) & 1) != 0 ? axes[a].steps - 1 : 0);
    checked.push_back(point);
  }
  const std::size_t part = std::max<std::size_t>(1, total / spread_checks);
  for (std::size_t k = 0; k < spread_checks; ++k) {
    std::size_t point = k * part + (k * 7919) % part;
    if (point >= total) continue;
    std::vector<std::size_t> index(n_axes);
    for (std::size_t a = n_axes, p = point; a-- > 0;) index[a] = p % axes[a].steps, p /= axes[a].steps;
    point = 0;
    for (std::size_t a = 0; a < n_axes; ++a) {
      if (refs[a].spectral()) index[a] = ((k % 8) * (axes[a].steps - 1)) / 7;
      point = point * axes[a].steps + index[a];
    }
    checked.push_back(point);
  }
  std::sort(checked.begin(), checked.end());
  checked.erase(std::unique(checked.begin(), checked.end()), checked.end());
  return checked;
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

// The same run when the floor is a sum of per-axis products: term k's product over the axes before the last,
// and its factors along the last axis from the run's first step.
struct TermRun {
  const double* outer_products;      // per term
  const double* const* last_factors; // per term, from the run's first step
  std::size_t terms;
  double t2, t4, base;               // T², T⁴, m_end + 2.5 lg S_end(x₀)
};

// N > 0: N axes known when compiled; N = 0: `n_axes` of them.
template <std::size_t N>
void fill_run_terms(const Run& r, const TermRun& f, std::size_t n_axes = N) {
  const std::size_t axes = N > 0 ? N : n_axes, last = axes - 1;
  for (std::size_t i = 0; i < r.count; ++i) {
    double* row = r.rows + i * r.n_columns;
    for (std::size_t a = 0; a < last; ++a) row[a] = r.outer_values[a];
    row[last] = r.values[i];
    double floor = 0;
    for (std::size_t k = 0; k < f.terms; ++k) floor += f.outer_products[k] * f.last_factors[k][i];
    // S* = (T² + √(T⁴ + 4T²c))/2 (Pan 2010 eq. (11), physics::signal_at_snr); NaN where no root (c < −T²/4).
    // (2.5 lg x as 2.5/ln 10 · ln x: glibc's log10 is its log and a multiplication, one call fewer.)
    const double required = 0.5 * (f.t2 + std::sqrt(f.t4 + 4.0 * f.t2 * floor));
    const double m = f.base + r.outer + r.inner[i] - magnitude_per_ln * std::log(required);
    row[axes] = m;
    r.ok[i] = m >= r.low && m <= r.high;  // (false for NaN)
  }
}

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
  if (!inversion && chain.solves.empty()) return plan_forward(sweep, worker, why_not);
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

  // The floor's terms, source by source, where the detector publishes them (vocabulary::floor_variances).
  std::vector<ResultId> term_ids;
  for (const auto& term : vocabulary::floor_variances)
    if (const auto id = chain.results().find(term.name)) term_ids.push_back(*id);
  const std::size_t n_terms = term_ids.size();

  std::vector<ParameterRef> refs;
  std::vector<bool> in_floor(n_axes, false);  // J
  // Why the power-law reasoning (which finds J from three steps) does not hold; the floor's terms may still factor.
  std::string not_power_law;
  bool criterion_axis = false;
  for (std::size_t a = 0; a < n_axes; ++a) {
    refs.push_back(chain.parameter(axes[a].key));
    const std::size_t first = refs[a].stage();
    if (refs[a].spectral()) {
      if (not_power_law.empty()) not_power_law = axes[a].key + " is spectral";
      continue;
    }
    if (is_criterion(chain.stages[first])) {
      in_floor[a] = true;  // a criterion's parameter moves T
      criterion_axis = true;
      continue;
    }
    for (std::size_t s = first; s < inversion->criterion_stage && not_power_law.empty(); ++s)
      if (!is_criterion(chain.stages[s]) && !chain.stages[s].stage->power_law())
        not_power_law = stage_name(chain.stages[s]) + " does not declare power-law results (swept: " + axes[a].key + ")";
  }
  // The terms carry a grid whose T is one number; a criterion's axis needs J.
  bool by_terms = n_terms > 0 && !criterion_axis;
  if (!not_power_law.empty() && !by_terms) {
    why_not = not_power_law;
    return std::nullopt;
  }

  // A long axis whose parameter declares a power law (ParamSpec::scales) is not evaluated step by step: lg S_end is
  // linear in lg x along it, with the slope from its ends, checked at its quarters (a one-axis sweep of 10⁶ apertures
  // then costs a logarithm per step, not a chain evaluation). So is each floor term, a product of powers.
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

  // One chain evaluation at the faint end, the axes at the given steps (the floor's terms need the full detail).
  struct At {
    double lg_signal, signal, variance, threshold;
    std::array<double, vocabulary::floor_variances.size()> terms;
  };
  std::size_t evaluations = 0;
  auto at = [&](const std::vector<std::size_t>& step, bool with_terms) {
    for (std::size_t a = 0; a < n_axes; ++a) {
      const double v = axes[a].value_si(step[a]);
      if (refs[a].value() != v) chain.set(refs[a], v);
    }
    if (inversion->unknown.value() != inversion->faint) chain.set(inversion->unknown, inversion->faint);
    chain.evaluate(with_terms ? Detail::full : Detail::essential);
    ++evaluations;
    const Results& r = chain.results();
    const double signal = r.value(inversion->signal), noise = r.value(inversion->noise);
    At p{std::log10(signal), signal, noise * noise, r.value(inversion->threshold), {}};
    if (with_terms)
      for (std::size_t k = 0; k < n_terms; ++k) p.terms[k] = r.value(term_ids[k]);
    return p;
  };
  auto usable = [](const At& p) { return p.signal > 0 && std::isfinite(p.lg_signal) && p.variance > 0 && p.threshold > 0; };
  // The terms hold at a point when they add up to n² − S (a noise that grows with the signal, PRNU, is in neither),
  // each is finite and not negative, and T is the grid's one T.
  std::string terms_why;
  double threshold = 0;
  auto check_terms = [&](const At& p) {
    if (!by_terms || !terms_why.empty()) return;
    double sum = 0;
    for (std::size_t k = 0; k < n_terms; ++k) {
      if (!(p.terms[k] >= 0) || !std::isfinite(p.terms[k])) {
        terms_why = fmt::format("the floor term {} is {} at a point of the grid", chain.results().info(term_ids[k]).name, p.terms[k]);
        return;
      }
      sum += p.terms[k];
    }
    if (!(std::abs(sum - (p.variance - p.signal)) <= floor_tolerance * p.variance))
      terms_why = fmt::format("the detector's floor terms add up to {:.12g} e-², not n² − S = {:.12g} e-² (a noise that "
                              "grows with the signal, such as PRNU, is not a floor)", sum, p.variance - p.signal);
    else if (p.threshold != threshold)
      terms_why = "the criterion's threshold changes over the grid";
  };

  FactoredGrid grid;
  grid.bright_ = inversion->bright;
  grid.faint_ = inversion->faint;
  grid.set_columns(sweep, chain.results());
  std::vector<std::vector<double>> line(n_axes);  // lg S_end along each axis through x₀
  // Each floor term along each axis through x₀: term_line[k * n_axes + a][i].
  std::vector<std::vector<double>> term_line(n_terms * n_axes);
  std::vector<std::size_t> step(n_axes, 0);
  std::string term_names;  // the terms the plan keeps (those not 0 everywhere)
  try {
    const At base = at(step, by_terms);
    if (!usable(base)) {
      why_not = "the signal or the noise is not positive at the grid's first point";
      return std::nullopt;
    }
    threshold = base.threshold;
    check_terms(base);
    for (std::size_t a = 0; a < n_axes; ++a) {
      const std::size_t last = axes[a].steps - 1;
      auto along = [&](std::size_t i) {
        step.assign(n_axes, 0);
        step[a] = i;
        const At p = at(step, by_terms);
        if (!usable(p)) why_not = fmt::format("the signal or the noise is not positive at {} step {}", axes[a].key, i);
        check_terms(p);
        return p;
      };
      line[a].resize(axes[a].steps);
      line[a][0] = base.lg_signal;
      for (std::size_t k = 0; k < n_terms; ++k) {
        term_line[k * n_axes + a].resize(axes[a].steps);
        term_line[k * n_axes + a][0] = base.terms[k];
      }
      auto keep = [&](std::size_t i, const At& p) {
        line[a][i] = p.lg_signal;
        for (std::size_t k = 0; k < n_terms; ++k) term_line[k * n_axes + a][i] = p.terms[k];
      };
      if (!power_line[a]) {
        for (std::size_t i = 1; i <= last && why_not.empty(); ++i) keep(i, along(i));
      } else {
        // (Natural logarithms: glibc's log costs a fraction of its log10, and the slope takes the factor.)
        // ln(x_i/x_0) from the values in the axis's unit: the unit's factor cancels.
        const double* values = grid.axis_values_[a].data();
        const double ln_first = std::log(values[0]), ln_span = std::log(values[last]) - ln_first;
        const At end = along(last);
        const double slope = (end.lg_signal - base.lg_signal) / ln_span;
        for (std::size_t i = 1; i < last; ++i) line[a][i] = base.lg_signal + slope * (std::log(values[i]) - ln_first);
        line[a][last] = end.lg_signal;
        // Each term is a power of x along the line too (0 where it is 0 at both ends).
        for (std::size_t k = 0; k < n_terms && by_terms; ++k) {
          std::vector<double>& t = term_line[k * n_axes + a];
          const double t0 = base.terms[k], t1 = end.terms[k];
          if (t0 == 0 || t1 == 0) {
            std::fill(t.begin(), t.end(), 0.0);
            t[0] = t0, t[last] = t1;
          } else {
            const double power = std::log(t1 / t0) / ln_span;
            for (std::size_t i = 1; i < last; ++i) t[i] = t0 * std::exp(power * (std::log(values[i]) - ln_first));
            t[last] = t1;
          }
        }
        for (std::size_t i : {last / 4, last / 2, 3 * last / 4}) {
          if (!why_not.empty()) break;
          const At p = along(i);
          if (!(std::abs(p.lg_signal - line[a][i]) <= separation_tolerance))
            why_not = fmt::format("the signal is not the power law of {} that it declares", axes[a].key);
          for (std::size_t k = 0; k < n_terms && by_terms && terms_why.empty(); ++k)
            if (!(std::abs(p.terms[k] - term_line[k * n_axes + a][i]) <= separation_tolerance * p.terms[k]))
              terms_why = fmt::format("the floor term {} is not a power law of {}", chain.results().info(term_ids[k]).name, axes[a].key);
        }
      }
      if (!why_not.empty()) return std::nullopt;
    }
    // Which axes the noise floor and T depend on, and whether the signal and each floor term separate, at every
    // corner of the others.
    for (std::size_t a = 0; a < n_axes && why_not.empty(); ++a) {
      if (in_floor[a]) continue;
      const std::vector<std::size_t> tested = test_steps(axes[a].steps);
      for (std::size_t corner = 0; corner < corners && why_not.empty(); ++corner) {
        to_corner(step, a, corner, corners, axes);
        At first{};
        for (std::size_t t = 0; t < tested.size(); ++t) {
          step[a] = tested[t];
          const At p = at(step, by_terms);
          if (!usable(p)) {
            why_not = fmt::format("the signal or the noise is not positive at a corner of the grid ({} step {})",
                                  axes[a].key, tested[t]);
            break;
          }
          check_terms(p);
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
          // term(corner, x_a) / term(corner, x_a,0) = term(x₀ line, x_a) / term(x₀): a product of per-axis factors
          for (std::size_t k = 0; k < n_terms && by_terms && terms_why.empty(); ++k) {
            const std::vector<double>& l = term_line[k * n_axes + a];
            const double lhs = p.terms[k] * l[0], rhs = first.terms[k] * l[tested[t]];
            if (!(std::abs(lhs - rhs) <= separation_tolerance * std::max(std::abs(lhs), std::abs(rhs))))
              terms_why = fmt::format("the floor term {} is not a product of per-axis factors ({} at a corner of the grid)",
                                      chain.results().info(term_ids[k]).name, axes[a].key);
          }
        }
      }
    }
    if (!why_not.empty()) return std::nullopt;
    // A term that is 0 at x₀ must be 0 at every point evaluated (its factors are ratios to its value there).
    for (std::size_t k = 0; k < n_terms && by_terms && terms_why.empty(); ++k)
      if (base.terms[k] == 0)
        for (std::size_t a = 0; a < n_axes; ++a)
          for (double v : term_line[k * n_axes + a])
            if (v != 0 && terms_why.empty())
              terms_why = fmt::format("the floor term {} is 0 at the grid's first point but not along {}",
                                      chain.results().info(term_ids[k]).name, axes[a].key);

    // The power-law reasoning with a small J: the floor over J's sub-grid. Else the floor's terms, when they hold.
    std::size_t floor_points = 1;
    grid.floor_strides_.assign(n_axes, 0);
    for (std::size_t a = n_axes; a-- > 0;)
      if (in_floor[a]) grid.floor_strides_[a] = floor_points, floor_points *= axes[a].steps;
    const bool j_pays = not_power_law.empty() && 4 * (evaluations + floor_points) <= sweep.points();
    by_terms = by_terms && terms_why.empty() && !j_pays;
    if (!j_pays && !by_terms) {
      why_not = !not_power_law.empty() ? (terms_why.empty() ? not_power_law : not_power_law + "; " + terms_why)
                : terms_why.empty()
                    ? fmt::format("the noise floor varies with axes of {} points: too many for factoring to pay", floor_points)
                    : fmt::format("the noise floor varies with axes of {} points: too many for factoring to pay; {}",
                                  floor_points, terms_why);
      return std::nullopt;
    }
    if (by_terms) {
      // c(x) = Σ_k Π_a F_ka[x_a]: axis 0's factor is the term along its line, the others' the ratio to its value at x₀.
      grid.floor_strides_.assign(n_axes, 0);
      grid.base_ = inversion->faint + 2.5 * base.lg_signal;
      grid.threshold_ = threshold;
      for (std::size_t k = 0; k < n_terms; ++k) {
        if (base.terms[k] == 0) continue;  // 0 everywhere (checked above)
        for (std::size_t a = 0; a < n_axes; ++a) {
          std::vector<double> factor = term_line[k * n_axes + a];
          if (a > 0)
            for (double& f : factor) f /= base.terms[k];
          grid.term_factors_.push_back(std::move(factor));
        }
        ++grid.term_count_;
        term_names += (term_names.empty() ? "" : ", ") + chain.results().info(term_ids[k]).name;
      }
    } else {
      grid.floor_terms_.resize(floor_points);
      step.assign(n_axes, 0);
      for (std::size_t j = 0; j < floor_points; ++j) {
        for (std::size_t a = 0; a < n_axes; ++a)
          if (in_floor[a]) step[a] = (j / grid.floor_strides_[a]) % axes[a].steps;
        const At p = at(step, false);
        // S* from this point's own c = n² − S and T; NaN (no root) leaves the points that use it to the per-point path.
        const double required = physics::signal_at_snr(p.threshold, p.variance, p.signal);
        grid.floor_terms_[j] = inversion->faint + 2.5 * base.lg_signal - 2.5 * std::log10(required);
      }
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

  // The plan against the per-point solve: the grid's corners and points spread over it.
  const std::size_t total = sweep.points();
  const std::vector<std::size_t> checked = checked_points(axes, refs, corners, total);
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
  if (by_terms) {
    grid.description_ = fmt::format(
        "closed form factored over the grid: the noise floor as a sum of per-axis products ({}); {} chain evaluations, "
        "{} points checked against the per-point solve",
        term_names, evaluations, compared);
    return grid;
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

// A sweep with no [[solve]] that reads only the detector's signal, noise or SNR: the signal a sum of per-axis
// products (the surface's electrons and the path radiance's), the noise floor another (the detector's published
// floor variances), n = √(S + c), SNR = S/n. The same checks as for a magnitude: the terms add up to n² − S at every
// point evaluated, each separates at every corner, and the plan against the per-point evaluation at the corners
// and 64 spread points (1e-11 relative).
std::optional<FactoredGrid> FactoredGrid::plan_forward(const Sweep& sweep, SweepWorker& worker, std::string& why_not) {
  Chain& chain = worker.chain();
  const Results& results = chain.results();
  const auto snr = results.find(vocabulary::detector_snr.name), signal = results.find(vocabulary::detector_signal_electrons.name),
             noise = results.find(vocabulary::detector_noise_electrons.name);
  if (!snr || !signal || !noise) {
    why_not = "no [[solve]], and the chain has no detector signal, noise and SNR";
    return std::nullopt;
  }
  FactoredGrid grid;
  grid.forward_ = true;
  for (const auto& name : sweep.results()) {
    const int kind = name == vocabulary::detector_snr.name                ? 0
                     : name == vocabulary::detector_signal_electrons.name ? 1
                     : name == vocabulary::detector_noise_electrons.name  ? 2
                                                                           : -1;
    if (kind < 0) {
      why_not = "no [[solve]], and a result other than the detector's signal, noise or SNR is read (" + name + ")";
      return std::nullopt;
    }
    grid.result_kinds_.push_back(kind);
  }
  // The quantities that separate: the surface's signal, the path radiance's, then the floor's terms.
  std::vector<ResultId> floor_ids;
  for (const auto& term : vocabulary::floor_variances)
    if (const auto id = results.find(term.name)) floor_ids.push_back(*id);
  if (floor_ids.empty()) {
    why_not = "no [[solve]], and the detector publishes no noise floor by source";
    return std::nullopt;
  }
  const auto path = results.find(vocabulary::detector_path_radiance_electrons.name);
  const std::size_t n_signal = path ? 2 : 1, n_quantities = n_signal + floor_ids.size();
  const std::vector<SweepAxis>& axes = sweep.axes();
  const std::size_t n_axes = axes.size();
  const std::size_t corners = n_axes - 1 <= 6 ? std::size_t{1} << (n_axes - 1) : 2;
  std::size_t line_cost = 0, test_cost = 0;
  for (const SweepAxis& axis : axes) line_cost += axis.steps, test_cost += corners * test_steps(axis.steps).size();
  const std::size_t check_cost = std::min<std::size_t>(2 * corners, 64) + spread_checks;
  if (4 * (line_cost + test_cost + check_cost) > sweep.points()) {
    why_not = fmt::format("no [[solve]], and the grid's {} points are too few for factoring to pay", sweep.points());
    return std::nullopt;
  }
  std::vector<ParameterRef> refs;
  for (const SweepAxis& axis : axes) refs.push_back(chain.parameter(axis.key));

  std::size_t evaluations = 0;
  std::string terms_why;
  auto at = [&](const std::vector<std::size_t>& step) {
    for (std::size_t a = 0; a < n_axes; ++a) {
      const double v = axes[a].value_si(step[a]);
      if (refs[a].value() != v) chain.set(refs[a], v);
    }
    chain.evaluate(Detail::full);
    ++evaluations;
    const double s = results.value(*signal), n = results.value(*noise), p = path ? results.value(*path) : 0.0;
    std::vector<double> q{s - p};
    if (path) q.push_back(p);
    double floor = 0;
    for (ResultId id : floor_ids) q.push_back(results.value(id)), floor += q.back();
    if (terms_why.empty()) {
      for (std::size_t k = 0; k < n_quantities; ++k)
        if (!(q[k] >= 0) || !std::isfinite(q[k])) terms_why = fmt::format("a signal or floor term is {} at a point of the grid", q[k]);
      if (terms_why.empty() && !(std::abs(floor - (n * n - s)) <= floor_tolerance * n * n))
        terms_why = fmt::format("the detector's floor terms add up to {:.12g} e-², not n² − S = {:.12g} e-² (a noise that "
                                "grows with the signal, such as PRNU, is not a floor)", floor, n * n - s);
    }
    return q;
  };
  // Each quantity along each axis through x₀: line[k * n_axes + a][i].
  std::vector<std::vector<double>> line(n_quantities * n_axes);
  std::vector<std::size_t> step(n_axes, 0);
  try {
    const std::vector<double> base = at(step);
    for (std::size_t a = 0; a < n_axes; ++a) {
      for (std::size_t k = 0; k < n_quantities; ++k) line[k * n_axes + a].assign(axes[a].steps, base[k]);
      for (std::size_t i = 1; i < axes[a].steps; ++i) {
        step.assign(n_axes, 0);
        step[a] = i;
        const std::vector<double> q = at(step);
        for (std::size_t k = 0; k < n_quantities; ++k) line[k * n_axes + a][i] = q[k];
      }
    }
    for (std::size_t a = 0; a < n_axes && terms_why.empty(); ++a) {
      const std::vector<std::size_t> tested = test_steps(axes[a].steps);
      for (std::size_t corner = 0; corner < corners && terms_why.empty(); ++corner) {
        to_corner(step, a, corner, corners, axes);
        std::vector<double> first;
        for (std::size_t t = 0; t < tested.size() && terms_why.empty(); ++t) {
          step[a] = tested[t];
          const std::vector<double> q = at(step);
          if (t == 0) {
            first = q;
            continue;
          }
          for (std::size_t k = 0; k < n_quantities && terms_why.empty(); ++k) {
            const std::vector<double>& l = line[k * n_axes + a];
            const double lhs = q[k] * l[0], rhs = first[k] * l[tested[t]];
            if (!(std::abs(lhs - rhs) <= separation_tolerance * std::max(std::abs(lhs), std::abs(rhs))))
              terms_why = fmt::format("the {} is not a product of per-axis factors ({} at a corner of the grid)",
                                      k < n_signal ? "signal" : results.info(floor_ids[k - n_signal]).name, axes[a].key);
          }
        }
      }
    }
    for (std::size_t k = 0; k < n_quantities && terms_why.empty(); ++k)
      if (base[k] == 0)
        for (std::size_t a = 0; a < n_axes; ++a)
          for (double v : line[k * n_axes + a])
            if (v != 0 && terms_why.empty())
              terms_why = fmt::format("a term is 0 at the grid's first point but not along {}", axes[a].key);
    if (!terms_why.empty()) {
      why_not = "no [[solve]]; " + terms_why;
      return std::nullopt;
    }
    // Q(x) = Π_a F_a[x_a]: axis 0's factor is the quantity along its line, the others' ratios to its value at x₀.
    for (std::size_t k = 0; k < n_quantities; ++k) {
      if (base[k] == 0) continue;  // 0 everywhere (checked above)
      for (std::size_t a = 0; a < n_axes; ++a) {
        std::vector<double> factor = line[k * n_axes + a];
        if (a > 0)
          for (double& f : factor) f /= base[k];
        grid.term_factors_.push_back(std::move(factor));
      }
      ++grid.term_count_;
      if (k < n_signal) ++grid.signal_terms_;
    }
  } catch (const InputError& error) {
    why_not = std::string("the chain refuses a point of the grid: ") + error.what();
    return std::nullopt;
  }
  if (grid.signal_terms_ == 0) {
    why_not = "no [[solve]], and the signal is 0 at the grid's first point";
    return std::nullopt;
  }
  grid.set_columns(sweep, chain.results());
  grid.axis_terms_.resize(n_axes);
  grid.floor_strides_.assign(n_axes, 0);
  for (std::size_t a = 0; a < n_axes; ++a) grid.axis_terms_[a].assign(axes[a].steps, 0.0);

  // The plan against the per-point evaluation: the grid's corners and points spread over it.
  const std::size_t total = sweep.points();
  const std::vector<std::size_t> checked = checked_points(axes, refs, corners, total);
  const std::size_t n_columns = sweep.columns();
  std::vector<double> row(n_columns), reference(n_columns);
  std::size_t compared = 0;
  for (std::size_t point : checked) {
    if (point >= total) continue;
    char ok = 0;
    grid.evaluate(point, 1, 1, row.data(), &ok);
    bool evaluated = false;
    try {
      evaluated = worker.evaluate(point, reference.data());
    } catch (const InputError& error) {
      why_not = std::string("the chain refuses a point of the grid: ") + error.what();
      return std::nullopt;
    }
    for (std::size_t c = n_axes; c < n_columns; ++c)
      if (!ok || !evaluated || !(std::abs(row[c] - reference[c]) <= check_tolerance * std::abs(reference[c]))) {
        why_not = fmt::format("no [[solve]]; at grid point {} the factored {} {:.12g} differs from the per-point {:.12g}", point,
                              sweep.results()[c - n_axes], row[c], reference[c]);
        return std::nullopt;
      }
    ++compared;
  }
  grid.description_ = fmt::format(
      "forward results factored over the grid: the signal and the noise floor as sums of per-axis products; {} chain "
      "evaluations, {} points checked against the per-point evaluation",
      evaluations, compared);
  return grid;
}

void FactoredGrid::evaluate(std::size_t first, std::size_t count, std::size_t stride, double* out, char* ok) const {
  const std::size_t n_axes = steps_.size(), n_results = column_factors_.size(), n_columns = n_axes + n_results;
  const std::size_t last = n_axes - 1;
  std::vector<std::size_t> index(n_axes);
  std::vector<double> outer_values(n_axes);  // the axes before the last, in their units
  std::vector<double> outer_products(term_count_);
  std::vector<const double*> last_factors(term_count_);
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
    double* rows = out + k * n_columns;
    if (forward_) {
      fill_forward(rows, ok + k, run, index, outer_values, i0);
    } else if (term_count_ > 0) {
      // Each term's product over the axes before the last (axis 0's factor carries the term's value at x₀).
      for (std::size_t t = 0; t < term_count_; ++t) {
        double product = 1;
        for (std::size_t a = 0; a < last; ++a) product *= term_factors_[t * n_axes + a][index[a]];
        outer_products[t] = product;
        last_factors[t] = term_factors_[t * n_axes + last].data() + i0;
      }
      const double t2 = threshold_ * threshold_;
      const Run r{rows, ok + k, run, n_columns, outer_values.data(), values, inner, nullptr, 0, outer, low, high};
      const TermRun f{outer_products.data(), last_factors.data(), term_count_, t2, t2 * t2, base_};
      switch (n_axes) {
        case 1: fill_run_terms<1>(r, f); break;
        case 2: fill_run_terms<2>(r, f); break;
        case 3: fill_run_terms<3>(r, f); break;
        case 4: fill_run_terms<4>(r, f); break;
        default: fill_run_terms<0>(r, f, n_axes);
      }
    } else {
      const double* floor = floor_terms_.data() + floor_outer + i0 * floor_step;
      const Run r{rows, ok + k, run, n_columns, outer_values.data(), values, inner, floor, floor_step, outer, low, high};
      switch (n_axes) {  // one pass over the rows, unrolled for the usual number of axes
        case 1: fill_run<1>(r); break;
        case 2: fill_run<2>(r); break;
        case 3: fill_run<3>(r); break;
        case 4: fill_run<4>(r); break;
        default: fill_run<0>(r, n_axes);
      }
    }
    for (std::size_t c = n_results; c-- > 0 && !forward_;)  // the columns' display units (a magnitude's factor is 1); column 0 last
      if (c > 0 || column_factors_[c] != 1.0)
        for (std::size_t i = 0; i < run; ++i) rows[i * n_columns + n_axes + c] = rows[i * n_columns + n_axes] * column_factors_[c];
    k += run;
    point += run * stride;
  }
}

}  // namespace radchain

namespace radchain {

void FactoredGrid::fill_forward(double* rows, char* ok, std::size_t run, const std::vector<std::size_t>& index,
                                std::vector<double>& outer_values, std::size_t i0) const {
  const std::size_t n_axes = steps_.size(), last = n_axes - 1, n_results = column_factors_.size(),
                    n_columns = n_axes + n_results;
  // Each quantity's product over the axes before the last, and its factors along the last from the run's first step.
  double outer[16];
  const double* along[16];
  for (std::size_t t = 0; t < term_count_; ++t) {
    double product = 1;
    for (std::size_t a = 0; a < last; ++a) product *= term_factors_[t * n_axes + a][index[a]];
    outer[t] = product;
    along[t] = term_factors_[t * n_axes + last].data() + i0;
  }
  for (std::size_t a = 0; a < last; ++a) outer_values[a] = axis_columns_[a][index[a]];
  const double* values = axis_columns_[last].data() + i0;
  for (std::size_t i = 0; i < run; ++i) {
    double* row = rows + i * n_columns;
    for (std::size_t a = 0; a < last; ++a) row[a] = outer_values[a];
    row[last] = values[i];
    double signal = 0, floor = 0;
    for (std::size_t t = 0; t < signal_terms_; ++t) signal += outer[t] * along[t][i];
    for (std::size_t t = signal_terms_; t < term_count_; ++t) floor += outer[t] * along[t][i];
    const double noise = std::sqrt(signal + floor);  // EMVA 1288 eq. 6: shot noise and the floor
    for (std::size_t c = 0; c < n_results; ++c) {
      const double v = result_kinds_[c] == 0 ? signal / noise : result_kinds_[c] == 1 ? signal : noise;
      row[n_axes + c] = v * column_factors_[c];
    }
    ok[i] = noise > 0 && std::isfinite(noise);
  }
}

}  // namespace radchain

namespace radchain {

void FactoredGrid::set_columns(const Sweep& sweep, const Results& results) {
  const std::vector<SweepAxis>& axes = sweep.axes();
  column_factors_.clear();
  for (const auto& name : sweep.results())
    column_factors_.push_back(sweep.options().si_columns ? 1.0 : results.info(*results.find(name)).display_factor);
  steps_.resize(axes.size());
  axis_values_.resize(axes.size());
  axis_columns_.clear();
  for (std::size_t a = 0; a < axes.size(); ++a) {
    steps_[a] = axes[a].steps;
    axis_values_[a].resize(axes[a].steps);
    for (std::size_t i = 0; i < axes[a].steps; ++i) axis_values_[a][i] = axes[a].value(i);
    axis_columns_.push_back(axis_values_[a]);
    if (sweep.options().si_columns)
      for (std::size_t i = 0; i < axes[a].steps; ++i) axis_columns_[a][i] = axes[a].value_si(i);
  }
}

}  // namespace radchain
