// Input distributions (radchain/distribution.hpp): their moments and quantiles, and the parser shared by
// `radchain uncertainty --vary` and the sensor file's [uncertainty] section.
#include "radchain/distribution.hpp"

#include "radchain/error.hpp"
#include "radchain/units.hpp"

#include <boost/math/special_functions/erf.hpp>
#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <numbers>

namespace radchain {
namespace {

const double nan = std::numeric_limits<double>::quiet_NaN();

std::string trimmed(const std::string& s) {
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string::npos) return {};
  return s.substr(first, s.find_last_not_of(" \t") - first + 1);
}

}  // namespace

double Distribution::mean() const {
  switch (kind) {
    case Kind::normal: return a;
    case Kind::uniform: return (a + b) / 2;
    case Kind::lognormal: return a;
    case Kind::triangular: return (a + b + c) / 3;
  }
  return nan;
}

double Distribution::sd() const {
  switch (kind) {
    case Kind::normal: return b;
    case Kind::uniform: return (b - a) / std::sqrt(12.0);
    case Kind::lognormal: return b;
    case Kind::triangular: return std::sqrt((a * a + b * b + c * c - a * b - a * c - b * c) / 18);
  }
  return nan;
}

double Distribution::quantile(double u) const {
  // Φ⁻¹(u) = −√2 erfc⁻¹(2u)
  auto z = [](double p) { return -std::numbers::sqrt2 * boost::math::erfc_inv(2 * p); };
  switch (kind) {
    case Kind::normal: return a + b * z(u);
    case Kind::uniform: return a + (b - a) * u;
    case Kind::lognormal: {
      const double s2 = std::log1p((b / a) * (b / a));
      return std::exp(std::log(a) - s2 / 2 + std::sqrt(s2) * z(u));
    }
    case Kind::triangular: {  // lo a, mode b, hi c
      const double f = (b - a) / (c - a);
      return u < f ? a + std::sqrt(u * (c - a) * (b - a)) : c - std::sqrt((1 - u) * (c - a) * (c - b));
    }
  }
  return nan;
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
    const std::string near = nearest_match(key, keys);
    throw fail(fmt::format("{} has no real-valued parameter \"{}\"{}", slot->params->context(), key.substr(dot + 1),
                           near.empty() ? "" : " (did you mean \"" + near + "\"?)"));
  }
  const ParamSpec& spec = *entry->spec;
  if (spec.spectral) throw fail(key + " is spectral: vary it with a sweep instead");
  for (const auto& s : chain.solves)
    if (s.unknown == key) throw fail("a [[solve]] determines " + key + " (add --no-solve to vary it)");

  VariedInput v;
  v.key = key;
  v.as_written = spec_text;
  v.unit = spec.type == ParamType::quantity ? spec.si_unit : "1";
  const auto open = spec_text.find('(');
  if (open == std::string::npos || spec_text.back() != ')')
    throw fail("expected normal(mean, sd), uniform(lo, hi), lognormal(mean, sd) or triangular(lo, mode, hi)");
  const std::string name = trimmed(spec_text.substr(0, open));
  std::vector<std::string> args;
  {
    const std::string inner = spec_text.substr(open + 1, spec_text.size() - open - 2);
    std::size_t start = 0;
    for (std::size_t at; (at = inner.find(',', start)) != std::string::npos; start = at + 1) args.push_back(trimmed(inner.substr(start, at - start)));
    args.push_back(trimmed(inner.substr(start)));
  }
  std::size_t arity = 2;
  if (name == "normal") v.distribution.kind = Distribution::Kind::normal;
  else if (name == "uniform") v.distribution.kind = Distribution::Kind::uniform;
  else if (name == "lognormal") v.distribution.kind = Distribution::Kind::lognormal;
  else if (name == "triangular") v.distribution.kind = Distribution::Kind::triangular, arity = 3;
  else {
    const std::string near = nearest_match(name, {"normal", "uniform", "lognormal", "triangular"});
    throw fail(fmt::format("unknown distribution \"{}\"{}: normal, uniform, lognormal or triangular", name,
                           near.empty() ? "" : " (did you mean \"" + near + "\"?)"));
  }
  if (args.size() != arity) throw fail(fmt::format("{} takes {} values, {} given", name, arity, args.size()));
  const bool dimensionless = spec.type != ParamType::quantity || units::dimension_of(spec.si_unit) == "1";
  double values[3] = {0, 0, 0};
  for (std::size_t i = 0; i < arity; ++i) {
    units::ParsedQuantity q;
    try {
      q = units::split_quantity(args[i]);
    } catch (const std::invalid_argument&) {
      throw fail(fmt::format("\"{}\" does not start with a number", args[i]));
    }
    if (!std::isfinite(q.number)) throw fail(fmt::format("\"{}\" is not finite", args[i]));
    if (q.unit.empty() && !dimensionless)
      throw fail(fmt::format("\"{}\" has no unit: expected {}", args[i], units::dimension_name(spec.si_unit)));
    double factor = 1;
    try {
      factor = units::conversion(q.unit.empty() ? "1" : q.unit, spec.type == ParamType::quantity ? spec.si_unit : "1").factor;
    } catch (const std::invalid_argument&) {
      throw fail(fmt::format("\"{}\": unknown unit", args[i]));
    } catch (const std::domain_error&) {
      throw fail(fmt::format("\"{}\": wrong unit, expected {}", args[i], dimensionless ? std::string("a plain number") : units::dimension_name(spec.si_unit)));
    }
    values[i] = q.number * factor;
  }
  Distribution& d = v.distribution;
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
  if (!spec.in_range(d.mean()))
    throw fail(fmt::format("its mean {:g} {} is out of range: accepted {}", d.mean(), v.unit, spec.range_text()));
  return v;
}

}  // namespace radchain
