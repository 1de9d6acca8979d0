// The chain's [[solve]] entries: each unknown is found by bracketing the root of its criteria's margins,
// one point at a time (Boost.Math TOMS 748) or for lane_count points in lockstep (Dekker's method).
#include "radchain/chain.hpp"

#include "radchain/error.hpp"
#include "radchain/vocabulary.hpp"

#include <boost/math/tools/roots.hpp>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cmath>
#include <fmt/format.h>
#include <limits>

namespace radchain {

// The margin a solver drives to zero, in a form close to linear in the unknown. Every criterion's margin is
// achieved/required − 1 (docs/architecture.md), and the physics behind the ratio r = 1 + margin is a power law or
// an exponential in the unknown (SNR ∝ D², ∝ 10^{-0.4 m}): log r is nearly straight where the margin itself spans
// decades over the bracket (TOMS 748 needs 8 iterations for the SBV magnitude instead of 17). Any strictly
// increasing g with g(0) = 0 has the same root, so log2 r need not be exact: its exponent plus
// t(10 − 4t + t²)/7 for the mantissa 1 + t (exact at powers of two, within 0.005 in between, increasing, and
// smooth to the second derivative across octaves, which TOMS 748's cubic steps need) costs a few integer
// operations where a library log costs ~15 ns, and a solve evaluates it at every step. A ratio ≤ 0 maps below
// every positive ratio.
static double solver_margin(double margin) {
  const double r = 1.0 + margin;
  if (!(r >= std::numeric_limits<double>::min())) return std::isnan(margin) ? margin : -2000.0;
  const auto bits = std::bit_cast<std::uint64_t>(r);
  const int exponent = static_cast<int>(bits >> 52) - 1023;  // r > 0 and normal: no sign bit, no subnormal
  const double t = std::bit_cast<double>((bits & 0x000fffffffffffffULL) | 0x3ff0000000000000ULL) - 1.0;
  return exponent + t * (10.0 / 7.0 - t * (4.0 / 7.0 - t * (1.0 / 7.0)));
}

void Chain::resolve_solves(const std::vector<ResultId>& echo_ids) {
  resolved_.clear();
  for (std::size_t i = 0; i < solves.size(); ++i) {
    ResolvedSolve r{parameter(solves[i].unknown), {}, i < echo_ids.size() ? echo_ids[i] : SIZE_MAX};
    for (const auto& name : solves[i].criteria) r.margins.push_back(*results_.find(vocabulary::criterion_margin.in_criterion(name)));
    resolved_.push_back(std::move(r));
  }
}

void Chain::solve(std::size_t index, SolveOutcome& outcome) {
  const SolveSpec& spec = solves[index];
  const ResolvedSolve& resolved = resolved_[index];
  const std::vector<ResultId>& margins = resolved.margins;
  // The outcome is reused between sweep points: its copy of the spec only when it is another solve's.
  if (outcome.spec.unknown != spec.unknown || outcome.spec.criteria != spec.criteria) outcome.spec = spec;
  outcome.value_si = std::numeric_limits<double>::quiet_NaN();
  outcome.iterations = 0;
  outcome.converged = false;
  outcome.message.clear();
  outcome.binding.clear();
  outcome.roots.clear();
  auto set_unknown = [&](double x, Detail detail) {
    set(resolved.unknown, x);
    evaluate(detail);
  };

  // Each criterion's own root (Boost.Math TOMS 748: Alefeld, Potra, Shi 1995; bracketing, superlinear).
  for (std::size_t k = 0; k < margins.size(); ++k) {
    auto f = [&](double x) {
      set_unknown(x, Detail::essential);
      return solver_margin(results_.value(margins[k]));
    };
    const double f_lo = f(spec.lo), f_hi = f(spec.hi);
    if (std::isnan(f_lo) || std::isnan(f_hi)) {
      outcome.message = fmt::format("criterion \"{}\": the margin is not a number at the bracket ends", spec.criteria[k]);
      return;
    }
    double root = f_lo == 0 ? spec.lo : spec.hi;
    if (f_lo != 0 && f_hi != 0) {
      if ((f_lo > 0) == (f_hi > 0)) {
        set_unknown(spec.lo, Detail::essential);
        const double margin_lo = results_.value(margins[k]);
        set_unknown(spec.hi, Detail::essential);
        const double margin_hi = results_.value(margins[k]);
        outcome.message = fmt::format("criterion \"{}\" has the same sign at both ends of the bracket (margin {:.4g} and "
                                      "{:.4g}): no solution in [{:g}, {:g}]",
                                      spec.criteria[k], margin_lo, margin_hi, spec.lo, spec.hi);
        return;
      }
      std::uintmax_t iterations = 200;
      const auto [a, b] = boost::math::tools::toms748_solve(f, spec.lo, spec.hi, f_lo, f_hi,
                                                            boost::math::tools::eps_tolerance<double>(48), iterations);
      if (iterations >= 200) {
        outcome.message = fmt::format("criterion \"{}\": no convergence in 200 iterations", spec.criteria[k]);
        return;
      }
      outcome.iterations += static_cast<int>(iterations);
      root = 0.5 * (a + b);
    }
    outcome.roots.emplace_back(spec.criteria[k], root);
  }

  // Keep the root at which every listed margin holds (≥ 0 up to the solver's tolerance): that criterion binds.
  std::size_t chosen = margins.size();
  double best_slack = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < margins.size(); ++k) {
    if (margins.size() > 1) set_unknown(outcome.roots[k].second, Detail::essential);  // (one criterion: nothing to check)
    double worst = std::numeric_limits<double>::infinity();
    for (std::size_t m = 0; m < margins.size(); ++m)
      if (m != k) worst = std::min(worst, results_.value(margins[m]));
    if (!(worst >= -1e-9)) continue;
    if (chosen == margins.size() || worst < best_slack) chosen = k, best_slack = worst;
  }
  if (chosen == margins.size()) {
    outcome.message = "no value satisfies all the listed criteria at once";
    return;
  }
  outcome.value_si = outcome.roots[chosen].second;
  outcome.binding = spec.criteria[chosen];
  outcome.converged = true;
  set_unknown(outcome.value_si, Detail::full);
}

