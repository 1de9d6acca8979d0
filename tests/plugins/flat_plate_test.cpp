// The flat_plate target (one satellite facet, diffuse + specular) against hand computation: the Lambert term
// ρ_d A cos θ_i cos θ_r/(π r²), the Sun's mirror glint ρ_s A cos θ_r/(Ω_sun r²), and a plate at full phase
// against the Lambertian sphere of the same cross-section (1.5×, a classical result of the two phase laws).
#include "radchain/chain.hpp"
#include "radchain/error.hpp"
#include "radchain/sensor_file.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <numbers>
#include <string>

namespace {
using namespace radchain;

// sensors/sbv-smallest-sphere.toml with its target replaced (the SBV telescope and CCD are not under test).
Chain plate_chain(const std::string& target) {
  const std::string path = std::string(RADCHAIN_SOURCE_DIR) + "/sensors/sbv-smallest-sphere.toml";
  std::ifstream in(path);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto begin = text.find("[target]"), end = text.find("[atmosphere]");
  text.replace(begin, end - begin, "[target]\nplugin = \"flat_plate\"\n" + target + "\n");
  text = text.substr(0, text.find("[[solve]]"));
  return load_sensor_text(text, path);
}

// A 10 m² plate, ρ_d = 0.2, ρ_s = 0.5, at 36000 km, phase 30°, normal on the bisector: θ_i = θ_r = 15°.
//   diffuse  0.2 × 10 × cos²15° / (π (3.6e7)²) = 1.8660254 / 4.0715041e15 = 4.58314e-16 → m = −26.73 + 38.3471 = 11.617
//   glint    θ_sun = 6.957e8 / 1.495978707e11 = 4.65047e-3 rad, Ω_sun = π θ_sun² = 6.79427e-5 sr;
//            0.5 × 10 × cos15° / (6.79427e-5 × 1.296e15) = 5.48486e-11 → m = −1.078 (diffuse included)
TEST(FlatPlate, DiffuseAndGlintByHand) {
  Chain chain = plate_chain("area = \"10 m2\"\ndiffuse_reflectance = 0.2\nspecular_reflectance = 0.5\nrange = \"36000 km\"\n"
                            "phase_angle = \"30 deg\"\n");
  chain.evaluate();
  EXPECT_NEAR(chain.result("target.diffuse_fraction"), 4.583135e-16, 1e-21);
  EXPECT_NEAR(chain.result("target.specular_fraction"), 5.484862e-11, 1e-16);
  EXPECT_EQ(chain.result("target.glint"), 1.0);
  EXPECT_NEAR(chain.result("target.magnitude"), -1.0779, 1e-4);
  // Turned by 1°: the reflected beam moves 2° (> θ_sun = 0.266°), no glint; θ_i = 14°, θ_r = 16°.
  chain.set("target.normal_offset", std::numbers::pi / 180);
  chain.evaluate();
  EXPECT_EQ(chain.result("target.glint"), 0.0);
  EXPECT_EQ(chain.result("target.specular_fraction"), 0.0);
  const double diffuse = 0.2 * 10 * std::cos(14 * std::numbers::pi / 180) * std::cos(16 * std::numbers::pi / 180) /
                         (std::numbers::pi * 3.6e7 * 3.6e7);
  EXPECT_NEAR(chain.result("target.diffuse_fraction") / diffuse, 1.0, 1e-12);
  EXPECT_NEAR(chain.result("target.magnitude"), -26.73 - 2.5 * std::log10(diffuse), 1e-9);
  // Seen edge-on from behind (θ_r ≥ 90°): dark.
  chain.set("target.normal_offset", 80 * std::numbers::pi / 180);
  chain.evaluate();
  EXPECT_EQ(chain.result("target.reflected_fraction"), 0.0);
}

TEST(FlatPlate, FullPhaseDiscIsOneAndAHalfLambertSpheres) {
  // A disc of diameter D facing Sun and sensor (α = 0): ρ (π D²/4)/(π r²) = ρ D²/(4 r²); the Lambert sphere of the
  // same D: p (D/2)²/r² with p = 2ρ/3, i.e. ρ D²/(6 r²). Ratio 3/2: the disc is 2.5 lg 1.5 = 0.4402 mag brighter.
  Chain plate = plate_chain("area = \"0.785398163 m2\"\ndiffuse_reflectance = 0.2\nrange = \"1000 km\"\nphase_angle = \"0 deg\"\n");
  plate.evaluate();
  Chain sphere = load_sensor(std::string(RADCHAIN_SOURCE_DIR) + "/sensors/sbv-smallest-sphere.toml",
                             {{"target.diameter", "1 m"}, {"target.phase_angle", "0 deg"}});
  sphere.evaluate();
  EXPECT_NEAR(sphere.result("target.magnitude") - plate.result("target.magnitude"), 2.5 * std::log10(1.5), 1e-8);
}

TEST(FlatPlate, RefusesMoreLightOutThanIn) {
  EXPECT_THROW(plate_chain("area = \"1 m2\"\ndiffuse_reflectance = 0.6\nspecular_reflectance = 0.5\nrange = \"1000 km\"\n"
                           "phase_angle = \"30 deg\"\n"),
               InputError);
}

}  // namespace
