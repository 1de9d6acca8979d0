// The chain's [[solve]] entries. Where the chain declares how the unknown acts (a power law of x or of the flux
// 10^(−0.4 x), through stages whose results are power laws, into a criterion with a closed-form inverse), the root
// follows in closed form — for a target's magnitude through the noise equation from the faint bracket end alone,
// otherwise from the margins at both ends — and is accepted when the margin there is zero to 1e-12;
// otherwise, and with --solver root, the root is bracketed one point at a time (Boost.Math TOMS 748) or for
// lane_count points in lockstep (Dekker's method).
#include "radchain/chain.hpp"

#include "radchain/error.hpp"
#include "radchain/physics/detection.hpp"
#include "radchain/vocabulary.hpp"

#include <boost/math/tools/roots.hpp>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <numbers>

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

namespace {

// A closed-form root is kept when the margin there is this close to zero (a bracketing solve ends within 2^-47 of
// the root, i.e. margins of ~1e-14 for the chain's power laws); otherwise the root is bracketed.
constexpr double closed_form_tolerance = 1e-12;

// One end of the bracket as the closed forms need it.
struct Sample {
  double x = 0, ratio = 0;            // the unknown; 1 + margin
  double signal = 0, variance = 0;    // noise_equation: S and n² (electrons)
};

// ln(u(x1)/u(x0)) for the unknown's variable u: x itself (power_law), or the flux ratio 10^(−0.4 x) (magnitude).
double log_variable_ratio(Scaling scaling, double x0, double x1) {
  return scaling == Scaling::magnitude ? -0.4 * std::numbers::ln10 * (x1 - x0) : std::log(x1 / x0);
}
// The x at which ln(u/u(x0)) = log_ratio.
double from_log_variable(Scaling scaling, double x0, double log_ratio) {
  return scaling == Scaling::magnitude ? x0 - log_ratio / (0.4 * std::numbers::ln10) : x0 * std::exp(log_ratio);
}

// The root of the criterion's margin in closed form from the two bracket ends (docs/performance.md, "Closed-form
// solves"); NaN when the ends do not follow the declared form (then the root is bracketed).
double closed_form_root(InverseForm form, Scaling scaling, const Sample& a, const Sample& b) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  if (scaling == Scaling::power_law && !(a.x > 0 && b.x > 0)) return nan;
  const double du = log_variable_ratio(scaling, a.x, b.x);
  if (!std::isfinite(du) || du == 0) return nan;
  if (form == InverseForm::power_law) {
    // 1 + margin = c·u^k: k from the ends, then the u at which it is 1.
    if (!(a.ratio > 0 && b.ratio > 0)) return nan;
    const double k = std::log(b.ratio / a.ratio) / du;
    if (!(std::abs(k) > 1e-12)) return nan;
    return from_log_variable(scaling, a.x, -std::log(a.ratio) / k);
  }
  // noise_equation: S ∝ u^k, n² = b·S + c, and 1 + margin = (S/n)/T. T is the same at both ends or the margin is
  // not of this form. At the root S/n = T: S² = T² (b S + c), whose positive root is S = (T² b + √(T⁴b² + 4T²c))/2.
  if (!(a.signal > 0 && b.signal > 0 && a.variance > 0 && b.variance > 0 && a.ratio > 0 && b.ratio > 0) ||
      a.signal == b.signal)
    return nan;
  const double k = std::log(b.signal / a.signal) / du;
  const double t_a = a.signal / (std::sqrt(a.variance) * a.ratio), t_b = b.signal / (std::sqrt(b.variance) * b.ratio);
  if (!(std::abs(t_a - t_b) <= 1e-9 * t_a)) return nan;
  const double slope = (b.variance - a.variance) / (b.signal - a.signal);
  const Sample& faint = a.signal < b.signal ? a : b;  // c from the end where b·S is smaller: less cancellation
  const double offset = faint.variance - slope * faint.signal;
  const double t2 = t_a * t_a;
  const double discriminant = t2 * t2 * slope * slope + 4.0 * t2 * offset;
  if (!(discriminant >= 0)) return nan;
  const double signal = 0.5 * (t2 * slope + std::sqrt(discriminant));
  if (!(signal > 0)) return nan;
  return from_log_variable(scaling, a.x, std::log(signal / a.signal) / k);
}

