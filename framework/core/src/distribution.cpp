// Input distributions (radchain/distribution.hpp): their moments and quantiles, and the parser shared by
// `radchain uncertainty --vary` and the sensor file's [uncertainty] section.
#include "radchain/distribution.hpp"
#include "radchain/strings.hpp"

#include "radchain/error.hpp"
#include "radchain/physics/detection.hpp"
#include "radchain/units.hpp"

#include <boost/math/quadrature/tanh_sinh.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace radchain {
namespace {
using strings::trimmed;


const double nan = std::numeric_limits<double>::quiet_NaN();

}  // namespace

double Distribution::mean() const { return truncated ? truncated_mean : parent_mean(); }

double Distribution::sd() const { return truncated ? truncated_sd : parent_sd(); }

double Distribution::parent_mean() const {
  switch (kind) {
    case Kind::normal: return a;
    case Kind::uniform: return (a + b) / 2;
    case Kind::lognormal: return a;
    case Kind::triangular: return (a + b + c) / 3;
  }
  return nan;
}

double Distribution::parent_sd() const {
  switch (kind) {
    case Kind::normal: return b;
    case Kind::uniform: return (b - a) / std::sqrt(12.0);
    case Kind::lognormal: return b;
    // √((a² + b² + c² − ab − ac − bc)/18) from the widths: the squares of the values overflow beyond 1e154 and
    // cancel for a narrow law far from 0 (1e8 ± 1: all digits lost).
    case Kind::triangular: return std::hypot(b - a, c - a, c - b) / 6;
  }
  return nan;
}

namespace {
// ln x ~ N(μ, s²) for a log-normal of mean m and sd σ: s² = ln(1 + σ²/m²), μ = ln m − s²/2.
struct LogNormal {
  double mu, s;
};
LogNormal log_normal(double mean, double sd) {
  // ln(1 + r²) as 2 ln r + ln(1 + 1/r²) once r² would overflow (r > 1e154): the law stays finite, not NaN.
  const double r = sd / mean;
  const double s2 = r < 1e150 ? std::log1p(r * r) : 2 * std::log(r) + std::log1p(1 / (r * r));
  return {std::log(mean) - s2 / 2, std::sqrt(s2)};
}
}  // namespace

// Each law in both tails: quantile(u) from the lower-tail probability u = F(x), upper_quantile(q) from the
// upper-tail probability q = 1 − F(x), each accurate where its probability is small (no 1 − p cancellation).
double Distribution::parent_quantile(double u) const {
  using physics::standard_normal_quantile;
  switch (kind) {
    case Kind::normal: return a + b * standard_normal_quantile(u);
    case Kind::uniform: return a + (b - a) * u;
    case Kind::lognormal: {
      const LogNormal l = log_normal(a, b);
      return std::exp(l.mu + l.s * standard_normal_quantile(u));
    }
    case Kind::triangular: {  // lo a, mode b, hi c
      // √(u (c − a)(b − a)) as a product of roots: the product of the widths overflows long before the root does.
      const double f = (b - a) / (c - a);
      return u < f ? a + std::sqrt(u) * std::sqrt(c - a) * std::sqrt(b - a) : c - std::sqrt(1 - u) * std::sqrt(c - a) * std::sqrt(c - b);
    }
  }
  return nan;
}

double Distribution::parent_upper_quantile(double q) const {
  using physics::standard_normal_quantile;
  switch (kind) {
    case Kind::normal: return a - b * standard_normal_quantile(q);
    case Kind::uniform: return b - (b - a) * q;
    case Kind::lognormal: {
      const LogNormal l = log_normal(a, b);
      return std::exp(l.mu - l.s * standard_normal_quantile(q));
    }
    case Kind::triangular: {
      const double f = (c - b) / (c - a);  // the upper tail's share
      return q < f ? c - std::sqrt(q) * std::sqrt(c - a) * std::sqrt(c - b) : a + std::sqrt(1 - q) * std::sqrt(c - a) * std::sqrt(b - a);
    }
  }
  return nan;
}

double Distribution::cdf(double x) const {
  switch (kind) {
    case Kind::normal: return physics::standard_normal_cdf((x - a) / b);
    case Kind::uniform: return std::clamp((x - a) / (b - a), 0.0, 1.0);
    case Kind::lognormal: {
      if (!(x > 0)) return 0;
      const LogNormal l = log_normal(a, b);
      return physics::standard_normal_cdf((std::log(x) - l.mu) / l.s);
    }
    case Kind::triangular:
      if (x <= a) return 0;
      if (x >= c) return 1;
      return x <= b ? (x - a) / (c - a) * ((x - a) / (b - a)) : 1 - (c - x) / (c - a) * ((c - x) / (c - b));
  }
  return nan;
}