bool Chain::lanes_can_solve() const { return solves.size() == 1 && !resolved_.empty() && !resolved_[0].unknown.spectral(); }

void Chain::solve_lanes(LaneSolveOutcome& outcome) {
  if (!lanes_can_solve()) throw std::logic_error("solve_lanes: the chain needs exactly one [[solve]] on a non-spectral unknown");
  const SolveSpec& spec = solves[0];
  const ResolvedSolve& resolved = resolved_[0];
  const std::size_t n_criteria = resolved.margins.size();
  const double tolerance = std::ldexp(1.0, 1 - 48);  // boost::math::tools::eps_tolerance<double>(48), as solve()
  outcome.passes = 0;
  outcome.converged.fill(true);
  for (auto& m : outcome.message) m.clear();
  auto margins_at = [&](const Lanes& x) {
    set_lanes(resolved.unknown, x);
    evaluate_lanes(Detail::essential);
    ++outcome.passes;
  };
  auto solver_margins = [&](ResultId id) {
    const Lanes& m = lane_result(id);
    Lanes g;
    for (int i = 0; i < lane_count; ++i) g(i) = solver_margin(m(i));
    return g;
  };
  auto fail = [&](int lane, std::string message) {
    if (outcome.converged[lane]) outcome.converged[lane] = false, outcome.message[lane] = std::move(message);
  };

  std::vector<Lanes> roots(n_criteria);
  for (std::size_t k = 0; k < n_criteria; ++k) {
    const ResultId id = resolved.margins[k];
    // Dekker's method per lane (Dekker 1969; Brent 1973 ch. 4): b the best end, a the contrapoint, c the previous
    // b. A secant step through b and c when it falls between b and the midpoint, else bisection; never a step
    // below the tolerance, so the bracket closes from both sides.
    Lanes a = constant_lanes(spec.lo), b = constant_lanes(spec.hi);
    margins_at(a);
    Lanes f_a = solver_margins(id);
    const Lanes margin_lo = lane_result(id);
    margins_at(b);
    Lanes f_b = solver_margins(id);
    Lanes c = a, f_c = f_a;
    Lanes& root = roots[k];
    std::array<bool, lane_count> active{};
    for (int i = 0; i < lane_count; ++i) {
      root(i) = spec.lo;
      if (std::isnan(f_a(i)) || std::isnan(f_b(i))) {
        fail(i, fmt::format("criterion \"{}\": the margin is not a number at the bracket ends", spec.criteria[k]));
      } else if (f_a(i) == 0 || f_b(i) == 0) {
        root(i) = f_a(i) == 0 ? spec.lo : spec.hi;
      } else if ((f_a(i) > 0) == (f_b(i) > 0)) {
        fail(i, fmt::format("criterion \"{}\" has the same sign at both ends of the bracket (margin {:.4g} and {:.4g}): "
                            "no solution in [{:g}, {:g}]",
                            spec.criteria[k], margin_lo(i), lane_result(id)(i), spec.lo, spec.hi));
      } else {
        active[i] = true;
      }
    }
    for (int iteration = 0; iteration < 200; ++iteration) {
      bool any = false;
      Lanes x = root;
      for (int i = 0; i < lane_count; ++i) {
        if (!active[i]) continue;
        // (Selects rather than branches: which end is best flips unpredictably.)
        const bool swap = std::abs(f_b(i)) > std::abs(f_a(i));
        const double a_i = swap ? b(i) : a(i), b_i = swap ? a(i) : b(i);
        const double fa_i = swap ? f_b(i) : f_a(i), fb_i = swap ? f_a(i) : f_b(i);
        const double c_i = swap ? a_i : c(i), fc_i = swap ? fa_i : f_c(i);
        a(i) = a_i, b(i) = b_i, c(i) = c_i, f_a(i) = fa_i, f_b(i) = fb_i, f_c(i) = fc_i;
        const double m = 0.5 * (a_i - b_i);
        const double step_min = 0.5 * tolerance * std::min(std::abs(a_i), std::abs(b_i));
        if (std::abs(m) <= step_min || fb_i == 0) {  // |a − b| ≤ tolerance × min(|a|, |b|): solve()'s test
          root(i) = fb_i == 0 ? b_i : 0.5 * (a_i + b_i);
          active[i] = false;
          continue;
        }
        any = true;
        const double secant = fb_i != fc_i ? b_i - fb_i * (b_i - c_i) / (fb_i - fc_i) : b_i + m;
        double s = (secant - b_i) * (secant - (b_i + m)) <= 0 ? secant : b_i + m;  // between b and the midpoint
        s = std::abs(s - b_i) < step_min ? b_i + std::copysign(step_min, m) : s;
        x(i) = s;
      }
      if (!any) break;
      margins_at(x);
      const Lanes f_x = solver_margins(id);
      for (int i = 0; i < lane_count; ++i) {
        if (!active[i]) continue;
        const bool same_side = (f_x(i) > 0) == (f_a(i) > 0);  // then the old b becomes the contrapoint
        a(i) = same_side ? b(i) : a(i), f_a(i) = same_side ? f_b(i) : f_a(i);
        c(i) = b(i), f_c(i) = f_b(i);
        b(i) = x(i), f_b(i) = f_x(i);
      }
    }
    for (int i = 0; i < lane_count; ++i)
      if (active[i]) fail(i, fmt::format("criterion \"{}\": no convergence in 200 iterations", spec.criteria[k]));
  }

  // Per lane, the root at which every listed margin holds: that criterion binds (as solve()).
  Lanes chosen_root = roots[0];
  if (n_criteria > 1) {
    std::array<double, lane_count> best_slack;
    std::array<bool, lane_count> found{};
    best_slack.fill(std::numeric_limits<double>::infinity());
    for (std::size_t k = 0; k < n_criteria; ++k) {
      margins_at(roots[k]);
      for (int i = 0; i < lane_count; ++i) {
        double worst = std::numeric_limits<double>::infinity();
        for (std::size_t m = 0; m < n_criteria; ++m)
          if (m != k) worst = std::min(worst, lane_result(resolved.margins[m])(i));
        if (!(worst >= -1e-9)) continue;
        if (!found[i] || worst < best_slack[i]) found[i] = true, best_slack[i] = worst, chosen_root(i) = roots[k](i);
      }
    }
    for (int i = 0; i < lane_count; ++i)
      if (!found[i]) fail(i, "no value satisfies all the listed criteria at once");
  }
  outcome.value = chosen_root;
  for (int i = 0; i < lane_count; ++i)
    if (!outcome.converged[i]) outcome.value(i) = std::numeric_limits<double>::quiet_NaN();
  set_lanes(resolved.unknown, chosen_root);
  evaluate_lanes(Detail::full);
  ++outcome.passes;
}

