// The closed loop at small size: rendered frames measured as an observer would, against the chain's predictions.
#include "radchain/imaging/render.hpp"
#include "render_test_helpers.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace {
using namespace radchain;
using namespace radchain::render;
using radchain::render_tests::load;
using radchain::render_tests::sbv_fine_adc;

TEST(RenderClosedLoop, DetectionRatesAtTheLimitingMagnitude) {
  // Pan 2010: SNR = T = 5 at the limit; decision level γ = z(0.99) (P_fa = 1 %) on the window statistic.
  auto sbv = sbv_fine_adc();
  DetectionCheckOptions d;
  d.trials = 20000;
  const DetectionCheck c = check_detection(sbv.chain, sbv.report, SpaceFrameOptions{}, d);
  EXPECT_NEAR(c.snr, 5.0, 1e-6);
  EXPECT_NEAR(c.rendered_signal_electrons, c.signal_electrons, 1e-9 * c.signal_electrons);
  // The decision level sits half-way between two DN values, within half a step (1e5/65536 e-) of γσ₀.
  EXPECT_NEAR(c.effective_threshold_sigma, 2.3263478740, 0.5 * 1e5 / 65536.0 / c.noise_only_electrons + 1e-12);
  EXPECT_NEAR(c.false_alarm.predicted, 0.5 * std::erfc(c.effective_threshold_sigma / std::sqrt(2.0)), 1e-12);
  EXPECT_GT(c.detection.predicted, 0.99);  // the paper's P_d ≥ 99 % holds
  EXPECT_TRUE(c.passed(4.0)) << "P_d " << c.detection.measured << " vs " << c.detection.predicted << " (z " << c.detection.z_predicted()
                             << "), P_fa " << c.false_alarm.measured << " vs " << c.false_alarm.predicted << " (z "
                             << c.false_alarm.z_predicted() << ")";
  EXPECT_LE(std::abs(c.detection.z_exact()), 4.0);
  EXPECT_LE(std::abs(c.false_alarm.z_exact()), 4.0);
}

TEST(RenderClosedLoop, FalseAlarmsAgainstTheExactLaw) {
  // Every target-free pixel of every frame (~1.3 M windows): the renderer's own law to < 1e-4, and the Gaussian
  // criterion's P_fa off by what the Poisson skew of the dark current makes of the tail.
  auto sbv = sbv_fine_adc();
  DetectionCheckOptions d;
  d.trials = 5000;
  d.false_alarm_windows_per_frame = 0;
  d.threshold_sigma = 3.0;  // a decision level where P_d is not 1 either
  const DetectionCheck c = check_detection(sbv.chain, sbv.report, SpaceFrameOptions{}, d);
  EXPECT_GT(c.false_alarm.trials, 1000000);
  EXPECT_LE(std::abs(c.false_alarm.z_exact()), 4.0) << c.false_alarm.measured << " vs exact " << c.false_alarm.exact;
  EXPECT_LE(std::abs(c.detection.z_exact()), 4.0) << c.detection.measured << " vs exact " << c.detection.exact;
  EXPECT_GT(c.false_alarm.exact, c.false_alarm.predicted);  // the skewed tail is heavier than the Gaussian one
}

TEST(RenderClosedLoop, SlantedEdgeMatchesTheSystemMtf) {
  auto k = load("kolobrodov-1996-ccd151-computed.toml");
  for (const OpticsMtf optics : {OpticsMtf::diffraction, OpticsMtf::kolobrodov_eq7}) {
    EarthSceneOptions scene;
    scene.optics = optics;
    const EdgeCheck c = check_edge_mtf(k.chain, k.report, scene);
    EXPECT_NEAR(c.angle_deg, 5.0, 0.05);
    EXPECT_TRUE(c.passed()) << to_string(optics) << ": max deviation " << c.max_relative_error;
    EXPECT_GT(c.frequency_per_px.size(), 10u);
    EXPECT_NEAR(c.frequency_per_px.back(), 0.5, 0.02);
  }
}

TEST(RenderClosedLoop, FlatFieldSnrMatchesTheNoiseBudget) {
  auto k = load("kolobrodov-1996-ccd151-computed.toml");
  const FlatFieldCheck earth = check_earth_flat_field(k.chain, k.report, EarthSceneOptions{}, 256, 3);
  EXPECT_TRUE(earth.passed(4.0)) << earth.measured_snr << " vs " << earth.predicted_snr << " ± " << earth.snr_sigma;
  // The 12-bit ADC over H_m = 2500 NEE adds (q/NEE)²/12 = 3 % to the variance of the NEE-only budget.
  EXPECT_NEAR(earth.predicted_snr / earth.chain_snr, 1.0 / std::sqrt(1.0 + std::pow(2500.0 / 4096.0, 2) / 12.0), 1e-9);

  auto sbv = sbv_fine_adc();
  const FlatFieldCheck space = check_space_flat_field(sbv.chain, sbv.report, SpaceFrameOptions{}, 256, 4);
  EXPECT_TRUE(space.passed(4.0)) << space.measured_snr << " vs " << space.predicted_snr << " ± " << space.snr_sigma;
  EXPECT_NEAR(space.predicted_snr, space.chain_snr, 1e-9);  // EMVA quantisation: the chain's budget is the frame's
}

}  // namespace