double Distribution::survival(double x) const {
  switch (kind) {
    case Kind::normal: return physics::standard_normal_tail((x - a) / b);
    case Kind::uniform: return std::clamp((b - x) / (b - a), 0.0, 1.0);
    case Kind::lognormal: {
      if (!(x > 0)) return 1;
      const LogNormal l = log_normal(a, b);
      return physics::standard_normal_tail((std::log(x) - l.mu) / l.s);
    }
    case Kind::triangular:
      if (x <= a) return 1;
      if (x >= c) return 0;
      return x <= b ? 1 - (x - a) / (c - a) * ((x - a) / (b - a)) : (c - x) / (c - a) * ((c - x) / (c - b));
  }
  return nan;
}

double Distribution::quantile(double u) const {
  if (!truncated) return parent_quantile(u);
  // The parent's quantile over [F(lo), F(hi)], from whichever tail keeps the probability small: for an interval in
  // the upper tail, F(x) rounds to 1 long before x reaches a far hi (hi = 1e9 for "no upper limit"), 1 − F does not.
  const double p = cdf_lo + u * (cdf_hi - cdf_lo);
  double x = 0;
  if (p <= 0.5) {
    x = p > 0 ? parent_quantile(p) : lo;
  } else {
    const double q = survival_hi + (1 - u) * (survival_lo - survival_hi);
    x = q > 0 ? parent_upper_quantile(q) : hi;
  }
  return std::clamp(x, lo, hi);
}

double Distribution::truncate(double lower, double upper) {
  truncated = false;
  lo = lower, hi = upper;
  cdf_lo = cdf(lower), cdf_hi = cdf(upper);
  survival_lo = survival(lower), survival_hi = survival(upper);
  const double probability = cdf_lo > 0.5 ? survival_lo - survival_hi : cdf_hi - cdf_lo;
  if (!(probability >= least_truncated_probability)) return probability;  // refused by the caller: nothing to sample
  truncated = true;
  // Moments of the truncated law as integrals of its quantile over u ∈ (0, 1): E[x] = ∫Q, var = ∫(Q − E[x])². Q is
  // bounded by [lo, hi] but, for an interval reaching far into a tail, steep at an end (Φ⁻¹ near 0): tanh–sinh
  // quadrature (Takahasi & Mori 1974) converges there, where Gauss–Kronrod stalls at ~1e-9.
  const double half_width = hi / 2 - lo / 2;  // finite where hi − lo is not
  if (std::max(std::abs(lo), std::abs(hi)) < 1e100 && half_width < 1e100 && half_width > 1e-100) {
    boost::math::quadrature::tanh_sinh<double> quadrature;
    truncated_mean = quadrature.integrate([&](double u) { return quantile(u); }, 0.0, 1.0, 1e-14);
    truncated_sd = std::sqrt(quadrature.integrate([&](double u) { const double d = quantile(u) - truncated_mean; return d * d; }, 0.0, 1.0, 1e-14));
    return probability;
  }
  // Bounds beyond 1e100 or closer than 1e-100: in doubles, (Q − E[x])² overflows near the largest values (boost then
  // throws an evaluation_error) and underflows for the smallest spreads, and scaling by the interval would underflow
  // a spread of 1 inside ±1e300. The x87 long double's exponent (to 1e±4931) holds all of them.
  static_assert(std::numeric_limits<long double>::max_exponent >= 16384, "squares of doubles need a wider exponent");
  boost::math::quadrature::tanh_sinh<long double> quadrature;
  // u as a double strictly inside (0, 1), as the double quadrature's abscissas are: a long double u within 2⁻⁵⁴ of 1
  // rounds to 1.0, where the quantile is hi (1e300) instead of the tail's limit.
  auto q = [&](long double u) {
    return static_cast<long double>(quantile(std::clamp(static_cast<double>(u), std::numeric_limits<double>::denorm_min(), greatest_u)));
  };
  const long double lower_l = lo, upper_l = hi;
  const long double m = std::clamp(quadrature.integrate(q, 0.0L, 1.0L, 1e-14L), lower_l, upper_l);
  const long double variance = quadrature.integrate([&](long double u) { const long double d = q(u) - m; return d * d; }, 0.0L, 1.0L, 1e-14L);
  truncated_mean = static_cast<double>(m);
  truncated_sd = static_cast<double>(std::min(std::sqrt(variance), static_cast<long double>(half_width)));  // at most half the interval
  return probability;
}

