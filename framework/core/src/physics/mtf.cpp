#include "radchain/physics/mtf.hpp"

#include <algorithm>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace radchain::physics {

namespace {

constexpr double pi = std::numbers::pi;

// Root of f on [a, b] (f(a), f(b) of opposite signs) by TOMS 748 (Alefeld, Potra & Shi 1995), to ~full precision.
template <class F>
double solve_bracketed(F f, double a, double b, double fa, double fb, const char* what) {
  if (fa == 0) return a;
  if (fb == 0) return b;
  if ((fa > 0) == (fb > 0)) throw std::invalid_argument(std::string(what) + ": the root is not bracketed");
  std::uintmax_t max_iter = 200;
  const auto [lo, hi] = boost::math::tools::toms748_solve(
      f, a, b, fa, fb, boost::math::tools::eps_tolerance<double>(std::numeric_limits<double>::digits - 2), max_iter);
  return 0.5 * (lo + hi);
}

void require_contrast(double contrast, const char* what) {
  if (!(contrast > 0 && contrast < 1))
    throw std::invalid_argument(std::string(what) + ": contrast must lie in (0, 1), got " + std::to_string(contrast));
}

// Overlap area of two discs of radii ra, rb whose centres are d apart (the "lens"): each disc contributes
// r² acos(·) − its triangle; written in the symmetric form with Heron's product for the kite.
double disc_overlap_area(double ra, double rb, double d) {
  if (d >= ra + rb) return 0.0;
  if (d <= std::abs(ra - rb)) {
    const double r = std::min(ra, rb);
    return pi * r * r;
  }
  const double ca = std::clamp((d * d + ra * ra - rb * rb) / (2 * d * ra), -1.0, 1.0);
  const double cb = std::clamp((d * d + rb * rb - ra * ra) / (2 * d * rb), -1.0, 1.0);
  const double kite = (-d + ra + rb) * (d + ra - rb) * (d - ra + rb) * (d + ra + rb);
  return ra * ra * std::acos(ca) + rb * rb * std::acos(cb) - 0.5 * std::sqrt(std::max(0.0, kite));
}

}  // namespace

// ---- Diffraction-limited objective ----------------------------------------------------------------------

double diffraction_cutoff_frequency_per_m(double wavelength_m, double f_number) {
  return 1.0 / (wavelength_m * f_number);
}

double diffraction_mtf_normalized(double normalized_frequency, double obscuration_ratio) {
  if (!(obscuration_ratio >= 0 && obscuration_ratio < 1))
    throw std::invalid_argument("diffraction_mtf: obscuration ratio must lie in [0, 1)");
  const double x = std::abs(normalized_frequency);
  if (x >= 1) return 0.0;
  if (obscuration_ratio == 0) {
    // Goodman (2005) ch. 6: the overlap of two unit discs d = 2x apart over π.
    return 2.0 / pi * (std::acos(x) - x * std::sqrt(1.0 - x * x));
  }
  // Pupil of outer radius 1 and inner radius ε; the OTF at x = ν/ν_c is the overlap of the pupil with its copy
  // shifted by d = 2x (ν_c = 2R/(λ f')), over the pupil area. For an annulus A∖B shifted against itself:
  // |A∩A'| − |A∩B'| − |B∩A'| + |B∩B'| (B ⊂ A), and the two cross terms are equal discs of radii 1 and ε.
  const double e = obscuration_ratio;
  const double d = 2.0 * x;
  const double overlap = disc_overlap_area(1.0, 1.0, d) - 2.0 * disc_overlap_area(1.0, e, d) + disc_overlap_area(e, e, d);
  return std::max(0.0, overlap / (pi * (1.0 - e * e)));
}

double diffraction_mtf(double frequency_per_m, double wavelength_m, double f_number, double obscuration_ratio) {
  return diffraction_mtf_normalized(frequency_per_m / diffraction_cutoff_frequency_per_m(wavelength_m, f_number),
                                    obscuration_ratio);
}

