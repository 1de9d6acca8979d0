// Kolobrodov 1996 utilisation coefficients k_i (2854 K reference lamp) and k_c (the Sun, working band
// 0.5-0.76 µm) for the shipped silicon curves, under each reading of the definition. The table printed here
// is docs/utilisation-coefficients.md; the expected values are the ones documented there (4 decimals).
//   printed: k_i = 0.187, k_c = 0.852, k_i/k_c = 0.22 (H_nr = 0.22 H_nt).
#include "radchain/constants.hpp"
#include "radchain/physics/band.hpp"
#include "radchain/spectrum_csv.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

namespace {
using namespace radchain;
using namespace radchain::physics;

const std::string spectra = std::string(RADCHAIN_SOURCE_DIR) + "/spectra/";
constexpr double um = 1e-6;
constexpr WavelengthRange working_band{0.5 * um, 0.76 * um};  // Kolobrodov 1996 λ1..λ2

struct Coefficients {
  double k_i, k_c;
  double ratio() const { return k_i / k_c; }
};

struct Documented {
  double k_i, k_c, ratio;  // as written in docs/utilisation-coefficients.md (4 decimals)
};

// The readings of k = ∫ S s_rel dλ / ∫ S dλ (docs/utilisation-coefficients.md):
//   band/band    numerator and denominator over the working band
//   band/whole   numerator over the working band, denominator over the whole source spectrum
//   whole/whole  numerator over the detector's whole response, denominator over the whole source spectrum
//   calibration  k_i whole/whole (the lamp calibration sees the detector's whole response),
//                k_c band/band (the working exposure is the in-band solar exposure)
enum class Reading { band_band, band_whole, whole_whole, calibration };

struct Case {
  const char* curve;
  const char* response;  // how the curve is read
  Reading reading;
  Documented documented;
};

struct Sources {
  Spectrum lamp = blackbody_exitance_spectrum(2854.0, constants::second_radiation_ipts48_m_K);  // Kolobrodov's 2854 K lamp
  Spectrum sun = load_spectrum_csv(spectra + "am0_astm_e490_00a.csv", "W m-2 m-1").spectrum;
};

const Sources& sources() {
  static const Sources s;
  return s;
}

// The response as used in the integral, and whether the integrals count energy or photons.
std::pair<Spectrum, Counting> response(const std::string& curve, const std::string& reading) {
  if (curve == "fairchild") {
    // 9 points, linearly interpolated by Spectrum (the source toolbox used a cubic spline).
    const Spectrum r = load_spectrum_csv(spectra + "ccd_front_illuminated_fairchild_relative.csv", "1").spectrum;
    if (reading == "per-watt") return {normalised_to_peak(r), Counting::energy};
    return {normalised_to_peak(r), Counting::photons};  // read as a relative QE
  }
  const Spectrum qe = load_spectrum_csv(spectra + "ccd_back_illuminated_hamamatsu_S10420-01_qe.csv", "1").spectrum;
  if (reading == "per-watt") return {per_watt_relative_response(qe), Counting::energy};  // ∝ QE λ, peak 1
  return {normalised_to_peak(qe), Counting::photons};
}

Coefficients compute(const std::string& curve, const std::string& reading_of_response, Reading reading) {
  // (not a structured binding: clang 14, the fuzz and ASan compiler, cannot capture one in the lambda below)
  const auto response_and_counting = response(curve, reading_of_response);
  const Spectrum& r = response_and_counting.first;
  const Counting counting = response_and_counting.second;
  const Spectrum& lamp = sources().lamp;
  const Spectrum& sun = sources().sun;
  auto k = [&](const Spectrum& s, bool band_numerator, bool band_denominator) {
    return utilisation_coefficient(s, r, band_numerator ? working_band : support(r),
                                   band_denominator ? working_band : support(s), counting);
  };
  switch (reading) {
    case Reading::band_band: return {k(lamp, true, true), k(sun, true, true)};
    case Reading::band_whole: return {k(lamp, true, false), k(sun, true, false)};
    case Reading::whole_whole: return {k(lamp, false, false), k(sun, false, false)};
    case Reading::calibration: return {k(lamp, false, false), k(sun, true, true)};
  }
  return {};
}

const char* name(Reading r) {
  switch (r) {
    case Reading::band_band: return "band/band";
    case Reading::band_whole: return "band/whole";
    case Reading::whole_whole: return "whole/whole";
    case Reading::calibration: return "k_i whole, k_c band";
  }
  return "";
}

const Case cases[] = {
    {"fairchild", "per-watt", Reading::band_band, {0.7241, 0.6342, 1.1417}},
    {"fairchild", "per-watt", Reading::band_whole, {0.0626, 0.1965, 0.3184}},
    {"fairchild", "per-watt", Reading::whole_whole, {0.1832, 0.3659, 0.5006}},
    {"fairchild", "per-watt", Reading::calibration, {0.1832, 0.6342, 0.2888}},
    {"fairchild", "per-photon", Reading::band_band, {0.7425, 0.6566, 1.1307}},
    {"fairchild", "per-photon", Reading::band_whole, {0.0226, 0.1328, 0.1699}},
    {"fairchild", "per-photon", Reading::whole_whole, {0.0786, 0.2752, 0.2856}},
    {"fairchild", "per-photon", Reading::calibration, {0.0786, 0.6566, 0.1197}},
    {"hamamatsu", "per-watt", Reading::band_band, {0.9315, 0.8922, 1.0440}},
    {"hamamatsu", "per-watt", Reading::band_whole, {0.0805, 0.2764, 0.2912}},
    {"hamamatsu", "per-watt", Reading::whole_whole, {0.2152, 0.5467, 0.3937}},
    {"hamamatsu", "per-watt", Reading::calibration, {0.2152, 0.8922, 0.2412}},
    {"hamamatsu", "per-photon", Reading::band_band, {0.9652, 0.9775, 0.9874}},
    {"hamamatsu", "per-photon", Reading::band_whole, {0.0293, 0.1977, 0.1483}},
    {"hamamatsu", "per-photon", Reading::whole_whole, {0.0784, 0.3910, 0.2006}},
    {"hamamatsu", "per-photon", Reading::calibration, {0.0784, 0.9775, 0.0802}},
};

TEST(PhysicsUtilisation, ShippedSiliconCurvesUnderEachReading) {
  std::printf("| curve | response | reading | k_i | k_c | k_i/k_c | vs 0.187 / 0.852 / 0.22 |\n");
  for (const Case& c : cases) {
    const Coefficients k = compute(c.curve, c.response, c.reading);
    std::printf("| %s | %s | %s | %.4f | %.4f | %.4f | %+.4f / %+.4f / %+.4f |\n", c.curve, c.response, name(c.reading),
                k.k_i, k.k_c, k.ratio(), k.k_i - 0.187, k.k_c - 0.852, k.ratio() - 0.22);
    EXPECT_NEAR(k.k_i, c.documented.k_i, 5e-5) << c.curve << " " << c.response << " " << name(c.reading);
    EXPECT_NEAR(k.k_c, c.documented.k_c, 5e-5) << c.curve << " " << c.response << " " << name(c.reading);
    EXPECT_NEAR(k.ratio(), c.documented.ratio, 5e-5) << c.curve << " " << c.response << " " << name(c.reading);
  }
}

}  // namespace