void Chain::solve_all(std::vector<SolveOutcome>& outcomes) {
  outcomes.resize(solves.size());
  if (solves.empty()) {
    evaluate();  // every solve ends with a full evaluation at the parameters it leaves; without solves, this one
    return;
  }
  // A failed solve has no value: the result echoing its unknown says NaN, not the bracket end the solver tried
  // last (issue 18: "results that lie"). Set after every evaluation, since each one rewrites the echoes.
  auto failed_are_nan = [&] {
    for (std::size_t i = 0; i < solves.size(); ++i)
      if (!outcomes[i].converged && resolved_[i].echo != SIZE_MAX)
        results_.set(resolved_[i].echo, std::numeric_limits<double>::quiet_NaN());
  };
  if (solves.size() == 1) {
    solve(0, outcomes[0]);
    failed_are_nan();
    return;
  }
  // Several solves form a design: repeat them in order until no unknown moves (they are usually decoupled,
  // and then one pass suffices).
  std::vector<double> previous(solves.size(), std::numeric_limits<double>::quiet_NaN());
  for (int pass = 0; pass < 30; ++pass) {
    bool moved = false;
    for (std::size_t i = 0; i < solves.size(); ++i) {
      solve(i, outcomes[i]);
      const double v = outcomes[i].value_si;
      if (!(std::abs(v - previous[i]) <= 1e-12 * std::abs(v))) moved = true;
      previous[i] = v;
    }
    if (!moved) break;
  }
  failed_are_nan();
}

}  // namespace radchain
