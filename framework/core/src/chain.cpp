#include "radchain/chain.hpp"

#include "radchain/error.hpp"
#include "radchain/units.hpp"

#include <boost/math/tools/roots.hpp>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <string_view>

namespace radchain {

bool Report::all_passed() const {
  for (const auto& s : solves)
    if (!s.converged) return false;
  for (const auto& e : expectations)
    if (!e.passed) return false;
  return true;
}

std::optional<double> Report::value(const std::string& name) const {
  for (std::size_t i = 0; i < results.size(); ++i)
    if (results[i].name == name) return values[i];
  return std::nullopt;
}

void Chain::invalidate_spectra() {
  spectral_from_ = 0;
  scalar_from_ = 0;
}

void Chain::prepare_from(std::size_t first) {
  light_before_.resize(stages.size());
  light_ = first == 0 ? Light{} : light_before_[first];
  for (std::size_t k = first; k < stages.size(); ++k) {
    StageSlot& slot = stages[k];
    light_before_[k] = light_;
    Context context(results_, light_, slot.section, slot.plugin, Detail::full, &slot.declarations, &slot.lookups);
    slot.stage->prepare(context);
  }
  spectral_from_ = stages.size();
}

void Chain::evaluate_from(std::size_t first, Detail detail) {
  scales_before_.resize(stages.size());
  const Scales start = first == 0 ? Scales{} : scales_before_[first];
  light_.illumination_scale = start.illumination;
  light_.signal.scale = start.signal;
  light_.background.scale = start.background;
  light_.up_path_scale = start.up_path;
  for (std::size_t k = first; k < stages.size(); ++k) {
    scales_before_[k] = Scales{light_.illumination_scale, light_.signal.scale, light_.background.scale, light_.up_path_scale};
    StageSlot& slot = stages[k];
    Context context(results_, light_, slot.section, slot.plugin, detail);
    slot.stage->evaluate(context);
  }
  for (const ResolvedSolve& r : resolved_)
    if (r.echo != SIZE_MAX) results_.set(r.echo, r.unknown.value());
  scalar_from_ = stages.size();
  ++scalar_version_;
  if (detail == Detail::essential) essential_from_ = std::min(essential_from_, first);
  else if (first <= essential_from_) essential_from_ = SIZE_MAX;
}

void Chain::set_lanes(const ParameterRef& parameter, const Lanes& values) {
  if (parameter.spectral_)
    throw std::logic_error("a spectral parameter cannot differ between lanes (the spectral phase is shared)");
  for (std::size_t i = 0; i < lane_slots_.size(); ++i)
    if (lane_slots_[i].address == parameter.value_) {
      lane_parameters_[i].values = values;
      return;
    }
  lane_parameters_.push_back(LaneParameter{parameter.value_, values});
  lane_slots_.push_back(LaneSlot{parameter.value_, parameter.stage_});
}

void Chain::evaluate_lanes(Detail detail) {
  evaluate(Detail::full);  // the scalar phase up to date: the lanes start from its results
  std::size_t first = stages.size();
  for (const LaneSlot& s : lane_slots_) first = std::min(first, s.stage);
  if (lane_base_version_ != scalar_version_ || lane_results_.size() != results_.size()) {
    lane_results_.resize(results_.size());
    for (std::size_t id = 0; id < results_.size(); ++id) lane_results_[id] = constant_lanes(results_.value(id));
    lane_base_version_ = scalar_version_;
  }
  if (first < stages.size()) {
    const Scales& start = scales_before_[first];
    lane_scales_ = LaneScales{constant_lanes(start.illumination), constant_lanes(start.signal),
                              constant_lanes(start.background), constant_lanes(start.up_path)};
  }
  for (std::size_t k = first; k < stages.size(); ++k) {
    LaneContext context(lane_results_, light_, lane_scales_, lane_parameters_, detail == Detail::full);
    if (!stages[k].stage->evaluate_lanes(context)) evaluate_lane_by_lane(stages[k], detail);
  }
  for (const ResolvedSolve& r : resolved_)
    if (r.echo != SIZE_MAX) {
      lane_results_[r.echo] = constant_lanes(r.unknown.value());
      for (const LaneParameter& p : lane_parameters_)
        if (p.address == r.unknown.value_) lane_results_[r.echo] = p.values;
    }
}

// The scalar evaluate() once per lane, with that lane's parameters, upstream results and scales in the scalar
// slots; everything scalar is put back afterwards, so the scalar phase stays valid.
void Chain::evaluate_lane_by_lane(StageSlot& slot, Detail detail) {
  saved_values_ = results_.values();
  const Light saved_light = light_;
  std::vector<double> saved_parameters;
  for (const LaneSlot& s : lane_slots_) saved_parameters.push_back(*s.address);
  for (int lane = 0; lane < lane_count; ++lane) {
    for (std::size_t i = 0; i < lane_slots_.size(); ++i) *lane_slots_[i].address = lane_parameters_[i].values(lane);
    for (std::size_t id = 0; id < results_.size(); ++id) results_.set(id, lane_results_[id](lane));
    light_.illumination_scale = lane_scales_.illumination(lane);
    light_.signal.scale = lane_scales_.signal(lane);
    light_.background.scale = lane_scales_.background(lane);
    light_.up_path_scale = lane_scales_.up_path(lane);
    Context context(results_, light_, slot.section, slot.plugin, detail);
    slot.stage->evaluate(context);
    for (ResultId id : slot.declarations) lane_results_[id](lane) = results_.value(id);
    lane_scales_.illumination(lane) = light_.illumination_scale;
    lane_scales_.signal(lane) = light_.signal.scale;
    lane_scales_.background(lane) = light_.background.scale;
    lane_scales_.up_path(lane) = light_.up_path_scale;
  }
  for (std::size_t i = 0; i < lane_slots_.size(); ++i) *lane_slots_[i].address = saved_parameters[i];
  results_.restore(saved_values_);
  light_ = saved_light;
}

void Chain::evaluate(Detail detail) {
  std::size_t first = scalar_from_;
  if (spectral_from_ < stages.size()) {
    first = std::min(first, spectral_from_);
    prepare_from(spectral_from_);
  }
  if (detail == Detail::full) first = std::min(first, essential_from_);
  if (first < stages.size()) evaluate_from(first, detail);
}

// Name equality without a call into libc, and lookups without temporary strings (sweeps and solves resolve their
// solved unknowns by name at every evaluation.
static bool same_name(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i] != b[i]) return false;
  return true;
}