// The root from the faint bracket end alone, where the unknown is a target's magnitude and the criterion is the
// noise equation: through stages whose signals are powers of the flux the signal is S ∝ u = 10^(−0.4 x) (k = 1),
// and a detector counting Poisson electrons has n² = S + c (b = 1), so the criterion's T and one end's c = n² − S
// give the root x = x_end − 2.5 log10(S*/S_end) with S* = (T² + √(T⁴ + 4T²c))/2. The faint end (largest
// magnitude), because at the bright one c = n² − S cancels (S ≫ c left margins of ~1e-11 at the root); T is the
// criterion's own, since rebuilding it from the margin at the faint end (1 + margin ≈ 1e-4) loses as many digits.
// Nothing is assumed unchecked: the margin at the root must be zero to 1e-12, as for the two-end form, or both
// ends are evaluated and the two-end form (or the bracketing solver) takes over. NaN when the end does not fit.
double closed_form_root_from_one_end(double x, double signal, double variance, double threshold) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  if (!(signal > 0 && variance > 0 && threshold > 0)) return nan;
  const double root_signal = physics::signal_at_snr(threshold, variance, signal);
  if (!(root_signal > 0)) return nan;
  return x - 2.5 * std::log10(root_signal / signal);
}

bool one_end_applies(InverseForm form, ResultId threshold, bool through_signal) {
  return form == InverseForm::noise_equation && threshold != SIZE_MAX && through_signal;
}

std::string stage_name(const StageSlot& s) { return fmt::format("{} (plugin \"{}\")", s.section, s.plugin); }

}  // namespace

Chain::Inversion Chain::inversion_for(const ParameterRef& unknown, const std::string& criterion) {
  Inversion inversion;
  std::size_t c = 0;
  while (c < stages.size() && stages[c].section != "criteria." + criterion) ++c;
  const StageSlot& owner = stages[unknown.stage()];
  if (unknown.scaling() == Scaling::none || unknown.spectral()) {
    inversion.why_not = stage_name(owner) + " declares no power law for the unknown";
  } else if (c == stages.size() || c < unknown.stage() || stages[c].info->inverse == InverseForm::none) {
    inversion.why_not = (c == stages.size() ? "criteria." + criterion : stage_name(stages[c])) + " declares no closed-form inverse";
  } else {
    // A target's magnitude acts only through the flux: the stages after it need signals that are powers of the
    // flux they receive; any other unknown (an aperture, a focal length, a sky brightness) needs power laws of all.
    const bool through_signal = unknown.scaling() == Scaling::magnitude && owner.section == "target";
    inversion.through_signal = through_signal;
    for (std::size_t s = unknown.stage() + 1; s < c && inversion.why_not.empty(); ++s) {
      if (stages[s].section.rfind("criteria.", 0) == 0) continue;
      const Stage& stage = *stages[s].stage;
      if (through_signal ? !stage.power_law_in_signal() : !stage.power_law())
        inversion.why_not = stage_name(stages[s]) + (through_signal ? " does not declare signals that are powers of its flux"
                                                                    : " does not declare power-law results");
    }
  }
  if (!inversion.why_not.empty()) return inversion;
  inversion.form = stages[c].info->inverse;
  if (inversion.form == InverseForm::noise_equation) {
    const auto signal = results_.find(vocabulary::detector_signal_electrons.name);
    const auto noise = results_.find(vocabulary::detector_noise_electrons.name);
    if (signal && noise) inversion.signal = *signal, inversion.noise = *noise;
    else inversion.form = InverseForm::power_law;  // no noise budget published: the SNR itself as c·u^k
    if (const auto threshold = results_.find(vocabulary::criterion_threshold.in_criterion(criterion))) inversion.threshold = *threshold;
  }
  return inversion;
}

