#include "radchain/spectrum_csv.hpp"
#include "radchain/strings.hpp"

#include "radchain/error.hpp"
#include "radchain/input_file.hpp"
#include "radchain/units.hpp"

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace radchain {
namespace {
using strings::split;
using strings::trimmed;

constexpr std::string_view blanks = " \t\r";  // a line's blanks (a CRLF file's \r too)


bool has_letter(const std::string& token) {
  for (char c : token)
    if (std::isalpha(static_cast<unsigned char>(c))) return true;
  return false;
}

// The unit carried by the end of a column name: the longest run of trailing '_'-separated tokens (leaving at
// least one token for the quantity's name) that udunits reads as a unit. "W_m-2_nm-1" -> "W m-2 nm-1";
// a leading "per" reads as a reciprocal: "alpha_per_cm" -> "1/(cm)". Empty when there is none.
std::string unit_of_column(const std::string& column) {
  const std::vector<std::string> tokens = split(column, '_');
  for (std::size_t first = 1; first < tokens.size(); ++first) {
    bool plausible = true;
    for (std::size_t i = first; i < tokens.size(); ++i) plausible = plausible && has_letter(tokens[i]);
    if (!plausible) continue;
    std::string unit;
    bool reciprocal = tokens[first] == "per";
    for (std::size_t i = first + (reciprocal ? 1 : 0); i < tokens.size(); ++i) unit += (unit.empty() ? "" : " ") + tokens[i];
    if (unit.empty()) continue;
    if (reciprocal) unit = "1/(" + unit + ")";
    if (units::parses(unit)) return unit;
  }
  return {};
}

}  // namespace

SpectrumFile load_spectrum_csv(const std::string& path, const std::string& expected_si_unit,
                               Extrapolation extrapolation) {
  auto fail = [&](int line, const std::string& problem, int column = 0) -> InputError {
    return InputError(SourceLocation{path, line, column}, "spectrum file", "", problem);
  };
  // A sensor file may name any readable file; a spectrum is a few thousand rows, never a device, a FIFO or
  // gigabytes: checked before opening, and per line below (a file that grows while read).
  std::ifstream in = open_input_file(path, "spectrum file", max_table_file_bytes);
  constexpr int max_rows = 1000000;
  constexpr std::size_t max_line = 4096;

  SpectrumFile out;
  std::string line;
  int line_number = 0;
  bool at_most_one = false;
  bool have_header = false;
  double wavelength_factor = 1.0, value_factor = 1.0;
  std::vector<double> wavelengths, values;
  while (std::getline(in, line)) {
    ++line_number;
    if (line_number > max_rows) throw fail(line_number, fmt::format("more than {} lines", max_rows));
    if (line.size() > max_line) throw fail(line_number, fmt::format("a line of {} characters: at most {}", line.size(), max_line));
    const std::string text = trimmed(line, blanks);
    if (text.empty()) throw fail(line_number, "blank line (the format has none)");
    if (text.front() == '#') {
      if (have_header) throw fail(line_number, "comment after the header line");
      out.provenance += text + "\n";
      continue;
    }
    const std::vector<std::string> fields = split(text, ',');
    if (fields.size() != 2)
      throw fail(line_number, "expected 2 comma-separated columns, found " + std::to_string(fields.size()));
    if (!have_header) {
      if (out.provenance.empty())
        throw fail(line_number, "no provenance: the file must start with '#' comment lines saying where the data come from");
      const std::string wl = trimmed(fields[0], blanks);
      if (wl.rfind("wavelength_", 0) != 0)
        throw fail(line_number, "no unit header: the first column must be named wavelength_<unit>, e.g. wavelength_nm");
      try {
        wavelength_factor = units::conversion(wl.substr(11), "m").factor;
      } catch (const std::exception&) {
        throw fail(line_number, "wavelength column unit \"" + wl.substr(11) + "\" is not a length");
      }
      out.value_column = trimmed(fields[1], blanks);
      // Passive optics and a quantum efficiency cannot exceed 1 (a transmittance of 5 would read 1.7 mag deeper).
      for (const char* bounded : {"transmittance", "throughput", "quantum_efficiency"})
        at_most_one = at_most_one || out.value_column.rfind(bounded, 0) == 0;
      const std::string unit = unit_of_column(out.value_column);
      const bool dimensionless_expected = units::dimension_of(expected_si_unit) == "1";
      if (unit.empty() && !dimensionless_expected) {
        std::string example = out.value_column + "_" + expected_si_unit;  // the column named with its SI unit
        for (char& c : example) c = c == ' ' ? '_' : c;
        throw fail(line_number, "no unit in the header's value column \"" + out.value_column + "\": expected " +
                                    units::dimension_name(expected_si_unit) + ", e.g. " + example);
      }
      try {
        value_factor = units::conversion(unit.empty() ? "1" : unit, expected_si_unit).factor;
      } catch (const std::exception&) {
        throw fail(line_number, "value column \"" + out.value_column + "\" is in " + unit + ": expected " +
                                    units::dimension_name(expected_si_unit));
      }
      have_header = true;
      continue;
    }
    double w = 0, v = 0;
    try {
      std::size_t used_w = 0, used_v = 0;
      const std::string ws = trimmed(fields[0], blanks), vs = trimmed(fields[1], blanks);
      w = std::stod(ws, &used_w);
      v = std::stod(vs, &used_v);
      if (used_w != ws.size() || used_v != vs.size()) throw std::invalid_argument("trailing");
    } catch (const std::exception&) {
      throw fail(line_number, "\"" + text + "\" is not two numbers");
    }
    if (!std::isfinite(w) || !std::isfinite(v)) throw fail(line_number, "non-finite number");
    // std::stod reads hexadecimal floats too ("0x10" is 16): a table is decimal, and a hex cell is a corrupted one.
    if (fields[0].find_first_of("xX") != std::string::npos || fields[1].find_first_of("xX") != std::string::npos)
      throw fail(line_number, "\"" + text + "\" is not two decimal numbers (hexadecimal is not accepted)");
    const int value_column = static_cast<int>(line.find(',')) + 2;  // 1-based, after the comma
    if (!(w > 0)) throw fail(line_number, "wavelength " + trimmed(fields[0], blanks) + " is not positive", 1);
    // Every spectrum is a non-negative physical quantity (an emission, a response, a transmittance, an absorption
    // coefficient): a negative cell would be integrated as light taken away.
    if (v < 0)
      throw fail(line_number, "value " + trimmed(fields[1], blanks) + " is negative: a spectrum, response or transmittance is ≥ 0", value_column);
    if (v > 1 && at_most_one)
      throw fail(line_number, "value " + trimmed(fields[1], blanks) + " is above 1: a " + out.value_column + " cannot exceed 1", value_column);
    if (!wavelengths.empty() && !(w * wavelength_factor > wavelengths.back()))
      throw fail(line_number, "wavelengths must be strictly increasing (" + trimmed(fields[0], blanks) + " follows a larger or equal one)");
    wavelengths.push_back(w * wavelength_factor);
    values.push_back(v * value_factor);
  }
  if (!have_header) throw fail(line_number, "no header line (wavelength_<unit>,<quantity>_<unit>)");
  if (wavelengths.size() < 2) throw fail(line_number, "fewer than 2 data rows");
  out.spectrum = Spectrum(Eigen::Map<Eigen::ArrayXd>(wavelengths.data(), static_cast<Eigen::Index>(wavelengths.size())),
                          Eigen::Map<Eigen::ArrayXd>(values.data(), static_cast<Eigen::Index>(values.size())),
                          expected_si_unit, extrapolation);
  return out;
}

const SpectrumFile& cached_spectrum_csv(const std::string& path, const std::string& expected_si_unit,
                                        Extrapolation extrapolation) {
  static std::mutex mutex;
  static std::map<std::tuple<std::string, std::string, int>, SpectrumFile> cache;
  std::lock_guard lock(mutex);
  const auto key = std::make_tuple(path, expected_si_unit, static_cast<int>(extrapolation));
  auto it = cache.find(key);
  if (it == cache.end()) it = cache.emplace(key, load_spectrum_csv(path, expected_si_unit, extrapolation)).first;
  return it->second;
}

}  // namespace radchain
