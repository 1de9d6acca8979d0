#pragma once
// Modulation transfer functions of an objective and a line-array detector, and Kolobrodov's matching of the
// two. Frequencies in cycles per metre (1 mm^-1 = 1e3 m^-1), lengths in metres, f_number N = f'/D.
// Sources:
//   Diffraction MTF of an aberration-free circular pupil in incoherent light: the pupil's autocorrelation
//     normalised to its area, Goodman, Introduction to Fourier Optics, 3rd ed. (2005), ch. 6 (OTF of a
//     diffraction-limited system); with a central obscuration: E. L. O'Neill, "Transfer function for an annular
//     aperture", J. Opt. Soc. Am. 46 (1956) 285 (computed here as the same autocorrelation of the annulus; the
//     test checks O'Neill's closed form).
//   Kolobrodov 1996, "Design of the optical system of a satellite-borne CCD camera"
//     (seed 000_b315c29ce1517a86): eqs. (7), (8), (10), (11), (12), (15).

namespace radchain::physics {

// ---- Diffraction-limited objective -------------------------------------------------------------------------

// Cut-off frequency ν_c = D/(λ f') = 1/(λ N), cycles/m.
double diffraction_cutoff_frequency_per_m(double wavelength_m, double f_number);

// MTF at x = ν/ν_c (|x| is used; 0 for |x| ≥ 1). Without obscuration (Goodman):
//   M(x) = (2/π)[acos x − x √(1 − x²)],  M(0) = 1, M(½) = 0.391002, M(1) = 0.
// With a central obscuration of linear ratio ε = d_obscuration/D (0 ≤ ε < 1): the overlap area of the annulus
// and its copy shifted by 2x outer radii, over the annulus area π(1 − ε²). Not monotonic for ε ≳ 0.45.
double diffraction_mtf_normalized(double normalized_frequency, double obscuration_ratio = 0.0);
// The same at a frequency in cycles/m.
double diffraction_mtf(double frequency_per_m, double wavelength_m, double f_number, double obscuration_ratio = 0.0);

// Lowest x = ν/ν_c in (0, 1) where the diffraction MTF falls to `contrast` (0 < contrast < 1). Without
// obscuration x(0.5) = 0.403973. Throws std::invalid_argument for a contrast outside (0, 1).
double diffraction_normalized_frequency_at_contrast(double contrast, double obscuration_ratio = 0.0);
double diffraction_frequency_at_contrast_per_m(double contrast, double wavelength_m, double f_number,
                                               double obscuration_ratio = 0.0);

// ---- Kolobrodov's linear objective MTF, eq. (7) -----------------------------------------------------------

// M_0(ν) = 1 − 1.218 (f'/D) λ ν / η. The paper takes 1.218 from Kolobrodov & Schuster (1994) without a
// derivation; it is the chord of the exact diffraction MTF through half the cut-off:
// (1 − M(½))/½ = (1 − 0.391002)/0.5 = 1.21800 (not the tangent 4/π = 1.273 at ν = 0). So for η = 1 the line
// equals the diffraction MTF at ν_c/2; η ≤ 1 makes it steeper (a real objective). Eq. (7) itself gives
// η = (1 − M_diffraction)/(1 − M_real) ≤ 1; the paper prints the ratio upside down (see the errata doc).
inline constexpr double kolobrodov_linear_mtf_slope = 1.218;

// Eq. (7), clamped at 0 beyond the line's zero ν = η/(1.218 N λ) (the linear model means nothing there).
double kolobrodov_linear_mtf(double frequency_per_m, double wavelength_m, double f_number, double eta);
// Frequency where eq. (7) reaches `contrast`: ν = (1 − contrast) η / (1.218 N λ); at 0.5 this is the first form
// of eq. (11), ν_x1 = η / (2.436 (f'/D) λ).
double kolobrodov_linear_frequency_at_contrast_per_m(double contrast, double wavelength_m, double f_number,
                                                     double eta);

// ---- Detector element, eq. (8) ----------------------------------------------------------------------------

// sinc(πu) = sin(πu)/(πu), 1 at u = 0 (signed: the OTF of a rectangle of unit width at frequency u).
double sinc_pi(double u);
// Eq. (8): M_D(ν) = |sinc(π V_D ν)| for an element of width V_D (the temporal MTF taken as 1, as the paper does).
// The modulus: beyond ν = 1/V_D the signed eq. (8) is a contrast reversal, whose MTF is its magnitude.
double detector_pixel_mtf(double frequency_per_m, double pixel_width_m);

// u in (0, 1) with sinc(πu) = contrast (0 < contrast < 1), by TOMS 748 (Boost.Math).
double sinc_root_at_contrast(double contrast);
// u_½ = 0.6033545644... (sinc(πu) = ½); the paper rounds it to 0.6 in eqs. (11) and (14).
double sinc_half_contrast_root();
inline constexpr double kolobrodov_sinc_half_root_printed = 0.6;
// Frequency where the element's MTF falls to `contrast`: u/V_D; the second form of eq. (11) is 0.6/V_D.
double detector_frequency_at_contrast_per_m(double contrast, double pixel_width_m);

// ---- Matching objective and detector, eqs. (10)-(15) ------------------------------------------------------

// Eq. (12): equating the two forms of eq. (11), η/(2·1.218·N λ) = u/V_D, gives η = (2·1.218·u)·N λ / V_D.
// The coefficient 2·1.218·u is 1.4616 with the paper's u = 0.6 (printed 1.46) and 1.469772 with the exact
// root u_½ = 0.603355.
double kolobrodov_eta_coefficient(double sinc_root);
inline constexpr double kolobrodov_eta_coefficient_printed = 1.46;
double kolobrodov_eta(double wavelength_m, double f_number, double pixel_width_m, double eta_coefficient);
// Eq. (12) solved for the f-number: the largest N at which an objective of quality η can still be matched,
// N = η V_D / (coefficient · λ); an objective slower than that cannot reach the detector's resolution.
double kolobrodov_max_f_number(double wavelength_m, double pixel_width_m, double eta, double eta_coefficient);

// Eq. (10): M_s(ν) = M_0(ν) · M_D(ν).
double kolobrodov_system_mtf(double frequency_per_m, double wavelength_m, double f_number, double eta,
                             double pixel_width_m);

// Eqs. (13)-(15). The system's resolution element is taken as a rectangle V_s whose sinc equals eq. (10) at the
// matching contrast c at ν_x2 = u/V_s (eq. 14). With η from eq. (12) computed with the same u, the objective
// term of eq. (10) at ν_x2 is 1 − (1 − c)·V_D/V_s exactly, so with r = V_D/V_s
//   (1 − (1 − c) r) · sinc(π u r) = c,      at c = ½:  (1 − V_D/(2 V_s)) · sinc(0.6 π V_D/V_s) = ½   (eq. 15).
// The left side falls monotonically from 1 to c·sinc(πu) < c on r ∈ [0, 1], so the root is unique.
// Residual of that equation at a given V_s/V_D:
double kolobrodov_eq15_residual(double system_to_detector_ratio, double sinc_root, double contrast = 0.5);
// Its root V_s/V_D (TOMS 748): 1.487699 with u = 0.6, 1.492224 with u = u_½; the paper prints 1.49 (eq. 15).
double kolobrodov_system_element_ratio(double sinc_root, double contrast = 0.5);
inline constexpr double kolobrodov_system_element_ratio_printed = 1.49;

// ---- MTF budget of an Earth-observation camera ------------------------------------------------------------
// Each factor is the modulus of the transfer function of one blur, frequency in cycles/m; the system MTF is
// their product (linear shift-invariant cascade: Goodman 2005 ch. 6; R. D. Fiete, Modeling the Imaging Chain of
// Digital Cameras, SPIE TT92 (2010), ch. 5-6; G. C. Holst, Electro-Optical Imaging System Performance, 5th ed.
// (2008), ch. 10). Diffraction with central obscuration and the pixel aperture are above.

// Atmospheric turbulence, long exposure: MTF = exp(−3.44 (λ f' ν / r₀)^(5/3)), r₀ the Fried parameter of the line
// of sight at the pupil, f' ν the angular frequency in cycles per radian (D. L. Fried, "Optical resolution through
// a randomly inhomogeneous medium for very long and very short exposures", JOSA 56 (1966) 1372; J. W. Goodman,
// Statistical Optics (1985) §8.6; Fiete 2010 ch. 5). r₀ ≤ 0: no turbulence (1).
double turbulence_mtf(double frequency_per_m, double wavelength_m, double focal_length_m, double fried_parameter_m);
// Gaussian jitter of rms σ on the focal plane (random high-frequency line-of-sight motion):
// MTF = exp(−2π² σ² ν²) (Fiete 2010 ch. 6; Holst 2008 ch. 10).
double jitter_mtf(double frequency_per_m, double jitter_rms_m);
// Linear smear of length d during the integration: |sinc(π d ν)| (Fiete 2010 ch. 6; Holst 2008 ch. 10).
double linear_smear_mtf(double frequency_per_m, double smear_length_m);
// Charge diffusion / crosstalk as a Gaussian spread of rms σ_d: exp(−2π² σ_d² ν²) (the Gaussian kernel model of
// lateral diffusion, Holst 2008 ch. 10, detector diffusion; a first-order model — measured diffusion MTFs of
// thick devices fall faster at low frequency).
double diffusion_mtf(double frequency_per_m, double diffusion_rms_m);
// Wavefront error W_rms (waves) as Shannon's aberration transfer factor on the diffraction MTF:
// ATF(x) = 1 − (W_rms/0.18)² [1 − 4 (x − ½)²], x = ν/ν_c, clamped at 0 (R. R. Shannon, The Art and Science of
// Optical Design (1997), the Hufnagel approximation; Fiete 2010 ch. 5). Valid for W_rms ≲ 0.18 waves. 1 beyond the
// cut-off (x ≥ 1), as at x = 1: the diffraction MTF it multiplies is 0 there.
double wavefront_error_mtf(double frequency_per_m, double wavelength_m, double f_number, double wfe_rms_waves);
// TDI synchronisation: N stages, each shifting the charge a fraction `mismatch` of a pixel pitch p away from the
// image motion; the N sub-images add with shifts k·mismatch·p, so MTF = |sin(π N δ ν)/(N sin(π δ ν))|,
// δ = mismatch·p (a Dirichlet kernel; H.-S. Wong, Y. L. Yao, E. S. Schlig, "TDI charge-coupled devices: design
// and applications", IBM J. Res. Dev. 36 (1992) 83; → |sinc(π N δ ν)| for small δ).
double tdi_synchronisation_mtf(double frequency_per_m, double stages, double mismatch_fraction, double pixel_pitch_m);
// The signed OTF of N equal copies of an image shifted by δ each (centred): sin(π N δ ν)/(N sin(π δ ν)), the
// Dirichlet kernel behind TDI synchronisation (δ = mismatch·p, above) and b×b binning (N = b, δ = p; Holst 2008
// ch. 10, sampled-data systems). Where sin(π δ ν) = 0 its limit cos(π N δ ν)/cos(π δ ν) = ±1. Signed, for images
// that keep contrast reversal.
double shifted_copies_otf(double frequency_per_m, double copies, double shift_m);
// Nyquist frequency of a pixel pitch p: 1/(2p).
double nyquist_frequency_per_m(double pixel_pitch_m);

}  // namespace radchain::physics
