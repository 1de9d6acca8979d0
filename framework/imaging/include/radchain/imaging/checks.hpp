#pragma once
// Closed loop: render what the model predicts, measure it as an observer would, and compare. Small sizes run as
// tests (tests/render), full sizes under `radchain validate`.
//
// (a) Detection (point-target sensors). The simulated detector: a window of n×n pixels (n² = the chain's
//     detector.window_pixel_count, 1 for Pan 2010) centred on the pixel that holds a target at a known
//     position; the statistic is the window's electrons with the known background removed,
//       X = g · Σ_window (DN − offset) − n² (N_d + B_sky),
//     and the decision "detected" is X > γ σ₀, where σ₀² = n² − S is the chain's noise without the target
//     (detector.noise_electrons² − detector.signal_electrons) and γ the threshold in those noise units. With the
//     ADC, X moves in steps of g: the decision level is put half-way between two of its values (nearest to γσ₀)
//     and γ is that level over σ₀, so that the continuous prediction and the discrete measurement are the same
//     quantity (without this, where the level falls between two steps moves a Gaussian prediction of P_fa = 1 %
//     by up to ±0.3 % at the SBV's 16-bit setting, and the comparison would test the rounding, not the model).
//     The Gaussian criterion behind Pan 2010 eq. (10) predicts
//       P_fa = 1 − Φ(γ),      P_d = Φ((S − γ σ₀) / n),
//     (with n = σ₀ this is Φ(SNR − γ)). Pan's T = 5 is a threshold on S/n, not on X: at SNR = T and
//     γ = z(1 − P_fa) the test reaches P_d = Φ((T n − γ σ₀)/n) ≥ Φ(T − γ). Measured: the fraction of frames
//     with X > γσ₀ at the target (P_d) and in target-free windows of the same frames (P_fa), each with its
//     binomial error √(p(1−p)/N). Beside the Gaussian prediction the check computes the exact law of X under
//     the renderer's model (Poisson ⊛ normal through the ADC, convolved over the window), which shows how far
//     the Gaussian criterion is from the counting statistics it stands for.
// (b) Slanted edge (pushbroom sensors): ISO 12233:2017 e-SFR style on a noise-free rendered edge at ≈ 5°: per
//     row the edge position (centroid of the derivative), a least-squares line, every pixel's distance to it
//     along the normal, binned 4× finer than the pixels, the ESF differenced, Hamming-windowed and Fourier
//     transformed (FFTW); divided by the transfer of the central difference sin(2πνΔ)/(2πνΔ) and of the bin
//     width sinc(νΔ), Δ = ¼ pixel. Compared with system_mtf() along the edge normal, times the scene's own
//     pixel box sinc(ν · input sampling).
// (c) Flat fields: the measured SNR and noise of uniform frames against the chain's noise budget.
// (d) Streaks (moving targets): PSF-weighted photometry of a streak — the matched filter
//     F̂ = Σ w_i (e_i − B_i), w_i = f_i / Σ f_j² with f_i the rendered streak's pixel fractions (from the frame's
//     own expected electrons), which is unbiased (Σ w_i f_i = 1) — over many frames: measured SNR = mean/std of F̂
//     against the renderer's own law, S / √(Σ w_i² (S f_i + B + N_d + σ_read² + g²/12)), and against the chain's
//     detector.snr = S / √(S + n_eff v) (SMTN-002's form, n_eff = 1/Σ f_i²; it counts the source's own shot noise
//     as S where the matched filter has S Σf³/(Σf²)², 4/3 S for a Gaussian, so the two agree where the sky
//     dominates). The same target not moving gives the still SNR; 2.5 lg(SNR_still/SNR_streak) at the same
//     magnitude is the loss as rendered. It equals the chain's detector.trailing_loss (1.25 lg of the n_eff ratio:
//     magnitudes at constant SNR) only where the sky dominates both: the still target's own shot noise lowers it.
#include "radchain/chain.hpp"
#include "radchain/imaging/earth_scene.hpp"
#include "radchain/imaging/space_frame.hpp"

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace radchain::render {

// A measured rate against its predictions.
struct Rate {
  long trials = 0, count = 0;
  double measured = 0;    // count / trials
  double predicted = 0;   // Gaussian criterion
  double exact = 0;       // the renderer's own law
  double binomial_sigma() const;  // √(p(1 − p)/N) at the predicted p (at least 1/N)
  double z_predicted() const;     // (measured − predicted) / binomial_sigma
  double z_exact() const;         // (measured − exact) / √(exact(1 − exact)/N)
};

struct DetectionCheckOptions {
  long trials = 20000;        // frames
  int frame_size = 16;        // pixels (square); the target sits in the centre pixel
  double threshold_sigma = 2.3263478740408408;  // γ = z(0.99): the paper's P_fa ≤ 1 %
  std::uint64_t seed = 1;
  // How many target-free windows per frame go into P_fa (they are independent): 1 keeps the binomial error of
  // P_fa comparable with that of P_d; 0 = every window that no source light reaches.
  int false_alarm_windows_per_frame = 1;
};

struct DetectionCheck {
  double magnitude = 0;         // the limiting magnitude rendered
  double signal_electrons = 0;  // S in the window: chain (detector.signal_electrons)
  double rendered_signal_electrons = 0;  // the rendered expected window sum (S from the frame's own ePSF)
  double noise_electrons = 0;   // n: chain
  double noise_only_electrons = 0;  // σ₀
  double snr = 0, threshold_T = 0;
  double threshold_sigma = 0;            // γ as asked
  double effective_threshold_sigma = 0;  // γ at the decision level used (half-way between two window sums with the ADC)
  int window = 1;               // n
  Rate detection, false_alarm;
  // Every rate within `max_z` binomial sigmas of its Gaussian prediction, and the rendered signal within 1 %
  // of the chain's.
  bool passed(double max_z = 4.0) const;
};

// (a) at the limiting magnitude. `frame` gives the geometry/PSF/noise options (its targets and stars are
// replaced by the one target). The chain must have run (report).
DetectionCheck check_detection(Chain& chain, const Report& report, SpaceFrameOptions frame,
                               const DetectionCheckOptions& options = {});

// ISO 12233-style slanted-edge MTF of an image holding one near-vertical edge.
struct EdgeMtf {
  double angle_deg = 0;                  // edge angle from the vertical (fitted)
  std::vector<double> frequency_per_px;  // cycles per pixel along the edge normal, 0 … 1
  std::vector<double> mtf;
};
EdgeMtf slanted_edge_mtf(const Image& image, int oversampling = 4);

struct EdgeCheckOptions {
  int output_size = 96;          // output pixels (square)
  int input_oversampling = 8;    // input samples per output sample
  double edge_angle_deg = 5.0;
  double tolerance = 0.05;       // relative, up to Nyquist
};
struct EdgeCheck {
  double angle_deg = 0;
  std::vector<double> frequency_per_px, measured, model;  // up to Nyquist (0.5 cycles per pixel)
  double max_relative_error = 0;    // max |measured / model − 1| up to Nyquist
  double mtf_at_nyquist_measured = 0, mtf_at_nyquist_model = 0;
  double tolerance = 0.05;
  bool passed() const { return max_relative_error <= tolerance; }
};
// (b): renders make_edge_scene() without noise or ADC (input sampling = output sampling / input_oversampling).
EdgeCheck check_edge_mtf(Chain& chain, const Report& report, EarthSceneOptions scene, const EdgeCheckOptions& options = {});

struct FlatFieldCheck {
  std::string what;          // "earth: Δρ step" / "space: flat field"
  long samples = 0;          // pixels (or windows) measured
  double measured_snr = 0;   // measured mean signal / measured noise
  double chain_snr = 0;      // the report's SNR
  double predicted_snr = 0;  // the chain's budget with the renderer's quantisation noise
  double snr_sigma = 0;      // statistical error of the measured SNR
  double measured_noise = 0, predicted_noise = 0;  // electrons (space) or J m-2 (earth), per window/pixel
  std::string measured_label;  // what the measured SNR is of, for the report line ("measured SNR of Δρ")
  std::string noise_unit;      // "e-" or "J m-2"
  bool passed(double max_z = 4.0) const;  // |measured − predicted| ≤ max_z σ
};
// (c), pushbroom: flat fields at ρ_0 and ρ_0 + Δρ (the target's), size×size output pixels; with a datasheet
// detector (electron radiometry) one flat field at the chain's reflectance against its detector.snr.
FlatFieldCheck check_earth_flat_field(Chain& chain, const Report& report, EarthSceneOptions scene, int size = 256,
                                      std::uint64_t seed = 1);
// (c), point target: a flat field of S/n² electrons per pixel (the limiting-magnitude signal spread evenly),
// measured over n×n windows: SNR of the window sum against the report's detector.snr.
FlatFieldCheck check_space_flat_field(Chain& chain, const Report& report, SpaceFrameOptions frame, int size = 256,
                                      std::uint64_t seed = 1);

struct StreakCheckOptions {
  long trials = 2000;  // frames (each with the moving and the still target)
  int height = 0;      // rows; 0: 16σ + 8 (the width: the streak + 16σ + 8)
  std::uint64_t seed = 1;
};
struct StreakSnr {
  double predicted = 0;  // the renderer's law for the matched filter
  double measured = 0;   // mean / std over the frames
  double sigma = 0;      // statistical error of `measured`: √(1/N + SNR²/(2N))
  double z() const { return (measured - predicted) / sigma; }
};
struct StreakCheck {
  double magnitude = 0, streak_px = 0, signal_electrons = 0, neff = 0, static_neff = 0;
  double chain_snr = 0, chain_trailing_loss = 0;  // detector.snr, detector.trailing_loss
  long trials = 0;
  StreakSnr streak, still;
  // 2.5 lg(SNR_still / SNR_streak) at the same magnitude: measured, by the renderer's law, and its statistical error.
  double measured_snr_loss() const { return 2.5 * std::log10(still.measured / streak.measured); }
  double predicted_snr_loss() const { return 2.5 * std::log10(still.predicted / streak.predicted); }
  double snr_loss_sigma() const;
  bool passed(double max_z = 4.0) const;  // both SNRs and the SNR loss within max_z σ of the renderer's law
};
// (d) at the limiting magnitude, the streak of the chain's detector.target_streak_pixels (refused when 0).
StreakCheck check_streak(Chain& chain, const Report& report, SpaceFrameOptions frame, const StreakCheckOptions& options = {});

// (e) PSF-weighted photometry of a still target (emva1288 photometry = "psf", whose signal is the whole image
// counted over n_eff pixels: a square window does not measure it). The target at the limiting magnitude on
// `trials` frames, measured by the matched filter against the renderer's law (the same weights, each pixel's
// variance). The chain counts S/√(S + n_eff v) (SMTN-002), which differs from the matched filter's law only in the
// source's own shot noise (S Σf³/(Σf²)² instead of S: up to 4/3 of it for a source-limited Gaussian); that form,
// evaluated on the frame's own n_eff and per-pixel variance v, must be the chain's SNR to `tolerance`.
struct PsfPhotometryCheck {
  double magnitude = 0, signal_electrons = 0;
  double neff = 0, chain_neff = 0;  // 1/Σ f_i² of the rendered PSF; detector.noise_equivalent_area
  double chain_snr = 0;             // detector.snr at the limiting magnitude
  double chain_form_snr = 0;        // S/√(S + n_eff v) on the frame
  long trials = 0;
  StreakSnr still;
  double tolerance = 1e-3;
  bool fixed_pattern = false;  // the chain counts DSNU/PRNU, which point-target frames do not render: not compared
  bool chain_agrees() const { return std::abs(chain_form_snr / chain_snr - 1.0) <= tolerance; }
  bool passed(double max_z = 4.0) const;  // measured within max_z σ of the renderer's law; the chain's form agrees
};
// True when the detector says its photometry is PSF-weighted (detector.psf_weighted = 1).
bool psf_weighted_photometry(const Report& report);
PsfPhotometryCheck check_psf_photometry(Chain& chain, const Report& report, SpaceFrameOptions frame,
                                        const StreakCheckOptions& options = {});

}  // namespace radchain::render
