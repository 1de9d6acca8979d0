#include "radchain/units.hpp"

#include <udunits2.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>

namespace radchain::units {
namespace {

// udunits is not thread-safe; every call goes through this lock (units are parsed while loading files,
// never inside evaluations).
std::mutex& registry_mutex() {
  static std::mutex m;
  return m;
}

struct Registry {
  ut_system* system = nullptr;
  Registry() {
    ut_set_error_message_handler(ut_ignore);
    system = ut_read_xml(nullptr);
    if (!system) throw std::runtime_error("udunits2: cannot read its unit database (set UDUNITS2_XML_PATH)");
    // Electron counts: a base dimension of their own, so "e-" never means coulomb.
    ut_unit* electron = ut_new_base_unit(system);
    ut_map_name_to_unit("electron", UT_ASCII, electron);
    ut_map_name_to_unit("electrons", UT_ASCII, electron);
    ut_map_unit_to_name(electron, "electron", UT_ASCII);
    ut_free(electron);  // the maps hold their own copies; ours would leak (LeakSanitizer)
    alias("deg", "arc_degree");
    alias("AU", "astronomical_unit");
    alias("lp", "1");  // line pairs (cycles) per length are counted as plain reciprocal lengths
    alias("cy", "1");
    alias("DN", "1");  // digital numbers (ADC counts): a system gain K is given in DN/e- (EMVA 1288)
    alias("ADU", "1");  // analogue-to-digital units: the astronomers' name for the same counts ("1.6 e-/ADU")
  }
  void alias(const char* symbol, const char* target) {
    ut_unit* unit = ut_parse(system, target, UT_ASCII);
    ut_map_symbol_to_unit(symbol, UT_ASCII, unit);
    ut_free(unit);  // the map holds a copy
  }
};

Registry& registry() {
  static Registry r;  // lives for the process; udunits' own atexit handling is not needed
  return r;
}

// "e-" (electron) is not udunits syntax: rewrite it as the electron unit before parsing, where it stands
// alone as a factor: at the start or after one of " *./(", and at the end or before one of " *./)^".
// (A hand-written scan rather than std::regex: GCC 12 warns inside <regex> under -fsanitize, which breaks
// the -Werror sanitizer build.)
std::string preprocess(const std::string& unit) {
  auto separates = [](char c, const char* others) {
    return std::isspace(static_cast<unsigned char>(c)) || (c != '\0' && std::strchr(others, c) != nullptr);
  };
  std::string out;
  out.reserve(unit.size() + 8);
  for (std::size_t i = 0; i < unit.size(); ++i) {
    const bool starts = i == 0 || separates(unit[i - 1], "*/.(");
    const bool ends = i + 2 == unit.size() || (i + 2 < unit.size() && separates(unit[i + 2], "*/.)^"));
    if (unit[i] == 'e' && i + 1 < unit.size() && unit[i + 1] == '-' && starts && ends) {
      out += "electron";
      ++i;
    } else {
      out += unit[i];
    }
  }
  return out;
}

struct UnitDeleter {
  void operator()(ut_unit* u) const { ut_free(u); }
};
using UnitPtr = std::unique_ptr<ut_unit, UnitDeleter>;

// A factor of zero ("m 0A", "W/0.0sr", "m.0X") is never a unit, and udunits2 (2.2.28) leaks the name that
// follows it when it refuses one (its parser drops the lexer's copy; found by tests/fuzz/overrides_fuzz and
// spectrum_csv_fuzz). Refused here first.
// A numeric factor can start at the string's start, after a space, '*', '/' or '(', or after a '.' that
// multiplies (udunits reads "kg.m" as kg·m): one after a name, or after an exponent ("m2.0" is m²·0), but not
// the decimal point of a number ("2.0").
bool factor_starts_at(const std::string& unit, std::size_t i) {
  if (i == 0) return true;
  const char before = unit[i - 1];
  if (std::isspace(static_cast<unsigned char>(before)) || std::strchr("*/(", before)) return true;
  if (before != '.') return false;
  std::size_t digits = i - 1;  // the digits just before the '.'
  while (digits > 0 && std::isdigit(static_cast<unsigned char>(unit[digits - 1]))) --digits;
  if (digits == i - 1) return true;                            // no digits: a name or ')' before the '.'
  return digits > 0 && std::isalpha(static_cast<unsigned char>(unit[digits - 1]));  // an exponent
}

bool has_zero_factor(const std::string& unit) {
  for (std::size_t i = 0; i < unit.size(); ++i) {
    const bool sign = (unit[i] == '-' || unit[i] == '+') && i + 1 < unit.size();  // "-0" is a zero too
    const char first = sign ? unit[i + 1] : unit[i];
    if (!factor_starts_at(unit, i) || !(std::isdigit(static_cast<unsigned char>(first)) || first == '.')) continue;
    char* end = nullptr;
    const double factor = std::strtod(unit.c_str() + i, &end);
    if (end != unit.c_str() + i && factor == 0) return true;
  }
  return false;
}

UnitPtr parse_locked(const std::string& text) {
  const std::string prepared = preprocess(text);
  if (has_zero_factor(prepared)) throw std::invalid_argument("unknown unit \"" + text + "\"");
  ut_unit* unit = ut_parse(registry().system, prepared.c_str(), UT_UTF8);
  if (!unit) throw std::invalid_argument("unknown unit \"" + text + "\"");
  return UnitPtr(unit);
}

// The dimension as base units with exponents, scale dropped: "1e-06 m" -> "m".
std::string signature_locked(const ut_unit* unit) {
  char buffer[256];
  const int n = ut_format(unit, buffer, sizeof buffer, UT_ASCII | UT_DEFINITION | UT_NAMES);
  if (n < 0 || n >= static_cast<int>(sizeof buffer)) throw std::invalid_argument("unit too complex");
  std::string text(buffer, static_cast<std::size_t>(n));
  // Drop a leading numeric scale and an optional offset description.
  std::size_t i = 0;
  while (i < text.size() && (std::isdigit(static_cast<unsigned char>(text[i])) || text[i] == '.' ||
                             text[i] == 'e' || text[i] == '-' || text[i] == '+')) {
    // stop if this 'e' starts a unit name like "electron"
    if (text[i] == 'e' && i + 1 < text.size() && std::isalpha(static_cast<unsigned char>(text[i + 1]))) break;
    ++i;
  }
  while (i < text.size() && text[i] == ' ') ++i;
  return i < text.size() ? text.substr(i) : std::string("1");
}

// udunits2 parses a unit string in ~10 µs (a catalogue of 1,000 files spends a third of its time there); the
// answers for a unit string never change, so they are remembered. Bounded: a hostile file of distinct unit strings
// empties the memo instead of growing it. Failures are not remembered (they throw, once per bad input).
constexpr std::size_t memo_limit = 4096;
std::map<std::string, std::string>& dimension_memo() {
  static std::map<std::string, std::string> memo;
  return memo;
}
std::map<std::pair<std::string, std::string>, double>& conversion_memo() {
  static std::map<std::pair<std::string, std::string>, double> memo;
  return memo;
}

}  // namespace

std::string dimension_of(const std::string& unit) {
  std::lock_guard lock(registry_mutex());
  auto& memo = dimension_memo();
  if (auto it = memo.find(unit); it != memo.end()) return it->second;
  UnitPtr u = parse_locked(unit);
  std::string signature = signature_locked(u.get());
  if (memo.size() >= memo_limit) memo.clear();
  memo.emplace(unit, signature);
  return signature;
}

bool parses(const std::string& unit) {
  try {
    dimension_of(unit);
    return true;
  } catch (const std::invalid_argument&) {
    return false;
  }
}

Conversion conversion(const std::string& unit, const std::string& si_unit) {
  std::lock_guard lock(registry_mutex());
  auto& memo = conversion_memo();
  const auto key = std::make_pair(unit, si_unit);
  if (auto it = memo.find(key); it != memo.end()) return Conversion{it->second};
  UnitPtr from = parse_locked(unit.empty() ? "1" : unit);
  UnitPtr to = parse_locked(si_unit.empty() ? "1" : si_unit);
  if (signature_locked(from.get()) != signature_locked(to.get()) || !ut_are_convertible(from.get(), to.get()))
    throw std::domain_error("\"" + unit + "\" is not convertible to \"" + si_unit + "\"");
  cv_converter* converter = ut_get_converter(from.get(), to.get());
  if (!converter) throw std::domain_error("no conversion from \"" + unit + "\" to \"" + si_unit + "\"");
  const double zero = cv_convert_double(converter, 0.0);
  const double one = cv_convert_double(converter, 1.0);
  cv_free(converter);
  if (std::abs(zero) > 1e-12 * std::abs(one))
    throw std::domain_error("\"" + unit + "\" has an offset (use kelvin for temperatures)");
  if (memo.size() >= memo_limit) memo.clear();
  memo.emplace(key, one);
  return Conversion{one};
}

std::string dimension_name(const std::string& si_unit) {
  static const std::map<std::string, std::string> names = {
      {"m", "a length"},
      {"s", "a time"},
      {"Hz", "a frequency"},
      {"s-1", "a rate"},
      {"K", "a temperature"},
      {"rad", "an angle"},
      {"sr", "a solid angle"},
      {"m2", "an area"},
      {"m-1", "a spatial frequency (reciprocal length)"},
      {"m/s", "a speed"},
      {"W m-2", "an irradiance"},
      {"J m-2", "an exposure (energy per area)"},
      {"W m-2 sr-1", "a radiance"},
      {"W m-2 m-1", "a spectral irradiance"},
      {"W m-2 sr-1 m-1", "a spectral radiance"},
      {"lx", "an illuminance"},
      {"electron", "an electron count"},
      {"electron/s", "an electron rate"},
      {"electron-1", "a system gain in DN/e- (or its reciprocal in e-/DN)"},
      {"1", "a dimensionless number"},
  };
  auto it = names.find(si_unit);
  if (it != names.end()) return it->second;
  return "a quantity in " + si_unit;
}

std::optional<double> reciprocal_conversion(const std::string& unit, const std::string& si_unit) {
  // Only a system gain: EMVA 1288 states K in DN/e-, astronomers the conversion factor 1/K in e-/ADU, and a value in
  // either reads unambiguously. Elsewhere (a time for a frequency, say) a reciprocal is far more likely a mistake.
  if (si_unit != "electron-1" || unit.empty()) return std::nullopt;
  try {
    return conversion(unit, "electron").factor;
  } catch (const std::invalid_argument&) {
    return std::nullopt;
  } catch (const std::domain_error&) {
    return std::nullopt;
  }
}

ParsedQuantity split_quantity(const std::string& text) {
  const char* begin = text.c_str();
  while (*begin == ' ' || *begin == '\t') ++begin;
  char* end = nullptr;
  const double number = std::strtod(begin, &end);
  if (end == begin || !std::isfinite(number)) throw std::invalid_argument("no number");
  std::string unit(end);
  const auto first = unit.find_first_not_of(" \t");
  const auto last = unit.find_last_not_of(" \t");
  unit = first == std::string::npos ? std::string() : unit.substr(first, last - first + 1);
  return ParsedQuantity{number, unit, std::string(begin, static_cast<const char*>(end))};
}

double to_si(double number, double factor) {
  static const double powers[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                  1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};  // exact
  for (int k = 1; k <= 22; ++k) {
    if (factor == powers[k]) return number * powers[k];
    if (factor == 1.0 / powers[k]) return number / powers[k];  // 1/10^k as the literal 1e-k is: the nearest double
  }
  return number * factor;
}

double to_si(const ParsedQuantity& quantity, double factor) {
  const double computed = to_si(quantity.number, factor);
  if (factor == 1.0 || quantity.number_text.empty()) return computed;
  const int k = static_cast<int>(std::lround(std::log10(factor)));
  if (k < -300 || k > 300 || factor != std::strtod(("1e" + std::to_string(k)).c_str(), nullptr)) return computed;
  std::string mantissa = quantity.number_text;
  long exponent = 0;
  if (const auto e = mantissa.find_first_of("eE"); e != std::string::npos) {
    char* end = nullptr;
    exponent = std::strtol(mantissa.c_str() + e + 1, &end, 10);
    if (*end != '\0') return computed;  // not a plain decimal exponent
    mantissa.resize(e);
  }
  if (mantissa.find_first_of("xXnNiI") != std::string::npos) return computed;  // hex, nan, inf: not decimal text
  const std::string shifted = mantissa + "e" + std::to_string(exponent + k);
  char* end = nullptr;
  const double value = std::strtod(shifted.c_str(), &end);
  return *end == '\0' && std::isfinite(value) ? value : computed;
}

}  // namespace radchain::units