double diffraction_normalized_frequency_at_contrast(double contrast, double obscuration_ratio) {
  require_contrast(contrast, "diffraction_frequency_at_contrast");
  auto f = [&](double x) { return diffraction_mtf_normalized(x, obscuration_ratio) - contrast; };
  // The obscured MTF is not monotonic, so walk up from 0 to the first sign change, then refine.
  constexpr int steps = 1024;
  double a = 0.0, fa = f(a);
  for (int i = 1; i <= steps; ++i) {
    const double b = static_cast<double>(i) / steps;
    const double fb = f(b);
    if ((fb > 0) != (fa > 0) || fb == 0) return solve_bracketed(f, a, b, fa, fb, "diffraction_frequency_at_contrast");
    a = b;
    fa = fb;
  }
  throw std::invalid_argument("diffraction_frequency_at_contrast: the MTF does not reach the contrast");
}

double diffraction_frequency_at_contrast_per_m(double contrast, double wavelength_m, double f_number,
                                               double obscuration_ratio) {
  return diffraction_normalized_frequency_at_contrast(contrast, obscuration_ratio) *
         diffraction_cutoff_frequency_per_m(wavelength_m, f_number);
}

// ---- Kolobrodov's linear objective MTF ------------------------------------------------------------------

double kolobrodov_linear_mtf(double frequency_per_m, double wavelength_m, double f_number, double eta) {
  // Kolobrodov 1996 eq. (7): M_0 = 1 − 1.218 (f'/D) λ ν / η.
  const double m = 1.0 - kolobrodov_linear_mtf_slope * f_number * wavelength_m * std::abs(frequency_per_m) / eta;
  return std::max(0.0, m);
}

double kolobrodov_linear_frequency_at_contrast_per_m(double contrast, double wavelength_m, double f_number,
                                                     double eta) {
  require_contrast(contrast, "kolobrodov_linear_frequency_at_contrast");
  // Eq. (7) = contrast; at contrast ½ this is eq. (11), ν_x1 = η / (2.436 (f'/D) λ).
  return (1.0 - contrast) * eta / (kolobrodov_linear_mtf_slope * f_number * wavelength_m);
}

// ---- Detector element -----------------------------------------------------------------------------------

double sinc_pi(double u) {
  const double a = pi * u;
  if (std::abs(a) < 1e-4) return 1.0 - a * a / 6.0;  // Taylor; the next term a⁴/120 < 1e-17
  return std::sin(a) / a;
}

double detector_pixel_mtf(double frequency_per_m, double pixel_width_m) {
  // Kolobrodov 1996 eq. (8): M_D = sin(π V_D ν)/(π V_D ν), as a modulus.
  return std::abs(sinc_pi(pixel_width_m * frequency_per_m));
}

double sinc_root_at_contrast(double contrast) {
  require_contrast(contrast, "sinc_root_at_contrast");
  // sinc(πu) falls monotonically from 1 to 0 on [0, 1].
  auto f = [&](double u) { return sinc_pi(u) - contrast; };
  return solve_bracketed(f, 0.0, 1.0, f(0.0), f(1.0), "sinc_root_at_contrast");
}

double sinc_half_contrast_root() {
  static const double root = sinc_root_at_contrast(0.5);
  return root;
}

double detector_frequency_at_contrast_per_m(double contrast, double pixel_width_m) {
  // Kolobrodov 1996 eq. (11), second form, with the exact root instead of 0.6.
  return sinc_root_at_contrast(contrast) / pixel_width_m;
}

// ---- Matching -------------------------------------------------------------------------------------------

double kolobrodov_eta_coefficient(double sinc_root) {
  // Eq. (12): 2 · 1.218 · u (the paper: 2.436 · 0.6 = 1.4616, printed 1.46).
  return 2.0 * kolobrodov_linear_mtf_slope * sinc_root;
}

double kolobrodov_eta(double wavelength_m, double f_number, double pixel_width_m, double eta_coefficient) {
  // Eq. (12): η = 1.46 (f'/D) λ / V_D.
  return eta_coefficient * f_number * wavelength_m / pixel_width_m;
}

double kolobrodov_max_f_number(double wavelength_m, double pixel_width_m, double eta, double eta_coefficient) {
  // Eq. (12) solved for f'/D.
  return eta * pixel_width_m / (eta_coefficient * wavelength_m);
}

double kolobrodov_system_mtf(double frequency_per_m, double wavelength_m, double f_number, double eta,
                             double pixel_width_m) {
  // Eq. (10) = eq. (7) × eq. (8).
  return kolobrodov_linear_mtf(frequency_per_m, wavelength_m, f_number, eta) *
         detector_pixel_mtf(frequency_per_m, pixel_width_m);
}

