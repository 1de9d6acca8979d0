#pragma once
// A camera described by its EMVA 1288 datasheet: the linear camera model and its noise terms, and the
// photometry of a point image on a pixel grid (noise-equivalent area of PSF-weighted photometry).
//   EMVA Standard 1288, Release 4.0 Linear (2021), §2 "Sensitivity, linearity and noise":
//     μ_e = η μ_p                                   (eq. 1: mean photoelectrons from mean photons)
//     μ_y = μ_y.dark + K μ_e                          (eq. 3: mean digital value, K the system gain in DN/e-)
//     σ_y² = K² (σ_d² + σ_e²) + σ_q²,  σ_e² = μ_e       (eq. 5: temporal variance; shot noise is Poisson)
//     σ_q² = 1/12 DN²                                 (eq. 5, the uniform quantiser)
//     SNR = μ_e / √(σ_d² + σ_q²/K² + μ_e)               (eq. 6)
//     σ_d² = σ_d0² + μ_I t_exp                        (§4.2 / eq. 29: dark shot noise of the dark current μ_I)
//     spatial non-uniformity: DSNU (σ_o in e-) and PRNU (s_g relative) add σ_o² + s_g² μ_e² per pixel
//                                                     (§2.4, the "SNR including spatial non-uniformities", eq. 18)
//     saturation capacity μ_e.sat: the largest charge still read linearly (§2.3)
//   Noise-equivalent area of PSF-weighted (optimal) photometry: for a PSF sampled into pixel fractions f_i
//   (Σ f_i = 1), the background-limited variance of the optimal estimator is B / Σ f_i² per pixel background B,
//   so n_eff = 1 / Σ f_i²  (King 1983, PASP 95, 163; LSST SMTN-002 §"Noise-equivalent number of pixels";
//   Ivezić et al. 2019, ApJ 873, 111, eq. 6 footnote). A Gaussian of FWHM θ in pixels gives n_eff → 2.266 θ²
//   (= 4π σ²) when θ ≫ 1 pixel; SMTN-002 uses n_eff = 2.266 (FWHM_eff / pixel scale)².
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