StageSlot& Chain::slot(const std::string& section) {
  for (auto& s : stages)
    if (same_name(s.section, section)) return s;
  throw std::out_of_range("no section \"" + section + "\"");
}

ParameterRef Chain::parameter(const std::string& qualified_key) {
  const auto dot = qualified_key.rfind('.');
  if (dot == std::string::npos) throw std::out_of_range("\"" + qualified_key + "\" is not <section>.<key>");
  const std::string_view section(qualified_key.data(), dot);
  const std::string_view key(qualified_key.data() + dot + 1, qualified_key.size() - dot - 1);
  StageSlot* s = nullptr;
  std::size_t index = 0;
  for (; index < stages.size(); ++index)
    if (same_name(stages[index].section, section)) {
      s = &stages[index];
      break;
    }
  if (!s) throw std::out_of_range("no section \"" + std::string(section) + "\"");
  Params::Entry* found = nullptr;
  for (auto& e : s->params->entries())
    if (same_name(e.spec->key, key)) {
      found = &e;
      break;
    }
  Params::Entry& entry = found ? *found : s->params->entry(std::string(key));  // (throws the schema's message)
  const ParamType type = entry.spec->type;
  if (type != ParamType::quantity && type != ParamType::number && type != ParamType::integer)
    throw std::out_of_range("\"" + qualified_key + "\" is not a numeric parameter");
  entry.present = true;
  ParameterRef ref;
  ref.value_ = &entry.number;
  ref.stage_ = index;
  ref.spectral_ = entry.spec->spectral;
  return ref;
}

void Chain::set(const ParameterRef& parameter, double value_si) {
  *parameter.value_ = value_si;
  scalar_from_ = std::min(scalar_from_, parameter.stage_);
  if (parameter.spectral_) spectral_from_ = std::min(spectral_from_, parameter.stage_);
}

double Chain::result(const std::string& name) const {
  if (auto id = results_.find(name)) return results_.value(*id);
  throw std::out_of_range("no result \"" + name + "\"");
}

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
    for (const auto& name : solves[i].criteria) r.margins.push_back(*results_.find("criteria." + name + ".margin"));
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
  if (solves.size() == 1) {
    solve(0, outcomes[0]);
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
}

Report Chain::run() {
  results_.clear_values();
  scalar_from_ = 0;  // every result again (the spectral phase only if something spectral changed)
  evaluate();
  Report report;
  report.sensor_file = sensor_file;
  report.sensor_name = sensor_name;
  solve_all(report.solves);
  report.results.reserve(results_.size());
  for (std::size_t i = 0; i < results_.size(); ++i) {
    report.results.push_back(results_.info(i));
    report.values.push_back(results_.value(i));
  }
  for (const auto& e : expected) {
    ExpectationOutcome outcome{e, std::numeric_limits<double>::quiet_NaN(), false, false};
    if (auto id = results_.find(e.result)) {
      outcome.found = true;
      outcome.computed_si = results_.value(*id);
      const double reference = e.follows_si.value_or(e.value_si);  // an erratum is checked against what follows
      const double difference = std::abs(outcome.computed_si - reference);
      const double allowed = std::max(e.tolerance_si, e.rel_tolerance * std::abs(reference));
      outcome.passed = difference <= allowed;
    }
    report.expectations.push_back(outcome);
  }
  return report;
}

}  // namespace radchain
