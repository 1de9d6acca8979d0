#pragma once
// A source's radiation in a wavelength band, and how much of it a detector uses. Pure functions.
//
//   z(λ)  fraction of a source's radiation below λ. Kolobrodov 1996 (after Pavlov 1974) writes the Sun's
//         in-band irradiance as E'_s = E_s [z(λ2) - z(λ1)] and prints z(0.5 µm) = 0.236, z(0.76 µm) = 0.58.
//         For a tabulated spectrum z is the ratio of two integrals over the table; for a blackbody use the
//         closed form physics::blackbody_fraction_below (planck.hpp) or blackbody_band_fraction below.
//
//   k     detector utilisation coefficient ("коэффициент использования", Ishanin et al. 1991, as used by
//         Kolobrodov 1996 for H_nr = H_nt k_i / k_c):
//             k = ∫_{response range} S(λ) s_rel(λ) dλ / ∫_{source range} S(λ) dλ
//         with S the source's spectral power and s_rel the detector's relative spectral response per watt,
//         peak 1. Both ranges are explicit arguments because the paper does not say which it meant
//         (docs/utilisation-coefficients.md lists the readings and what each gives).
#include "radchain/constants.hpp"
#include "radchain/spectrum.hpp"

#include <Eigen/Core>

namespace radchain::physics {

// A closed wavelength interval [lo_m, hi_m], metres.
struct WavelengthRange {
  double lo_m = 0;
  double hi_m = 0;
};

// The whole grid of a spectrum, [min, max].
WavelengthRange support(const Spectrum& spectrum);

// z(λ) = ∫_{min}^{λ} S dλ / ∫_{min}^{max} S dλ over the spectrum's own grid (0 below the grid, 1 above it).
// Throws std::invalid_argument when the spectrum integrates to zero or less.
double fraction_below(const Spectrum& source, double wavelength_m);
// z(hi) - z(lo): the fraction of the source's total in [lo, hi].
double band_fraction(const Spectrum& source, double lo_m, double hi_m);
// The blackbody equivalent from the closed-form series (Widger & Woodall 1976):
// F(0→hi T) - F(0→lo T) for the exitance M_λ with the given c2 convention.
double blackbody_band_fraction(double lo_m, double hi_m, double temperature_K,
                               double c2_m_K = constants::second_radiation_m_K);

// What the detector counts: the energy its response is stated per (watt), or photons (the response is a
// relative quantum efficiency, and both integrands are weighted by λ/(hc); hc cancels in the ratio).
enum class Counting { energy, photons };

// Kolobrodov 1996 / Ishanin et al. 1991 utilisation coefficient
//   k = ∫_{response_range} S s_rel [λ] dλ / ∫_{source_range} S [λ] dλ      ([λ]: photons only)
// `relative_response` is used as given (normalise it with normalised_to_peak first if it is not).
double utilisation_coefficient(const Spectrum& source, const Spectrum& relative_response,
                               WavelengthRange response_range, WavelengthRange source_range,
                               Counting counting = Counting::energy);

// Kolobrodov 1996, text after eq. (20) (from Ishanin et al. 1991): a noise-equivalent exposure measured
// with a reference source (H_nt, utilisation k_reference) expressed for the working source:
//   H_nr = H_nt k_i / k_c.
inline double exposure_for_working_source(double reference_exposure, double k_reference, double k_working) {
  return reference_exposure * k_reference / k_working;
}

// The same curve scaled to peak 1 (unit "1").
Spectrum normalised_to_peak(const Spectrum& spectrum);
// A per-photon response (quantum efficiency η(λ)) as a per-watt relative response: responsivity
// R(λ) = η e λ/(hc) ∝ η λ, normalised to peak 1 (e.g. Janesick, Scientific CCDs (2001) §2.2).
Spectrum per_watt_relative_response(const Spectrum& quantum_efficiency);

// A grid for sampled Planck curves, from the far UV to the far infrared, so that any band a chain integrates
// lies inside it (a Planck curve is never 0 for want of a node): 1000 logarithmic steps from 10 nm to 100 nm,
// 1 nm steps to 2500 nm (so it contains every integer-nm node of the CIE and detector tables, where linear
// interpolation then adds nothing), 2000 logarithmic steps to 100 µm and 1500 more to 1 mm. It misses < 4e-8 of a
// 2000 K blackbody's total (beyond 1 mm) and < 1e-9 of a 6000 K one (both ends together).
Eigen::ArrayXd planck_grid_m();
// Planck spectral exitance M_λ (W m^-2 m^-1) sampled on `grid_m`, with a stated c2 convention.
Spectrum blackbody_exitance_spectrum(double temperature_K, double c2_m_K = constants::second_radiation_m_K,
                                     const Eigen::ArrayXd& grid_m = planck_grid_m());

}  // namespace radchain::physics
