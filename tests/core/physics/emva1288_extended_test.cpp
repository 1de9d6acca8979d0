// The extended-scene functions of physics/emva1288.hpp (issue 14, item 3) by hand: the pixel's projected solid
// angle π(1 − ε²)/(4N²), the uniform-scene noise variance with binning and co-adds (EMVA 1288 eqs. 5, 6, 18),
// the responsivity k and the saturation radiance.
#include "radchain/physics/emva1288.hpp"

#include <gtest/gtest.h>

#include <numbers>

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

TEST(PhysicsEmva1288Extended, ResponsivityIsTheEtendueCount) {
  // k = N t p² Ω τ ∫η λ/(hc): 4 stages, 1 ms, 10 µm, f/4, τ 0.5, 1e10 electrons s-1 per W m-2 m-1.
  const double omega = physics::pixel_projected_solid_angle_sr(4.0);
  EXPECT_NEAR(physics::radiance_responsivity_e(4.0, 1e-3, 10e-6, omega, 0.5, 1e10),
              4.0 * 1e-3 * 1e-10 * std::numbers::pi / 64.0 * 0.5 * 1e10, 1e-18);
}

}  // namespace