namespace {

// How much the choice of lamp statement and of solar spectrum moves the numbers above: the reading matters,
// these do not (docs/utilisation-coefficients.md).
TEST(PhysicsUtilisation, LampConventionAndSolarModelAreMinorEffects) {
  const Spectrum fairchild =
      normalised_to_peak(load_spectrum_csv(spectra + "ccd_front_illuminated_fairchild_relative.csv", "1").spectrum);
  auto k_whole = [&](const Spectrum& s) { return utilisation_coefficient(s, fairchild, support(fairchild), support(s)); };
  auto k_band = [&](const Spectrum& s) { return utilisation_coefficient(s, fairchild, working_band, working_band); };
  const double k_ipts48 = k_whole(sources().lamp);
  const double k_cie_a = k_whole(blackbody_exitance_spectrum(2848.0, constants::second_radiation_1931_m_K));
  const double k_exact = k_whole(blackbody_exitance_spectrum(2856.0, constants::second_radiation_m_K));
  const double k_2856_on_1931 = k_whole(blackbody_exitance_spectrum(2856.0, constants::second_radiation_1931_m_K));
  const double k_sun = k_band(sources().sun), k_5900 = k_band(blackbody_exitance_spectrum(5900.0));
  std::printf("k_i (Fairchild, per-watt, whole/whole): 2854 K ipts48 %.5f, 2848 K cie_a_1931 %.5f, 2856 K exact %.5f, "
              "2856 K with c2 = 1.435e-2 %.5f\n", k_ipts48, k_cie_a, k_exact, k_2856_on_1931);
  std::printf("k_c (Fairchild, per-watt, band/band): E-490 %.5f, 5900 K blackbody %.5f\n", k_sun, k_5900);
  EXPECT_NEAR(k_ipts48, 0.18316, 5e-6);
  EXPECT_NEAR(k_cie_a, k_ipts48, 1e-4);
  EXPECT_NEAR(k_exact, k_ipts48, 1e-4);
  EXPECT_NEAR(k_5900, k_sun, 5e-3);
}

}  // namespace