VariedInput parse_varied_input(Chain& chain, const std::string& key, const std::string& spec_text, const SourceLocation& where,
                               const std::string& context) {
  auto fail = [&](const std::string& problem) { return InputError(where, context, context.empty() ? spec_text : key + " = \"" + spec_text + "\"", problem); };
  // The parameter: numeric, real, scalar, not spectral, not solved.
  const auto dot = key.rfind('.');
  const Params::Entry* entry = nullptr;
  const StageSlot* slot = nullptr;
  std::vector<std::string> keys;
  if (dot != std::string::npos)
    for (const auto& s : chain.stages)
      if (s.section == key.substr(0, dot)) {
        slot = &s;
        for (const auto& e : s.params->entries()) {
          if (e.spec->type == ParamType::quantity || e.spec->type == ParamType::number) keys.push_back(s.section + "." + e.spec->key);
          if (e.spec->key == key.substr(dot + 1)) entry = &e;
        }
      }
  if (!entry || (entry->spec->type != ParamType::quantity && entry->spec->type != ParamType::number)) {
    if (!slot) {
      std::vector<std::string> sections;
      for (const auto& s : chain.stages) sections.push_back(s.section);
      throw fail(fmt::format("the sensor file has no section \"{}\"; sections: {}", dot == std::string::npos ? key : key.substr(0, dot),
                             join(sections)));
    }
    throw fail(fmt::format("{} has no real-valued parameter \"{}\"{}", slot->params->context(), key.substr(dot + 1),
                           did_you_mean(key, keys)));
  }
  const ParamSpec& spec = *entry->spec;
  if (spec.spectral) throw fail(key + " is spectral: vary it with a sweep instead");
  for (const auto& s : chain.solves)
    if (s.unknown == key) throw fail("a [[solve]] determines " + key + " (add --no-solve to vary it)");

  VariedInput v;
  v.key = key;
  v.as_written = spec_text;
  v.unit = spec.type == ParamType::quantity ? spec.si_unit : "1";
  const bool dimensionless = spec.type != ParamType::quantity || units::dimension_of(spec.si_unit) == "1";
  // One number with the key's unit ("9 e-"; plain for a dimensionless key), in SI.
  auto value_of = [&](const std::string& text) {
    units::ParsedQuantity q;
    try {
      q = units::split_quantity(text);
    } catch (const std::invalid_argument&) {
      throw fail(fmt::format("\"{}\" does not start with a number", text));
    }
    if (!std::isfinite(q.number)) throw fail(fmt::format("\"{}\" is not finite", text));
    if (q.unit.empty() && !dimensionless)
      throw fail(fmt::format("\"{}\" has no unit: expected {}", text, units::dimension_name(spec.si_unit)));
    double factor = 1;
    try {
      factor = units::conversion(q.unit.empty() ? "1" : q.unit, spec.type == ParamType::quantity ? spec.si_unit : "1").factor;
    } catch (const std::invalid_argument&) {
      throw fail(fmt::format("\"{}\": unknown unit", text));
    } catch (const std::domain_error&) {
      // A law over 1/K is not the same law over K.
      if (units::reciprocal_conversion(q.unit, spec.si_unit))
        throw fail(fmt::format("\"{}\": a distribution of a system gain is stated in DN/e- (a law over e-/DN is another "
                               "law over its reciprocal)", text));
      throw fail(fmt::format("\"{}\": wrong unit, expected {}", text, dimensionless ? std::string("a plain number") : units::dimension_name(spec.si_unit)));
    }
    // A finite number times its unit's factor can still overflow ("1e308 km").
    const double si = q.number * factor;
    if (!std::isfinite(si)) throw fail(fmt::format("\"{}\" is not finite in SI units ({})", text, v.unit));
    return si;
  };
  const std::string expected =
      "expected normal(mean, sd), uniform(lo, hi), lognormal(mean, sd), triangular(lo, mode, hi) or truncated(<one of these>, lo, hi)";
  // "name(arg, arg, ...)": the name and its arguments split at the commas outside parentheses.
  auto call_of = [&](const std::string& text, std::string& name) {
    const auto open = text.find('(');
    if (open == std::string::npos || text.empty() || text.back() != ')') throw fail(expected);
    name = trimmed(text.substr(0, open));
    std::vector<std::string> args;
    const std::string inner = text.substr(open + 1, text.size() - open - 2);
    int depth = 0;
    std::size_t start = 0;
    for (std::size_t i = 0; i < inner.size(); ++i) {
      if (inner[i] == '(') ++depth;
      if (inner[i] == ')' && --depth < 0) throw fail(expected);
      if (inner[i] == ',' && depth == 0) args.push_back(trimmed(inner.substr(start, i - start))), start = i + 1;
    }
    if (depth != 0) throw fail(expected);
    args.push_back(trimmed(inner.substr(start)));
    return args;
  };
  auto parse = [&](const std::string& text) {
    std::string name;
    const std::vector<std::string> args = call_of(text, name);
    Distribution d;
    std::size_t arity = 2;
    if (name == "normal") d.kind = Distribution::Kind::normal;
    else if (name == "uniform") d.kind = Distribution::Kind::uniform;
    else if (name == "lognormal") d.kind = Distribution::Kind::lognormal;
    else if (name == "triangular") d.kind = Distribution::Kind::triangular, arity = 3;
    else {
      throw fail(fmt::format("unknown distribution \"{}\"{}: normal, uniform, lognormal, triangular or truncated", name,
                             did_you_mean(name, {"normal", "uniform", "lognormal", "triangular", "truncated"})));
    }
    if (args.size() != arity) throw fail(fmt::format("{} takes {} values, {} given", name, arity, args.size()));
    double values[3] = {0, 0, 0};
    for (std::size_t i = 0; i < arity; ++i) values[i] = value_of(args[i]);
    d.a = values[0], d.b = values[1], d.c = values[2];
    switch (d.kind) {
      case Distribution::Kind::normal:
        if (!(d.b > 0)) throw fail("the standard deviation must be > 0");
        break;
      case Distribution::Kind::lognormal:
        if (!(d.a > 0) || !(d.b > 0)) throw fail("lognormal(mean, sd) needs mean > 0 and sd > 0");
        break;
      case Distribution::Kind::uniform:
        if (!(d.b > d.a)) throw fail("uniform(lo, hi) needs lo < hi");
        break;
      case Distribution::Kind::triangular:
        if (!(d.a <= d.b && d.b <= d.c && d.a < d.c)) throw fail("triangular(lo, mode, hi) needs lo <= mode <= hi, lo < hi");
        break;
    }
    // The width enters every quantile and probability of these two (hi − lo beyond the largest double: NaN).
    const double width = d.kind == Distribution::Kind::uniform ? d.b - d.a : d.c - d.a;
    if (d.kind != Distribution::Kind::normal && d.kind != Distribution::Kind::lognormal && !std::isfinite(width)) {
      throw fail(fmt::format("{}: hi − lo is beyond the range of a double", name));
    }
    return d;
  };
  std::string name;
  const std::vector<std::string> args = call_of(spec_text, name);
  if (name == "truncated") {
    // truncated(D, lo, hi): D restricted to [lo, hi]. The interval must hold a real share of D's probability, or
    // the samples would be quantiles of rounding noise.
    if (args.size() != 3) throw fail(fmt::format("truncated takes a distribution and two values (lo, hi), {} given", args.size()));
    if (args[0].rfind("truncated", 0) == 0) throw fail("truncated(...) of a truncated distribution: give one interval");
    v.distribution = parse(args[0]);
    const double lower = value_of(args[1]), upper = value_of(args[2]);
    if (!(lower < upper)) throw fail("truncated(D, lo, hi) needs lo < hi");
    const double probability = v.distribution.truncate(lower, upper);
    if (!v.distribution.truncated)
      throw fail(fmt::format("[{}, {}] holds a probability of {:.3g} under {}: at least {:g} is needed", args[1], args[2], probability,
                             args[0], Distribution::least_truncated_probability));
  } else {
    v.distribution = parse(spec_text);
  }
  const Distribution& d = v.distribution;
  // Every sample a finite double (distribution.hpp: the quantile is monotonic, so its ends decide).
  if (!std::isfinite(d.mean()) || !std::isfinite(d.sd()) || !std::isfinite(d.quantile(Distribution::least_u)) ||
      !std::isfinite(d.quantile(Distribution::greatest_u)))
    throw fail(fmt::format("its values reach beyond the range of a double ({:g} {} to {:g} {}, mean {:g}, sd {:g})",
                           d.quantile(Distribution::least_u), v.unit, d.quantile(Distribution::greatest_u), v.unit,
                           d.mean(), d.sd()));
  if (!spec.in_range(d.mean()))
    throw fail(fmt::format("its mean {:g} {} is out of range: accepted {}", d.mean(), v.unit, spec.range_text()));
  return v;
}

}  // namespace radchain
