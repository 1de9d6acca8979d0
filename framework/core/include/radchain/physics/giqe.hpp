#pragma once
// The General Image Quality Equation: predicted NIIRS (National Imagery Interpretability Rating Scale) of a
// visible image from its ground sample distance, edge sharpness and signal-to-noise ratio.
// Sources:
//   GIQE-5: National Geospatial-Intelligence Agency, "General Image Quality Equation (GIQE) Version 5.0",
//     NGA/NIPS (16 Sep 2015), the equation
//       NIIRS = A0 + A1 log10 GSD + A2 [1 − exp(A3 / SNR)] log10 RER + A4 (log10 RER)^4 + A5 / SNR
//     with A0 = 9.57, A1 = −3.32, A2 = 3.32, A3 = −1.9, A4 = −2.0, A5 = −1.8; GSD the weighted GSD of its
//     eq. (5) in inches, RER the weighted relative edge response of its eq. (7) (below), SNR the SNR of a
//     reference target in the unenhanced image. The document states where its data end: Q = λN/p between 1
//     and 2 (Q > 2 "a pure extrapolation"), smear up to 4 pixels in the fit (8 in the smear study), target
//     elevations down to 8.9°, less precise below SNR 5 (its §2.2-4; docs/eo-imagers.md). Read from the public
//     release in github.com/Kitware/pybsm @ 6a6d23d, docs/GIQE-5_for_Public_Release.pdf. The three versions are compared in "Comparative study of the different versions of the
//     General Image Quality Equation" (ISPRS Open J. Photogramm. Remote Sens., 2023).
//   GIQE-4: J. C. Leachtenauer, W. Malila, J. Irvine, L. Colburn, N. Salvaggio, "General Image-Quality
//     Equation: GIQE", Appl. Opt. 36 (1997) 8322, eq. (2):
//       NIIRS = 10.251 − a log10 GSD + b log10 RER − 0.656 H − 0.344 G / SNR,
//     a = 3.32, b = 1.559 for RER ≥ 0.9; a = 3.16, b = 2.817 for RER < 0.9 (GSD in inches).
//   Relative edge response and overshoot from an MTF: ER(x) = ½ + (1/π) ∫₀^∞ MTF(ν) sin(2πνx)/ν dν for a
//     real, even MTF (the edge is the integral of the line spread function, the LSF the inverse transform of
//     the MTF); RER = ER(½) − ER(−½) with x in samples (Leachtenauer 1997, §2; R. D. Fiete, Modeling the
//     Imaging Chain of Digital Cameras, SPIE TT92 (2010), §12.3); H = the maximum of ER over 1 ≤ x ≤ 3 samples,
//     or ER(1.25) where the edge rises monotonically there (GIQE-4's definition, Leachtenauer 1997).

#include <functional>

namespace radchain::physics {

inline constexpr double metres_per_inch = 0.0254;  // exact (international inch, 1959)

struct Giqe5Coefficients {
  double a0 = 9.57, a1 = -3.32, a2 = 3.32, a3 = -1.9, a4 = -2.0, a5 = -1.8;  // NGA GIQE v5.0 (2015)
};

// GIQE-5's weighted GSD, NGA GIQE v5.0 eq. (5): GSD_W = GSD_NP / sin(elevation)^¼, the geometric mean of the
// normal-plane GSD GSD_NP = p R / f' (R the slant range) and the ground-plane GSD_NP / sin(elevation)^½ (GIQE-4's);
// elevation = the target's, 90° − the view zenith angle.
double giqe5_weighted_gsd_m(double normal_plane_gsd_m, double elevation_rad);
// GIQE-5's weighted RER, NGA GIQE v5.0 eq. (7): (RER_cs RER_as²)^⅓ with RER_as ≤ RER_cs, i.e. the lesser of the
// two directions counted twice ("a loss of RER in one direction cannot be mitigated by … the orthogonal direction").
double giqe5_weighted_rer(double rer_a, double rer_b);
// GIQE-5 NIIRS; gsd in metres (converted to inches here), rer and snr > 0.
double giqe5_niirs(double gsd_m, double rer, double snr, const Giqe5Coefficients& c = {});
// GIQE-4 NIIRS; gsd in metres, overshoot H, noise gain G (1 without sharpening), snr > 0.
double giqe4_niirs(double gsd_m, double rer, double overshoot, double noise_gain, double snr);

// Edge response of a system with modulation transfer `mtf` (argument: frequency in cycles per sample) at x
// samples from the edge; the integral is taken to `max_frequency` cycles/sample (where the MTF is ~0: the
// diffraction cut-off in samples, or several cycles/sample for an unbounded MTF) by composite Simpson with
// `intervals` panels.
double edge_response(const std::function<double(double)>& mtf, double x_samples, double max_frequency,
                     int intervals = 4000);
// RER = ER(½) − ER(−½).
double relative_edge_response(const std::function<double(double)>& mtf, double max_frequency, int intervals = 4000);
// GIQE-4 overshoot H: max ER on [1, 3] samples if the edge is not monotonic there, else ER(1.25).
double edge_overshoot(const std::function<double(double)>& mtf, double max_frequency, int intervals = 4000);

// pyBSM's rule for the same integrals (Kitware/pybsm @ 6a6d23d, metrics.functional.edge_response, IBSM eq. 3-57),
// to reproduce its numbers (validation/pybsm): the MTF at the 50 nodes ν_k = k c/50, k = 0…49, of its 101-point
// grid over ±c (c the cut-off in cycles/sample; otf.functional.slice_otf stops before c), and the trapezoid over
// w_k = ν_k/ifov + 10⁻⁶ cycles/rad (pyBSM's offset that keeps 1/w finite, an angular frequency, hence ifov):
// ER(x) = ½ + (1/π) trapz_k[MTF(ν_k) sin(2π w_k ifov x)/w_k]. It stops 2 % short of the cut-off and samples
// 50 points: RER 1.6e-4 to 3e-4 above the converged integral on pyBSM's own cases.
double edge_response_pybsm(const std::function<double(double)>& mtf, double x_samples, double cutoff_samples,
                           double ifov_rad);
double relative_edge_response_pybsm(const std::function<double(double)>& mtf, double cutoff_samples, double ifov_rad);
// GIQE-4's overshoot as pyBSM samples it (metrics.functional.edge_height_overshoot): ER at x = 1, 1.25, …, 3;
// ER(1.25) if every step rises, else the maximum.
double edge_overshoot_pybsm(const std::function<double(double)>& mtf, double cutoff_samples, double ifov_rad);

}  // namespace radchain::physics
