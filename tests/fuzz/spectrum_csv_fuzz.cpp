// CSV spectra (spectra/README.md): the loader, then the operations the chain applies to a loaded spectrum.
// The input is the file; it is read as a relative curve (QE, transmittance, filter) with clamped ends and as a
// spectral irradiance with zero ends, the two kinds of expectations the plugins have.
#include "fuzz_input.hpp"

#include "radchain/error.hpp"
#include "radchain/spectrum_csv.hpp"

#include <utility>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = radchain::fuzz::write_scratch("spectrum.csv", radchain::fuzz::as_text(data, size));
  for (const auto& [unit, extrapolation] : {std::pair{"1", radchain::Extrapolation::clamp},
                                            std::pair{"W m-2 m-1", radchain::Extrapolation::zero}}) {
    try {
      const radchain::Spectrum s = radchain::load_spectrum_csv(path, unit, extrapolation).spectrum;
      (void)s(0.5 * (s.min_wavelength_m() + s.max_wavelength_m()));
      (void)s.integral();
      (void)s.peak_wavelength_m();
      (void)s.product(s);
    } catch (const radchain::InputError&) {
    }
  }
  return 0;
}
