#pragma once
// Detection of a known signal in additive Gaussian noise, the "classical detection theory" behind Pan 2010
// eq. (10) and its Fig. 5. A detection test compares the sample (signal + noise, in units of the noise rms σ)
// with a threshold γ: with noise alone the sample is N(0, 1), with the object present N(SNR, 1), so
//   P_fa = 1 − Φ(γ),            P_d = 1 − Φ(γ − SNR) = Φ(SNR − γ),
// and the SNR needed for a required pair (P_d, P_fa) is
//   T = z(1 − P_fa) + z(P_d)     (z = Φ⁻¹, the standard normal quantile).
// Source: e.g. H. L. Van Trees, Detection, Estimation, and Modulation Theory, Part I (1968), §2.2 (the
// Gaussian "d" = SNR of the likelihood-ratio test); M. I. Skolnik, Introduction to Radar Systems (single
// sample, coherent case). Φ and z from Boost.Math.

#include <cmath>
#include <limits>

namespace radchain::physics {

// Φ(x), the standard normal distribution function.
double standard_normal_cdf(double x);
// Q(x) = 1 − Φ(x), computed without cancellation for large x.
double standard_normal_tail(double x);
// z(p) = Φ⁻¹(p), 0 < p < 1 (z(0.99) = 2.326348). Throws std::domain_error outside (0, 1).
double standard_normal_quantile(double probability);

// The SNR threshold for a required detection probability and an allowed false-alarm probability:
// T = z(1 − P_fa) + z(P_d). T(0.99, 0.01) = 2 z(0.99) = 4.652696.
double snr_threshold_for(double detection_probability, double false_alarm_probability);
// P_d at a given SNR with the decision level set for P_fa: Φ(SNR − z(1 − P_fa)).
double detection_probability_at(double snr, double false_alarm_probability);
// P_fa that a given SNR allows while still reaching P_d: 1 − Φ(SNR − z(P_d)).
double false_alarm_probability_at(double snr, double detection_probability);

// The signal S (electrons) at which S/√(S + c) = T: Poisson noise of the signal itself plus a variance c that does
// not scale with it (dark, read, quantisation, background). S² = T²(S + c), whose positive root is
//   S = (T² + √(T⁴ + 4T²c))/2       (Pan 2010 eq. (11)).
// `variance` is n² = S_at + c at some signal S_at (c = variance − signal_at, as a detector reports it). NaN where no
// positive root exists (c < −T²/4).
// (Inline: a sweep's solver evaluates it for every point.)
inline double signal_at_snr(double threshold, double variance, double signal_at) {
  const double t2 = threshold * threshold;
  const double discriminant = t2 * t2 + 4.0 * t2 * (variance - signal_at);
  if (!(discriminant >= 0)) return std::numeric_limits<double>::quiet_NaN();
  return 0.5 * (t2 + std::sqrt(discriminant));
}

}  // namespace radchain::physics
