// The extended-scene functions of physics/emva1288.hpp by hand: the pixel's projected solid
// angle π(1 − ε²)/(4N²), the uniform-scene noise variance with binning and co-adds (EMVA 1288 eqs. 5, 6, 18),
// the responsivity k and the saturation radiance.
#include "radchain/physics/emva1288.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

namespace {
using namespace radchain;

TEST(PhysicsEmva1288Extended, EtendueNoiseAndSaturationByHand) {
  EXPECT_NEAR(physics::pixel_projected_solid_angle_sr(4.0), std::numbers::pi / 64.0, 1e-16);
  EXPECT_NEAR(physics::pixel_projected_solid_angle_sr(4.0, 0.5), 0.75 * std::numbers::pi / 64.0, 1e-16);
  // PRNU of b² independent native pixels: s_g² S₁²/b²; DSNU b² σ_o²; over M frames in amplitude.
  EXPECT_NEAR(physics::emva_uniform_scene_variance_e2(1000.0, 100.0, 3.0, 0.01, 2.0, 3.0),
              3.0 * (1000.0 + 400.0) + 9.0 * (4.0 * 9.0 + 1e-4 * 1e6 / 4.0), 1e-9);
  EXPECT_NEAR(physics::saturation_radiance(1000.0, 100.0, 9.0), 100.0, 1e-12);
  EXPECT_EQ(physics::saturation_radiance(1000.0, 2000.0, 9.0), 0.0);
}

// PRNU of a TDI and binned sample, against the textbook form simulated: the sample sums b² N_tdi different native
// pixels, each receiving S₁/(b² N_tdi) times a gain 1 + s_g g_i with g_i independent N(0, 1) (EMVA 1288 §2.4 defines
// s_g per pixel). The spread of that sum over many draws of the gains is the PRNU noise; the variance function's
// spatial term (no temporal noise, no DSNU, one exposure) must match it to the Monte Carlo's 2 % (4 standard
// errors of a standard deviation from 20000 draws: 4/√(2·20000) = 2.8 %).
TEST(PhysicsEmva1288Extended, PrnuOfATdiAndBinnedSampleAveragesItsPixels) {
  std::mt19937_64 random(12345);
  std::normal_distribution<double> gain(0.0, 1.0);
  const double s_g = 0.01, signal = 1e5;
  for (auto [b, tdi] : {std::pair{1.0, 1.0}, std::pair{1.0, 64.0}, std::pair{2.0, 8.0}, std::pair{3.0, 32.0}}) {
    const int pixels = static_cast<int>(b * b * tdi);
    const int draws = 20000;
    double sum = 0, sum2 = 0;
    for (int k = 0; k < draws; ++k) {
      double sample = 0;
      for (int i = 0; i < pixels; ++i) sample += signal / pixels * (1.0 + s_g * gain(random));
      sum += sample, sum2 += sample * sample;
    }
    const double simulated = std::sqrt(sum2 / draws - (sum / draws) * (sum / draws));
    const double modelled = std::sqrt(physics::emva_uniform_scene_variance_e2(signal, 0.0, 0.0, s_g, b, 1.0, tdi) - signal);
    EXPECT_NEAR(modelled / simulated, 1.0, 0.028) << b << "x" << b << " binning, " << tdi << " TDI stages";
    EXPECT_NEAR(modelled, s_g * signal / std::sqrt(b * b * tdi), 1e-9 * signal);
  }
}

TEST(PhysicsEmva1288Extended, ResponsivityIsTheEtendueCount) {
  // k = N t p² Ω τ ∫η λ/(hc): 4 stages, 1 ms, 10 µm, f/4, τ 0.5, 1e10 electrons s-1 per W m-2 m-1.
  const double omega = physics::pixel_projected_solid_angle_sr(4.0);
  EXPECT_NEAR(physics::radiance_responsivity_e(4.0, 1e-3, 10e-6, omega, 0.5, 1e10),
              4.0 * 1e-3 * 1e-10 * std::numbers::pi / 64.0 * 0.5 * 1e10, 1e-18);
}

}  // namespace
