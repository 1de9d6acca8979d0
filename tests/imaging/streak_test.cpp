// Moving targets on rendered frames: the streak a chain predicts is drawn, its PSF-weighted
// SNR measured on many frames agrees with the prediction, and the trailing loss shows.
#include "radchain/error.hpp"
#include "radchain/imaging/render.hpp"
#include "radchain/physics/streak.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

namespace {
using namespace radchain;
using namespace radchain::render;

// examples/rubin-geo-streak.toml with a 1 s exposure: the GEO satellite trails 15.041 × 1 / 0.20006 = 75.18 pixels.
struct Streak {
  Chain chain;
  Report report;
};
Streak rubin_geo_1s() {
  Streak s{load_sensor(std::string(RADCHAIN_SOURCE_DIR) + "/examples/rubin-geo-streak.toml",
                       {{"detector.integration_time", "1 s"}}),
           {}};
  s.report = s.chain.run();
  return s;
}

TEST(RenderStreak, MeasuredStreakSnrAndTrailingLoss) {
  Streak s = rubin_geo_1s();
  StreakCheckOptions o;
  o.trials = 3000;
  const StreakCheck c = check_streak(s.chain, s.report, SpaceFrameOptions{}, o);
  EXPECT_NEAR(c.streak_px, 15.041 / (10e-6 / 10.31 * 180 / std::numbers::pi * 3600), 1e-9);  // 0.20006"/px: 75.18 px
  // The rendered streak's n_eff (1/Σ f² of the frame's expected light) is the chain's: same grid, same PSF.
  EXPECT_NEAR(c.neff / s.report.value("detector.noise_equivalent_area").value(), 1.0, 1e-5);
  EXPECT_NEAR(c.static_neff / s.report.value("detector.static_noise_equivalent_area").value(), 1.0, 1e-5);
  // Measured against the renderer's law for the matched filter, within 4 statistical σ (3000 frames: σ ≈ 0.065).
  EXPECT_TRUE(c.passed(4.0)) << "streak " << c.streak.measured << " vs " << c.streak.predicted << ", still " << c.still.measured
                             << " vs " << c.still.predicted;
  // The chain's SNR (S + n_eff v, SMTN-002) differs from the matched filter's law only by the source's own shot
  // noise (S Σf³/(Σf²)² instead of S): here read noise and sky dominate, so < 1 %; the measured SNR is within 4σ of it.
  EXPECT_NEAR(c.chain_snr / c.streak.predicted, 1.0, 0.01);
  EXPECT_NEAR(c.chain_snr, 5.0, 1e-6);  // rendered at the limiting magnitude (SNR = T = 5)
  EXPECT_LE(std::abs(c.streak.measured - c.chain_snr), 4 * c.streak.sigma + std::abs(c.chain_snr - c.streak.predicted));
  // The trailing loss shows on the frames: the still target's SNR over the streak's at the same magnitude, > 10σ
  // from 0 and within 4σ of the renderer's law (in passed()). It is below the chain's detector.trailing_loss
  // (magnitudes at constant SNR, background-limited): the still target at this magnitude has SNR ≈ 15, where its own
  // shot noise counts.
  EXPECT_GT(c.measured_snr_loss(), 10 * c.snr_loss_sigma());
  EXPECT_GT(c.predicted_snr_loss(), 0.5 * c.chain_trailing_loss);
  EXPECT_LT(c.predicted_snr_loss(), c.chain_trailing_loss);
}

// A still target counted by PSF-weighted photometry (the Rubin r file): the matched filter measured on frames, its
// n_eff the chain's on the same pixel grid, and the chain's S/√(S + n_eff v) rebuilt from the frame's own light and
// per-pixel variance equal to the chain's SNR at the limiting magnitude.
TEST(RenderPsfPhotometry, TheMatchedFilterMeasuresTheChainsStillTarget) {
  Chain chain = load_sensor(std::string(RADCHAIN_SOURCE_DIR) + "/sensors/rubin-lsst-r-m5.toml");
  const Report report = chain.run();
  ASSERT_TRUE(psf_weighted_photometry(report));
  StreakCheckOptions o;
  o.trials = 3000;
  const PsfPhotometryCheck c = check_psf_photometry(chain, report, SpaceFrameOptions{}, o);
  EXPECT_NEAR(c.neff / report.value("detector.noise_equivalent_area").value(), 1.0, 1e-5);
  EXPECT_NEAR(c.chain_snr, 5.0, 1e-6);
  EXPECT_NEAR(c.chain_form_snr / c.chain_snr, 1.0, 1e-4);
  // The matched filter's law is lower only by the source's own shot noise (< 1 % at SNR 5, background-limited).
  EXPECT_LT(c.still.predicted, c.chain_form_snr);
  EXPECT_GT(c.still.predicted, 0.99 * c.chain_form_snr);
  EXPECT_TRUE(c.passed(4.0)) << c.still.measured << " ± " << c.still.sigma << " vs " << c.still.predicted;
  // Window photometry is not PSF-weighted: the same file counting a 5×5 window.
  Chain window = load_sensor(std::string(RADCHAIN_SOURCE_DIR) + "/sensors/rubin-lsst-r-m5.toml",
                             {{"detector.photometry", "window"}, {"detector.window_pixels", "5"}});
  EXPECT_FALSE(psf_weighted_photometry(window.run()));
  // A frame is one exposure: co-adds are refused at their result, not drawn as one frame.
  Chain coadded = load_sensor(std::string(RADCHAIN_SOURCE_DIR) + "/sensors/rubin-lsst-r-m5.toml", {{"detector.exposures", "4"}});
  try {
    check_psf_photometry(coadded, coadded.run(), SpaceFrameOptions{}, o);
    ADD_FAILURE() << "4 co-added exposures rendered as one frame";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("detector.exposures"), std::string::npos) << e.what();
  }
}

TEST(RenderStreak, DrawsTheStreakAndRefusesOneLongerThanTheFrame) {
  Streak s = rubin_geo_1s();
  SpaceFrameOptions o;
  o.width = 200;
  o.height = 40;
  o.noise = NoiseTerms::none();
  const SpaceFrameRenderer r(space_frame_setup(s.chain, s.report, o));
  const Image e = r.expected_electrons();
  // The target's electrons are all on the frame, spread over the streak: along the centre row the middle of the
  // streak is flat (s_i = 1/L there, physics/streak.hpp), and nothing is left beyond its end.
  const double background = e(0, 0), total = r.setup().sources.at(0).electrons;
  double sum = 0;
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 200; ++x) sum += e(x, y) - background;
  EXPECT_NEAR(sum / total, 1.0, 1e-4);
  EXPECT_NEAR(e(100, 20) - background, e(120, 20) - background, 1e-4 * (e(100, 20) - background));
  EXPECT_NEAR(e(150, 20) - background, 0.0, 1e-6 * total);  // 12 pixels (7σ) past its end at 138.1
  bool found = false;
  for (const auto& card : r.header(1))
    if (card.key == "STREAK") found = true;
  EXPECT_TRUE(found);
  o.width = 60;  // the 75-pixel streak does not fit
  try {
    space_frame_setup(s.chain, s.report, o);
    ADD_FAILURE() << "a streak longer than the frame was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("longer than the frame (60 pixels wide)"), std::string::npos) << e.what();
  }
}

}  // namespace
