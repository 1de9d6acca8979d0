// The MTF at Nyquist of every catalogue imager with an MTF budget, against O'Neill's (1956) closed form of the
// annular pupil's MTF (tests/core/physics/mtf_references.hpp; the library computes it from disc overlaps, and its
// physics tests hold the two together): the diffraction component at ν = 1/(2p), i.e. x = ν/ν_c = λN/(2p) with the
// file's λ, N = f'/D and ε, and the system MTF as that × the pixel's |sinc(π p ν)| = 2/π × the other components.
// What this checks is the catalogue plumbing — each file's values reach the MTF budget as the physics expects.
// (These were [expected] rows of the sensor files, "hand computation": a check of the code, not of a publication,
// so it lives here; the catalogue's checks are published figures only.)
#include "../core/physics/mtf_references.hpp"
#include "radchain/chain.hpp"
#include "radchain/sensor_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <numbers>
#include <set>
#include <string>

namespace {

namespace fs = std::filesystem;

TEST(EoImagerMtf, NyquistMtfOfEveryImagerAgainstONeill) {
  std::set<std::string> checked;
  for (const auto& entry : fs::directory_iterator(std::string(RADCHAIN_SOURCE_DIR) + "/sensors")) {
    if (entry.path().extension() != ".toml") continue;
    radchain::Chain chain = radchain::load_sensor(entry.path().string());
    const radchain::Report report = chain.run();
    const auto diffraction = report.value("criteria.iq.mtf_nyquist_diffraction");
    if (!diffraction) continue;
    const std::string name = entry.path().stem().string();
    const double D = report.value("optics.aperture").value(), f = report.value("optics.focal_length").value();
    const double epsilon = report.value("optics.obscuration").value();
    const double lambda = report.value("criteria.iq.mtf_wavelength").value(), p = report.value("criteria.iq.sample_pitch").value();
    const double expected_diffraction = radchain::test::oneill_annular_mtf(lambda * (f / D) / (2 * p), epsilon);
    EXPECT_NEAR(*diffraction, expected_diffraction, 1e-9) << name;
    const double other = report.value("criteria.iq.mtf_nyquist_other").value();
    EXPECT_NEAR(report.value("criteria.iq.mtf_nyquist_system").value(), expected_diffraction * (2 / std::numbers::pi) * other, 1e-9)
        << name;
    checked.insert(name);
  }
  // Every imager of the catalogue with an MTF budget: none may drop out silently.
  const std::set<std::string> imagers = {"ikonos-2-pan",       "ikonos-2-pan-27deg", "landsat-8-oli-b2",      "landsat-8-tirs-b10",
                                         "pleiades-1a-hiri-pan", "seahawk-hawkeye-b4", "sentinel-2a-msi-b4",   "sentinel-2a-msi-b8",
                                         "worldview-2-pan",    "worldview-2-pan-20deg"};
  for (const auto& imager : imagers) EXPECT_TRUE(checked.count(imager)) << imager << " has no MTF budget any more";
}

}  // namespace
