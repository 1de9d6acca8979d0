#pragma once
// CSV spectra as shipped in spectra/ (see spectra/README.md for the format):
//   # provenance comment lines (at least one; they may contain commas)
//   wavelength_<unit>,<quantity>[_<unit>]       e.g. wavelength_nm,spectral_irradiance_W_m-2_nm-1
//   <wavelength>,<value>                        strictly increasing wavelengths
// The unit in the header is required for the wavelength column; for the value column it is required when
// the caller expects a dimensional quantity, and a relative quantity (quantum_efficiency,
// relative_response, transmittance, ...) must not carry a dimensional unit.
#include "radchain/spectrum.hpp"

#include <string>

namespace radchain {

struct SpectrumFile {
  Spectrum spectrum;        // SI units (wavelength in metres, value in `expected_si_unit`)
  std::string provenance;   // the '#' comment lines, joined with newlines
  std::string value_column; // the header's quantity name, e.g. "spectral_irradiance_W_m-2_nm-1"
};

// Loads and converts. `expected_si_unit` is "1" for relative spectra, or e.g. "W m-2 m-1".
// Throws InputError naming the file and line (the caller adds the sensor-file context).
SpectrumFile load_spectrum_csv(const std::string& path, const std::string& expected_si_unit,
                               Extrapolation extrapolation = Extrapolation::zero);

// The same, memoised per (path, unit): a sweep or a catalogue reads each file once per process.
const SpectrumFile& cached_spectrum_csv(const std::string& path, const std::string& expected_si_unit,
                                        Extrapolation extrapolation = Extrapolation::zero);

}  // namespace radchain