namespace radchain::physics {

// EMVA 1288 eq. (5): quantisation variance in electrons², σ_q²/K² with σ_q² = 1/12 DN².
inline double emva_quantisation_variance_e2(double gain_dn_per_e) { return 1.0 / (12.0 * gain_dn_per_e * gain_dn_per_e); }

// EMVA 1288 eq. (6) with the spatial terms of §2.4 (eq. 18): SNR of one pixel's signal μ_e.
inline double emva_pixel_snr(double signal_e, double dark_noise_e, double dark_current_e_s, double exposure_s,
                             double gain_dn_per_e, double dsnu_e = 0.0, double prnu = 0.0) {
  const double var = signal_e + dark_noise_e * dark_noise_e + dark_current_e_s * exposure_s +
                     emva_quantisation_variance_e2(gain_dn_per_e) + dsnu_e * dsnu_e + prnu * prnu * signal_e * signal_e;
  return signal_e / std::sqrt(var);
}

// Fraction of a centred Gaussian PSF (standard deviation σ, pixels) in the pixel column i ∈ ℤ (the PSF centred
// on pixel 0's centre, `offset` pixels off it): Φ((i + ½ − offset)/σ) − Φ((i − ½ − offset)/σ).
inline double gaussian_pixel_fraction(int i, double sigma_px, double offset_px = 0.0) {
  const double s = sigma_px * std::numbers::sqrt2;
  return 0.5 * (std::erf((i + 0.5 - offset_px) / s) - std::erf((i - 0.5 - offset_px) / s));
}

// n_eff = 1 / Σ f_ij² for a Gaussian PSF of FWHM (pixels) sampled by square pixels, centred on a pixel
// (separable: Σ f_ij² = (Σ_i g_i²)²). Tends to 4π σ² = 2.266 FWHM² for FWHM ≫ 1 and to 1 for FWHM → 0.
// The columns are symmetric (g_−i = g_i) and share their edges, so each edge's erf is taken once: half+1 of them.
inline double gaussian_noise_equivalent_area_px(double fwhm_px) {
  const double sigma = fwhm_px / (2.0 * std::sqrt(2.0 * std::numbers::ln2));
  const int half = static_cast<int>(std::ceil(8.0 * sigma)) + 1;
  const double s = sigma * std::numbers::sqrt2;
  double inner = std::erf(0.5 / s);  // erf at the column's inner edge, i − ½ (for i = 0: g_0 = erf(½/s))
  double sum = inner * inner;
  for (int i = 1; i <= half; ++i) {
    const double outer = std::erf((i + 0.5) / s);
    const double g = 0.5 * (outer - inner);
    sum += 2.0 * g * g;
    inner = outer;
  }
  return 1.0 / (sum * sum);
}

// The continuous Gaussian's n_eff = 1/∫∫f² = 4π σ² = π FWHM²/(2 ln 2) = 2.266 FWHM² (pixels; no pixel sampling):
// LSST SMTN-002's "n_eff = 2.266 (FWHM_eff/pixel scale)²" and the exposure-time calculators built on it. The
// pixel-sampled n_eff above tends to it for FWHM ≫ 1 and is larger by about one pixel's worth for a few-pixel PSF.
inline double gaussian_continuous_noise_equivalent_area_px(double fwhm_px) {
  return std::numbers::pi * fwhm_px * fwhm_px / (2.0 * std::numbers::ln2);
}

// The fraction of a Gaussian PSF in its brightest pixel (centred on the pixel): erf(1/(2√2 σ))².
inline double gaussian_peak_pixel_fraction(double fwhm_px) {
  const double sigma = fwhm_px / (2.0 * std::sqrt(2.0 * std::numbers::ln2));
  const double g = gaussian_pixel_fraction(0, sigma);
  return g * g;
}

// ---- Extended scenes: a pixel of an Earth-observation camera looking at a uniform scene -----------------------
// Étendue of one pixel: a pixel of area p² on axis, behind a circular pupil of f-number N (object at infinity),
// sees the pupil under the projected solid angle Ω = π/(4N²) (1 − ε²) for a central obscuration ε, so
//   A_pixel Ω = p² π (1 − ε²) / (4 N²)  ≡  A_pupil IFOV² = π D²/4 (1 − ε²) (p/f')²
// (the camera equation E' = π L τ (1 − ε²) / (4 N²) that the telescope plugin applies, Kolobrodov 1996 eq. 5,
// times the pixel area; on axis, no cos⁴ fall-off).
inline double pixel_projected_solid_angle_sr(double f_number, double obscuration = 0.0) {
  return std::numbers::pi * (1.0 - obscuration * obscuration) / (4.0 * f_number * f_number);
}

// Electrons of one native pixel in one exposure for a scene of spectral radiance L_λ constant over the band:
//   μ_e = N_tdi t p² Ω τ ∫ L_λ η(λ) λ/(hc) dλ = L · k,   k = N_tdi t p² Ω τ ∫ η(λ) λ/(hc) dλ
// (EMVA 1288 §2.1: μ_p = A E t_exp λ/(hc) photons on a pixel of area A under irradiance E, and eq. 1, μ_e = η μ_p,
// in spectral form; E = Ω τ L on the focal plane; TDI sums N_tdi exposures in the charge domain). `qe_photon_integral` is
// ∫_band η(λ) λ/(hc) dλ in electrons s-1 per (W m-2 m-1). With a band-averaged radiance as missions state it,
// L̄ = ∫ L_λ R(λ) dλ / ∫ R(λ) dλ with the system's response per watt R ∝ τ η λ, the same k holds for any scene
// spectrum: μ_e = k L̄ (the mission convention: Sentinel-2 L_ref, Landsat-8 L_typ are band-averaged radiances).
inline double radiance_responsivity_e(double tdi_stages, double exposure_s, double pitch_m, double solid_angle_sr,
                                      double transmittance, double qe_photon_integral) {
  return tdi_stages * exposure_s * pitch_m * pitch_m * solid_angle_sr * transmittance * qe_photon_integral;
}

// Noise variance of one b×b binned pixel over M co-added exposures for a uniform scene (EMVA 1288 eqs. 5, 6, 18):
//   temporal, one exposure:  S₁ + b² [N_tdi μ_I t + σ_d0² + σ_q²/K² + σ_other²]   (shot noise of signal and dark,
//                            read noise of each of the b² native pixels once: charge-domain TDI reads once)
//   spatial (repeats in every exposure, adds in amplitude over M): b² σ_DSNU² + s_g² S₁²/(b² N_tdi)
//                            (PRNU of the b² N_tdi different native pixels the sample sums: b² binned pixels, and
//                            N_tdi TDI stages, each a different pixel row carrying S₁/(b² N_tdi) with a gain of its
//                            own; independent gains of relative spread s_g (EMVA 1288 §2.4 defines s_g per pixel)
//                            give the sum a relative spread s_g/√(b² N_tdi). Co-added frames read the same pixels,
//                            so their PRNU adds in amplitude: the M² below.)
//   n² = M (S₁ + v_t) + M² (v_s + s_g² S₁²/(b² N_tdi))
// `signal1_e` is S₁ (binned pixel, one exposure); `floor_native_e2` is the native pixel's σ_d0² + σ_q²/K² +
// σ_other² + N_tdi μ_I t (the variance at zero signal, dark shot noise included).
inline double emva_uniform_scene_variance_e2(double signal1_e, double floor_native_e2, double dsnu_e, double prnu,
                                             double binning, double exposures, double tdi_stages = 1.0) {
  const double b2 = binning * binning;
  const double temporal = signal1_e + b2 * floor_native_e2;
  const double spatial = b2 * dsnu_e * dsnu_e + prnu * prnu * signal1_e * signal1_e / (b2 * tdi_stages);
  return exposures * temporal + exposures * exposures * spatial;
}

// The band-averaged radiance that fills the pixel: the smaller of the saturation capacity μ_e.sat (EMVA 1288 §2.3)
// and the ADC's last code (2^bits − 1)/K, less the dark charge N_tdi μ_I t, over the responsivity k (e- per unit
// radiance). 0 when the dark charge alone fills it.
inline double saturation_radiance(double capacity_e, double dark_e, double responsivity_e_per_radiance) {
  return std::max(0.0, capacity_e - dark_e) / responsivity_e_per_radiance;
}

// FWHM of the diffraction core of an annular pupil approximated as a Gaussian: 1.028 λ/D for a clear pupil
// (Airy FWHM, Born & Wolf §8.5.2), the same for ε ≤ 0.5 to within 5 % (the core narrows slightly,
// Mahajan 2001). Added in quadrature to the seeing FWHM (Ivezić et al. 2019 §3.2: FWHM_eff² = θ_atm² + θ_sys²).
inline double diffraction_fwhm_rad(double wavelength_m, double aperture_m) { return 1.028 * wavelength_m / aperture_m; }

// Seeing at airmass X from seeing at the zenith: θ(X) = θ_0 X^0.6 (Kolmogorov turbulence, r0 ∝ X^-3/5;
// Roddier 1981, Prog. Optics 19, 281; Ivezić et al. 2019 §3.2).
inline double seeing_at_airmass(double zenith_fwhm, double airmass) { return zenith_fwhm * std::pow(airmass, 0.6); }

}  // namespace radchain::physics
