// MTF curves of the Kolobrodov design: end points and the matching condition of eq. (11).
#include "radchain/imaging/mtf_curves.hpp"

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