double kolobrodov_eq15_residual(double system_to_detector_ratio, double sinc_root, double contrast) {
  // Eq. (15) generalised to a matching contrast c: (1 − (1 − c) r) sinc(π u r) − c, r = V_D/V_s.
  const double r = 1.0 / system_to_detector_ratio;
  return (1.0 - (1.0 - contrast) * r) * sinc_pi(sinc_root * r) - contrast;
}

double kolobrodov_system_element_ratio(double sinc_root, double contrast) {
  require_contrast(contrast, "kolobrodov_system_element_ratio");
  if (!(sinc_root > 0 && sinc_root < 1))
    throw std::invalid_argument("kolobrodov_system_element_ratio: the sinc root must lie in (0, 1)");
  // Solve in r = V_D/V_s ∈ [0, 1], where the residual falls monotonically from 1 − c to c (sinc(πu) − 1) < 0.
  auto f = [&](double r) { return (1.0 - (1.0 - contrast) * r) * sinc_pi(sinc_root * r) - contrast; };
  const double r = solve_bracketed(f, 0.0, 1.0, f(0.0), f(1.0), "kolobrodov_system_element_ratio");
  return 1.0 / r;
}

// ---- MTF budget (sources in mtf.hpp) ----------------------------------------------------------------------

double turbulence_mtf(double frequency_per_m, double wavelength_m, double focal_length_m, double fried_parameter_m) {
  if (!(fried_parameter_m > 0)) return 1.0;
  const double x = wavelength_m * focal_length_m * std::abs(frequency_per_m) / fried_parameter_m;
  return std::exp(-3.44 * std::pow(x, 5.0 / 3.0));  // Fried 1966, long exposure
}

double jitter_mtf(double frequency_per_m, double jitter_rms_m) {
  return std::exp(-2 * pi * pi * jitter_rms_m * jitter_rms_m * frequency_per_m * frequency_per_m);
}

double linear_smear_mtf(double frequency_per_m, double smear_length_m) {
  return std::abs(sinc_pi(smear_length_m * frequency_per_m));
}

double diffusion_mtf(double frequency_per_m, double diffusion_rms_m) {
  return std::exp(-2 * pi * pi * diffusion_rms_m * diffusion_rms_m * frequency_per_m * frequency_per_m);
}

double wavefront_error_mtf(double frequency_per_m, double wavelength_m, double f_number, double wfe_rms_waves) {
  const double x = std::abs(frequency_per_m) / diffraction_cutoff_frequency_per_m(wavelength_m, f_number);
  // Defined on [0, 1], where it ends at 1; beyond the cut-off the diffraction MTF it multiplies is 0, and the factor
  // stays 1 (it was 0 there, so the budget's "other" components read 0 at Nyquist whenever Q > 2).
  if (x >= 1) return 1.0;
  const double w = wfe_rms_waves / 0.18;
  return std::max(0.0, 1 - w * w * (1 - 4 * (x - 0.5) * (x - 0.5)));
}

double tdi_synchronisation_mtf(double frequency_per_m, double stages, double mismatch_fraction, double pixel_pitch_m) {
  // N is a count; a real N > 0 is accepted so that a sweep or solve may pass through it smoothly.
  if (!(stages > 0)) throw std::invalid_argument("TDI: the number of stages must be positive, got " + std::to_string(stages));
  return std::abs(shifted_copies_otf(frequency_per_m, stages, mismatch_fraction * pixel_pitch_m));
}

double shifted_copies_otf(double frequency_per_m, double copies, double shift_m) {
  const double a = pi * shift_m * frequency_per_m;
  if (std::abs(std::sin(a)) < 1e-12) return std::cos(copies * a) / std::cos(a);  // the limit: ±1 (−1 for even N at odd k)
  return std::sin(copies * a) / (copies * std::sin(a));
}

double nyquist_frequency_per_m(double pixel_pitch_m) {
  if (!(pixel_pitch_m > 0)) throw std::invalid_argument("pixel pitch must be positive");
  return 0.5 / pixel_pitch_m;
}

}  // namespace radchain::physics
