// The MTF at Nyquist of every catalogue imager with an MTF budget, against an independent reference: the diffraction
// MTF as the normalised overlap area of the pupil and its copy shifted by λ f' ν (Goodman, Introduction to Fourier
// Optics, 3rd ed., §6.3: the OTF of an aberration-free system is the pupil's normalised autocorrelation), here with
// the annulus' overlap from circle–circle intersection areas — not O'Neill's closed form the plugin uses. The
// system MTF at Nyquist is that × the pixel's |sinc(π p ν)| = 2/π × the other components the file declares.
// (These were [expected] rows of the sensor files, "hand computation": a check of the code, not of a publication,
// so it lives here; the catalogue's checks are published figures only.)
#include "radchain/chain.hpp"
#include "radchain/sensor_file.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>

namespace {

namespace fs = std::filesystem;

// Area common to two discs of radii r1, r2 whose centres are d apart.
double disc_overlap(double r1, double r2, double d) {
  if (d >= r1 + r2) return 0;
  if (d <= std::abs(r1 - r2)) return std::numbers::pi * std::min(r1, r2) * std::min(r1, r2);
  const double a1 = std::acos((d * d + r1 * r1 - r2 * r2) / (2 * d * r1));
  const double a2 = std::acos((d * d + r2 * r2 - r1 * r1) / (2 * d * r2));
  return r1 * r1 * a1 + r2 * r2 * a2 - 0.5 * std::sqrt((-d + r1 + r2) * (d + r1 - r2) * (d - r1 + r2) * (d + r1 + r2));
}

// The annulus (outer radius 1, inner ε) overlapping its copy shifted by d, over the annulus' area:
// A∩A' = O(1,1) − 2·O(1,ε) + O(ε,ε) (inclusion–exclusion over the discs).
double annulus_mtf(double epsilon, double d) {
  const double overlap = disc_overlap(1, 1, d) - 2 * disc_overlap(1, epsilon, d) + disc_overlap(epsilon, epsilon, d);
  return overlap / (std::numbers::pi * (1 - epsilon * epsilon));
}

TEST(EoImagerMtf, NyquistMtfOfEveryImagerAgainstPupilOverlap) {
  int checked = 0;
  for (const auto& entry : fs::directory_iterator(std::string(RADCHAIN_SOURCE_DIR) + "/sensors")) {
    if (entry.path().extension() != ".toml") continue;
    radchain::Chain chain = radchain::load_sensor(entry.path().string());
    const radchain::Report report = chain.run();
    const auto diffraction = report.value("criteria.iq.mtf_nyquist_diffraction");
    if (!diffraction) continue;
    const std::string name = entry.path().filename().string();
    const double D = report.value("optics.aperture").value(), f = report.value("optics.focal_length").value();
    const double epsilon = report.value("optics.obscuration").value();
    const double lambda = report.value("criteria.iq.mtf_wavelength").value(), p = report.value("criteria.iq.sample_pitch").value();
    // At ν = 1/(2p) on the focal plane the pupil copies are λ f' ν apart: in units of the pupil radius D/2,
    // d = 2 λ f' ν / D = λ N / p.
    const double d = lambda * (f / D) / p;
    const double expected_diffraction = annulus_mtf(epsilon, d);
    EXPECT_NEAR(*diffraction, expected_diffraction, 1e-9) << name;
    const double other = report.value("criteria.iq.mtf_nyquist_other").value();
    EXPECT_NEAR(report.value("criteria.iq.mtf_nyquist_system").value(), expected_diffraction * (2 / std::numbers::pi) * other, 1e-9)
        << name;
    ++checked;
  }
  EXPECT_GE(checked, 8);  // the EO imagers of the catalogue (issue 14 item 7)
}

// The reference itself: a clear pupil's overlap is Goodman's (2/π)[acos x − x√(1−x²)] with x = d/2; an annulus is 1
// at d = 0 and 0 beyond d = 2, and a thin one keeps more contrast near cut-off than the clear pupil.
TEST(EoImagerMtf, PupilOverlapReference) {
  for (double d : {0.0, 0.1, 0.5, 1.0, 1.7, 2.0}) {
    const double x = d / 2;
    EXPECT_NEAR(annulus_mtf(0, d), (2 / std::numbers::pi) * (std::acos(x) - x * std::sqrt(1 - x * x)), 1e-14) << d;
  }
  EXPECT_NEAR(annulus_mtf(0.3, 0), 1.0, 1e-14);
  EXPECT_EQ(annulus_mtf(0.3, 2.0), 0.0);
  // A thin annulus keeps contrast at high frequencies where the clear pupil has lost it (ε = 0.9, d = 1.9).
  EXPECT_GT(annulus_mtf(0.9, 1.9), annulus_mtf(0, 1.9));
}

}  // namespace