void Chain::resolve_solves(const std::vector<ResultId>& echo_ids) {
  resolved_.clear();
  for (std::size_t i = 0; i < solves.size(); ++i) {
    ResolvedSolve r{parameter(solves[i].unknown), {}, {}, i < echo_ids.size() ? echo_ids[i] : SIZE_MAX};
    for (const auto& name : solves[i].criteria) {
      r.margins.push_back(*results_.find(vocabulary::criterion_margin.in_criterion(name)));
      r.inversions.push_back(inversion_for(r.unknown, name));
    }
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
  outcome.method.clear();
  outcome.fallback.clear();
  std::vector<std::pair<std::string, std::string>> methods;  // per criterion: how its root was found, why not closed
  // With one criterion the closed form's check is the final full evaluation at the root.
  const Detail check_detail = margins.size() == 1 ? Detail::full : Detail::essential;
  bool final_evaluated = false;
  auto set_unknown = [&](double x, Detail detail) {
    set(resolved.unknown, x);
    evaluate(detail);
  };

  // Each criterion's own root: in closed form where declared and confirmed, else bracketed (Boost.Math TOMS 748:
  // Alefeld, Potra, Shi 1995; superlinear).
  for (std::size_t k = 0; k < margins.size(); ++k) {
    const Inversion& inversion = resolved.inversions[k];
    auto f = [&](double x) {
      set_unknown(x, Detail::essential);
      return solver_margin(results_.value(margins[k]));
    };
    auto sample = [&](double x) {
      Sample s{x, 1.0 + results_.value(margins[k])};
      if (inversion.form == InverseForm::noise_equation) {
        const double n = results_.value(inversion.noise);
        s.signal = results_.value(inversion.signal), s.variance = n * n;
      }
      return s;
    };
    if (solver == SolverChoice::automatic && one_end_applies(inversion.form, inversion.threshold, inversion.through_signal)) {
      const double faint = std::max(spec.lo, spec.hi);
      const double f_faint = f(faint);
      const Sample at = sample(faint);
      const double x = f_faint != 0 && !std::isnan(f_faint)
                           ? closed_form_root_from_one_end(faint, at.signal, at.variance, results_.value(inversion.threshold))
                           : std::numeric_limits<double>::quiet_NaN();
      if (x >= std::min(spec.lo, spec.hi) && x <= std::max(spec.lo, spec.hi)) {
        set_unknown(x, check_detail);
        ++outcome.iterations;
        if (std::abs(results_.value(margins[k])) <= closed_form_tolerance) {
          final_evaluated = check_detail == Detail::full;
          outcome.roots.emplace_back(spec.criteria[k], x);
          methods.emplace_back("closed form (noise equation)", "");
          continue;
        }
      }
    }
    const double f_lo = f(spec.lo);
    const Sample at_lo = sample(spec.lo);
    const double f_hi = f(spec.hi);
    const Sample at_hi = sample(spec.hi);
    std::string method = "root (TOMS 748)", why_not = solver == SolverChoice::automatic ? inversion.why_not : "";
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
      bool closed = false;
      if (solver == SolverChoice::automatic && inversion.form != InverseForm::none) {
        const double x = closed_form_root(inversion.form, resolved.unknown.scaling(), at_lo, at_hi);
        if (x >= std::min(spec.lo, spec.hi) && x <= std::max(spec.lo, spec.hi)) {
          set_unknown(x, check_detail);
          ++outcome.iterations;
          const double margin = results_.value(margins[k]);
          closed = std::abs(margin) <= closed_form_tolerance;
          final_evaluated = closed && check_detail == Detail::full;
          if (closed) root = x, method = inversion.form == InverseForm::noise_equation ? "closed form (noise equation)" : "closed form (power law)";
          else why_not = fmt::format("the closed form's root {:.10g} leaves a margin of {:.3g}", x, margin);
        } else {
          why_not = "the margins at the bracket ends do not follow the declared power law";
        }
      }
      if (!closed) {
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
    } else {
      method = "bracket end";
      why_not.clear();
    }
    outcome.roots.emplace_back(spec.criteria[k], root);
    methods.emplace_back(method, why_not);
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
  outcome.method = methods[chosen].first;
  outcome.fallback = methods[chosen].second;
  outcome.converged = true;
  if (!final_evaluated) set_unknown(outcome.value_si, Detail::full);
}

std::optional<Chain::MagnitudeInversion> Chain::magnitude_inversion() const {
  if (solver != SolverChoice::automatic || solves.size() != 1 || resolved_.size() != 1 || resolved_[0].margins.size() != 1)
    return std::nullopt;
  const ResolvedSolve& resolved = resolved_[0];
  const Inversion& inversion = resolved.inversions[0];
  if (!one_end_applies(inversion.form, inversion.threshold, inversion.through_signal)) return std::nullopt;
  std::size_t criterion = 0;
  while (criterion < stages.size() && stages[criterion].section != "criteria." + solves[0].criteria[0]) ++criterion;
  return MagnitudeInversion{resolved.unknown,       criterion,
                            inversion.signal,        inversion.noise,
                            inversion.threshold,     std::max(solves[0].lo, solves[0].hi),
                            std::min(solves[0].lo, solves[0].hi)};
}

bool Chain::lanes_can_solve() const { return solves.size() == 1 && !resolved_.empty() && !resolved_[0].unknown.spectral(); }

void Chain::solve_lanes(LaneSolveOutcome& outcome) {
  if (!lanes_can_solve()) throw std::logic_error("solve_lanes: the chain needs exactly one [[solve]] on a non-spectral unknown");
  const SolveSpec& spec = solves[0];
  const ResolvedSolve& resolved = resolved_[0];
  const std::size_t n_criteria = resolved.margins.size();
  const double tolerance = std::ldexp(1.0, 1 - 48);  // boost::math::tools::eps_tolerance<double>(48), as solve()
  outcome.passes = 0;
  outcome.closed_form = 0;
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

  std::vector<Lanes>& roots = outcome.criterion_roots;
  roots.resize(n_criteria);
  for (std::size_t k = 0; k < n_criteria; ++k) {
    const ResultId id = resolved.margins[k];
    const Inversion& inversion = resolved.inversions[k];
    const bool try_closed_form = solver == SolverChoice::automatic && inversion.form != InverseForm::none;
    auto samples = [&](std::array<Sample, lane_count>& out, const Lanes& x) {
      if (!try_closed_form) return;
      const Lanes& m = lane_result(id);
      for (int i = 0; i < lane_count; ++i) out[i] = Sample{x(i), 1.0 + m(i)};
      if (inversion.form != InverseForm::noise_equation) return;
      const Lanes &s = lane_result(inversion.signal), &n = lane_result(inversion.noise);
      for (int i = 0; i < lane_count; ++i) out[i].signal = s(i), out[i].variance = n(i) * n(i);
    };
    // Dekker's method per lane (Dekker 1969; Brent 1973 ch. 4): b the best end, a the contrapoint, c the previous
    // b. A secant step through b and c when it falls between b and the midpoint, else bisection; never a step
    // below the tolerance, so the bracket closes from both sides.
    Lanes a = constant_lanes(spec.lo), b = constant_lanes(spec.hi);
    Lanes& root = roots[k];
    // The check both closed forms share (as solve()): the lanes evaluated at the candidates' roots (the others where
    // x leaves them), and the roots kept whose margin is zero to the tolerance.
    auto confirm = [&](const Lanes& x, const std::array<bool, lane_count>& candidate) {
      set_lanes(resolved.unknown, x);
      evaluate_lanes(n_criteria == 1 ? outcome.final_detail : Detail::essential);
      ++outcome.passes;
      const Lanes& m = lane_result(id);
      std::array<bool, lane_count> confirmed{};
      for (int i = 0; i < lane_count; ++i)
        if (candidate[i] && std::abs(m(i)) <= closed_form_tolerance) confirmed[i] = true, root(i) = x(i), ++outcome.closed_form;
      return confirmed;
    };
    // Lanes whose root the faint end alone gave and the check at the root confirmed.
    std::array<bool, lane_count> settled{};
    if (try_closed_form && one_end_applies(inversion.form, inversion.threshold, inversion.through_signal)) {
      const double faint = std::max(spec.lo, spec.hi);
      margins_at(constant_lanes(faint));
      const Lanes &m = lane_result(id), &s = lane_result(inversion.signal), &n = lane_result(inversion.noise),
                  &t = lane_result(inversion.threshold);
      Lanes x = constant_lanes(faint);
      std::array<bool, lane_count> candidate{};
      bool any = false;
      for (int i = 0; i < lane_count; ++i) {
        if (std::isnan(m(i)) || m(i) == 0) continue;  // (as the bracket ends: NaN fails, zero is the root)
        const double xi = closed_form_root_from_one_end(faint, s(i), n(i) * n(i), t(i));
        candidate[i] = xi >= std::min(spec.lo, spec.hi) && xi <= faint;
        if (candidate[i]) x(i) = xi, any = true;
      }
      if (any) {
        settled = confirm(x, candidate);
        if (std::all_of(settled.begin(), settled.end(), [](bool s) { return s; })) {
          if (n_criteria == 1) {  // every lane was last evaluated at its root, in the final detail
            outcome.value = root;
            return;
          }
          continue;
        }
      }
    }
    std::array<Sample, lane_count> at_lo, at_hi;
    margins_at(a);
    Lanes f_a = solver_margins(id);
    const Lanes margin_lo = lane_result(id);
    samples(at_lo, a);
    margins_at(b);
    Lanes f_b = solver_margins(id);
    samples(at_hi, b);
    Lanes c = a, f_c = f_a;
    std::array<bool, lane_count> active{};
    for (int i = 0; i < lane_count; ++i) {
      if (settled[i]) continue;
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
    bool final_evaluated = false;  // the closed form's check was the final full evaluation (one criterion)
    if (try_closed_form) {  // the closed-form roots, kept where the margin confirms them (as solve())
      Lanes x = root;
      bool any = false;
      std::array<bool, lane_count> candidate{};
      for (int i = 0; i < lane_count; ++i) {
        if (!active[i]) continue;
        const double xi = closed_form_root(inversion.form, resolved.unknown.scaling(), at_lo[i], at_hi[i]);
        candidate[i] = xi >= std::min(spec.lo, spec.hi) && xi <= std::max(spec.lo, spec.hi);
        if (candidate[i]) x(i) = xi, any = true;
      }
      if (any) {
        const std::array<bool, lane_count> confirmed = confirm(x, candidate);
        for (int i = 0; i < lane_count; ++i) active[i] = active[i] && !confirmed[i];
        final_evaluated = n_criteria == 1 && std::none_of(active.begin(), active.end(), [](bool a) { return a; });
      }
    }
    if (final_evaluated) {  // every lane's root is where the lanes were last evaluated, in the final detail
      outcome.value = root;
      for (int i = 0; i < lane_count; ++i)
        if (!outcome.converged[i]) outcome.value(i) = std::numeric_limits<double>::quiet_NaN();
      return;
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
  evaluate_lanes(outcome.final_detail);
  ++outcome.passes;
}

void Chain::drop_solves() {
  solves.clear();
  for (ResolvedSolve& r : resolved_) r.margins.clear(), r.inversions.clear();  // (echoes stay: the unknowns' values)
}

void Chain::solve_all(std::vector<SolveOutcome>& outcomes) {
  outcomes.resize(solves.size());
  if (solves.empty()) {
    evaluate();  // every solve ends with a full evaluation at the parameters it leaves; without solves, this one
    return;
  }
  // A failed solve has no value: the result echoing its unknown says NaN, not the bracket end the solver tried
  // last, which would pass for a real result. Set after every evaluation, since each one rewrites the echoes.
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
