#include "radchain/spectral_limits.hpp"

#include <fmt/format.h>

#include <filesystem>

namespace radchain {

std::string nm_range(double lo_m, double hi_m) { return fmt::format("{:.1f}-{:.1f} nm", lo_m * 1e9, hi_m * 1e9); }
std::string nm_range(const Spectrum& s) { return nm_range(s.min_wavelength_m(), s.max_wavelength_m()); }

void note_table(Light& light, const Spectrum& table, std::string what) {
  if (table.empty() || table.extrapolation() != Extrapolation::zero) return;
  light.tables.push_back(SpectralTable{table.min_wavelength_m(), table.max_wavelength_m(), table.value()(0) == 0,
                                       table.value()(table.size() - 1) == 0, std::move(what)});
}

void note_table(Light& light, const Params& params, std::string_view key) {
  if (!params.has(key)) return;
  const Params::Entry& entry = params.entry(key);
  // As written in the file; a default has no text there: its file name then.
  const std::string written = !entry.as_written.empty() ? entry.as_written
                                                        : "\"" + std::filesystem::path(entry.text).filename().string() + "\"";
  note_table(light, params.spectrum(key), std::string(key) + " = " + written + " of " + params.context());
}

void require_band_inside_tables(const Params& params, const Light& light, const Spectrum& spectrum, double lo_m,
                                double hi_m, const std::string& lo_key, const std::string& hi_key) {
  // Relative slack of 1e-9: a band edge written as the table's edge in other units may round past it.
  auto check = [&](const SpectralTable& table) {
    const bool below = lo_m < table.min_m * (1 - 1e-9) && !table.zero_at_min;
    const bool above = hi_m > table.max_m * (1 + 1e-9) && !table.zero_at_max;
    if (!below && !above) return;
    params.reject(below ? lo_key : hi_key,
                  fmt::format("the band ({}) reaches {} the table {}, which spans {} and ends there at a value above 0: "
                              "nothing is known beyond it, and counting it as 0 would hide the loss; narrow the band or "
                              "extend the table",
                              nm_range(lo_m, hi_m), below ? "below" : "past", table.what, nm_range(table.min_m, table.max_m)));
  };
  for (const SpectralTable& table : light.tables) check(table);
  if (!spectrum.empty() && spectrum.extrapolation() == Extrapolation::zero)
    check(SpectralTable{spectrum.min_wavelength_m(), spectrum.max_wavelength_m(), spectrum.value()(0) == 0,
                        spectrum.value()(spectrum.size() - 1) == 0, "of the light reaching this stage"});
}

void require_band_inside_own_table(const Params& params, std::string_view key, double lo_m, double hi_m,
                                   const std::string& lo_key, const std::string& hi_key) {
  Light own;
  note_table(own, params, key);
  require_band_inside_tables(params, own, Spectrum{}, lo_m, hi_m, lo_key, hi_key);
}

}  // namespace radchain
