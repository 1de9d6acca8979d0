// MTF curves of the Kolobrodov design: end points and the matching condition of eq. (11).
#include "radchain/mtf_curves.hpp"
#include "radchain/sensor_file.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

TEST(MtfCurves, KolobrodovComputedDesign) {
  radchain::Chain chain =
      radchain::load_sensor(std::string(RADCHAIN_SOURCE_DIR) + "/sensors/kolobrodov-1996-ccd151-computed.toml");
  const radchain::MtfCurves c = radchain::mtf_curves(chain.run());
  ASSERT_EQ(c.frequency_per_m.size(), 201u);
  EXPECT_DOUBLE_EQ(c.system.front(), 1.0);
  EXPECT_NEAR(c.detector.back(), 0.0, 1e-12);            // first zero of sinc at 1/V_D
  EXPECT_NEAR(c.eta, 0.8, 1e-9);                         // the binding matching criterion: η = η_max
  for (std::size_t i = 0; i < c.system.size(); ++i) {
    EXPECT_LE(c.objective[i], c.diffraction[i] + 1e-12);  // a real objective (η ≤ 1) is below diffraction
    EXPECT_NEAR(c.system[i], c.objective[i] * c.detector[i], 1e-15);
  }
  // Eq. (11): objective and detector both reach 0.5 at ν_x1 = u/V_D (exact root).
  const double nu = 0.6033545644 / c.element_m;
  const double eq7 = 1 - 1.218 * c.f_number * c.wavelength_m * nu / c.eta;
  EXPECT_NEAR(eq7, 0.5, 1e-9);
  const std::string csv = radchain::mtf_curves_csv(c);
  EXPECT_NE(csv.find("frequency_mm-1,diffraction,objective_eq7,detector_eq8,system_eq10\n"), std::string::npos);
}

// The MTF budget of an Earth-observation camera (WorldView-2 pan, giqe criterion), against the closed forms: the
// clear-pupil diffraction MTF (2/π)(acos x − x√(1 − x²)), x = λNν (Goodman 2005 eq. 6-32), the pixel 2/π at
// Nyquist, and a Gaussian jitter exp(−2π²σ²ν²) set on the command line.
TEST(MtfCurves, EarthObservationBudget) {
  radchain::Chain chain = radchain::load_sensor(std::string(RADCHAIN_SOURCE_DIR) + "/sensors/worldview-2-pan.toml",
                                                {{"criteria.iq.jitter_rms", "\"2 um\""}});
  const radchain::Report report = chain.run();
  ASSERT_TRUE(radchain::has_mtf_budget(report));
  const radchain::MtfBudgetCurves c = radchain::mtf_budget_curves(report);
  EXPECT_EQ(c.criterion, "criteria.iq");
  ASSERT_EQ(c.frequency_per_m.size(), 201u);
  const double lambda = 625e-9, n = 13.3 / 1.1, p = 8e-6, sigma = 2e-6, nyquist = 0.5 / p;
  EXPECT_NEAR(c.nyquist_per_m, nyquist, 1e-9);
  EXPECT_NEAR(c.frequency_per_m[100], nyquist, 1e-9);  // Nyquist is the middle grid point
  const radchain::physics::MtfComponents& m = c.components[100];
  const double x = lambda * n * nyquist;
  const double diffraction = 2 / M_PI * (std::acos(x) - x * std::sqrt(1 - x * x));
  EXPECT_NEAR(m.diffraction, diffraction, 1e-9);
  EXPECT_NEAR(m.pixel, 2 / M_PI, 1e-12);
  EXPECT_NEAR(m.jitter, std::exp(-2 * M_PI * M_PI * sigma * sigma * nyquist * nyquist), 1e-12);
  EXPECT_NEAR(m.smear * m.diffusion * m.wavefront * m.tdi * m.atmosphere, 1.0, 1e-12);  // not set in the file
  // The system at Nyquist is the criterion's own mtf_nyquist_system.
  EXPECT_NEAR(m.system(), *report.value("criteria.iq.mtf_nyquist_system"), 1e-12);
  EXPECT_NEAR(m.system(), diffraction * 2 / M_PI * m.jitter, 1e-9);
  const std::string csv = radchain::mtf_budget_csv(c);
  EXPECT_NE(csv.find("frequency_mm-1,diffraction,pixel,jitter,smear,diffusion,wavefront,tdi,atmosphere,system\n"), std::string::npos);
  EXPECT_NE(csv.find("# Nyquist 1/(2p) = 62.5 mm-1"), std::string::npos) << csv.substr(0, 400);
  // Turbulence of r0 = 1.5 m on the 13.3 m focal length: exp(−3.44 (λ f' ν / r0)^(5/3)) = 0.556 at Nyquist (Fried
  // 1966), in the criterion's system MTF and in the budget's curves alike.
  radchain::Chain turbulent = radchain::load_sensor(std::string(RADCHAIN_SOURCE_DIR) + "/sensors/worldview-2-pan.toml",
                                                    {{"criteria.iq.jitter_rms", "\"2 um\""}, {"criteria.iq.fried_parameter", "\"1.5 m\""}});
  const radchain::Report tr = turbulent.run();
  const radchain::MtfBudgetCurves tc = radchain::mtf_budget_curves(tr);
  const double atmosphere = std::exp(-3.44 * std::pow(lambda * 13.3 * nyquist / 1.5, 5.0 / 3.0));
  EXPECT_NEAR(atmosphere, 0.5557, 1e-4);  // x = 0.3464 (by hand): a term that matters, so the comparisons below can fail
  EXPECT_NEAR(tc.components[100].atmosphere, atmosphere, 1e-12);
  EXPECT_NEAR(*tr.value("criteria.iq.mtf_nyquist_system"), m.system() * atmosphere, 1e-12);
  EXPECT_NEAR(tc.components[100].system(), m.system() * atmosphere, 1e-12);
  EXPECT_LT(*tr.value("criteria.iq.rer"), *report.value("criteria.iq.rer"));
  // Kolobrodov's design has no budget.
  radchain::Chain kolobrodov =
      radchain::load_sensor(std::string(RADCHAIN_SOURCE_DIR) + "/sensors/kolobrodov-1996-ccd151-computed.toml");
  EXPECT_FALSE(radchain::has_mtf_budget(kolobrodov.run()));
}
