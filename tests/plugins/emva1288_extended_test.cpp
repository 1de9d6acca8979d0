// The EMVA 1288 detector on an extended scene: a reflectance ground through a telescope,
// counted by étendue. Every number against a hand computation: the étendue count A_pixel Ω τ ∫ L η λ/(hc) dλ,
// NEΔL = L_ref / SNR, the saturation radiance from the full well (or the ADC), TDI's √N, NEΔρ, and the bad
// inputs that must be refused with a located error.
#include "radchain/chain.hpp"
#include "radchain/constants.hpp"
#include "radchain/error.hpp"
#include "radchain/spectrum_csv.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

namespace {
using namespace radchain;

const std::string spectra = std::string(RADCHAIN_SOURCE_DIR) + "/spectra/";

// The detector's lines: `detector`, then each default whose key `detector` does not set.
std::string with_defaults(const std::string& detector) {
  const char* defaults[] = {"band_min = \"0.63 um\"", "band_max = \"0.69 um\"", "qe = 0.5", "gain = \"0.1 DN/e-\"",
                            "read_noise = \"20 e-\"", "full_well = \"80000 e-\"", "adc_bits = 14",
                            "pixel_pitch = \"10 um\"", "integration_time = \"2 ms\""};
  std::string text = detector + "\n";
  for (const std::string line : defaults) {
    const std::string key = line.substr(0, line.find(' '));
    if (("\n" + detector).find("\n" + key + " ") == std::string::npos) text += line + "\n";
  }
  return text;
}

// A ground of reflectance 0.25 under the Sun at 60° (no atmosphere) seen through a 10 cm f/8 telescope
// (τ = 0.8) by a datasheet camera in 630-690 nm. `detector` lines are appended to the detector section.
std::string write_sensor(const std::string& name, const std::string& detector, const std::string& target_extra = "",
                         const std::string& atmosphere = "plugin = \"none\"\n", const std::string& source_extra = "",
                         const std::string& optics_extra = "") {
  const std::string text = R"([sensor]
name = "emva1288 extended-scene test"
[platform]
plugin = "earth_orbit"
altitude = "700 km"
[source]
plugin = "sun"
)" + source_extra + R"(
[atmosphere]
)" + atmosphere + R"(
[target]
plugin = "reflectance_ground"
reflectance = 0.25
solar_zenith = "60 deg"
)" + target_extra + R"(
[optics]
plugin = "telescope"
aperture = "10 cm"
focal_length = "0.8 m"
transmittance = 0.8
)" + optics_extra + R"(
[detector]
plugin = "emva1288"
)" + with_defaults(detector) + R"(
[criteria.unsaturated]
plugin = "unsaturated"
)";
  const auto path = std::filesystem::temp_directory_path() /
                    ("radchain_emva1288_ext_" + std::to_string(::getpid()) + "_" + name + ".toml");
  std::ofstream(path) << text;
  return path.string();
}

Report run(const std::string& file) {
  Chain chain = load_sensor(file);
  Report r = chain.run();
  std::filesystem::remove(file);
  return r;
}

double v(const Report& r, const std::string& name) { return r.value(name).value(); }

constexpr double hc = constants::planck_J_s * constants::speed_of_light_m_s;
constexpr double lo = 0.63e-6, hi = 0.69e-6;

// Electrons of one pixel per exposure per unit band-averaged radiance (W m-2 sr-1 m-1), by hand:
// k = N t p² · π τ / (4 N²) · qe · ∫ λ/(hc) dλ,  ∫_{λ1}^{λ2} λ dλ = (λ2² − λ1²)/2.
double k_by_hand(double tdi = 1.0) {
  const double omega = std::numbers::pi / (4.0 * 8.0 * 8.0);  // f/8, clear pupil
  return tdi * 2e-3 * 10e-6 * 10e-6 * omega * 0.8 * 0.5 * (hi * hi - lo * lo) / (2.0 * hc);
}

// The noise of one pixel by hand: EMVA 1288 eq. (6), σ_d0 = 20 e-, σ_q = 1/√12 DN at K = 0.1 DN/e-.
double snr_by_hand(double signal, double read = 20.0, double gain = 0.1) {
  return signal / std::sqrt(signal + read * read + 1.0 / (12.0 * gain * gain));
}

TEST(Emva1288Extended, ReferenceRadianceCountedByEtendueAsByHand) {
  // L_ref = 100 W m-2 sr-1 µm-1 = 1e8 W m-2 sr-1 m-1, flat over the band.
  const Report r = run(write_sensor("reference", "reference_radiance = \"100 W m-2 sr-1 um-1\""));
  const double k = k_by_hand();
  EXPECT_NEAR(v(r, "detector.pixel_solid_angle"), std::numbers::pi / 256.0, 1e-15);
  EXPECT_NEAR(v(r, "detector.pixel_etendue"), 1e-10 * std::numbers::pi / 256.0, 1e-24);
  // A_pixel Ω = A_pupil IFOV²: π (0.1)²/4 × (10 µm / 0.8 m)².
  EXPECT_NEAR(v(r, "detector.pixel_etendue"), std::numbers::pi * 0.01 / 4.0 * std::pow(10e-6 / 0.8, 2), 1e-24);
  EXPECT_NEAR(v(r, "detector.radiance_responsivity"), k, 1e-9 * k);
  EXPECT_NEAR(v(r, "detector.reference_radiance"), 1e8, 1e-6);
  const double s = k * 1e8;
  EXPECT_NEAR(v(r, "detector.reference_signal_electrons"), s, 1e-9 * s);
  EXPECT_GT(s, 1000.0);  // a sanity range for the numbers above: about 3100 e-
  EXPECT_LT(s, 1e5);
  EXPECT_NEAR(v(r, "detector.snr_at_reference"), snr_by_hand(s), 1e-9 * snr_by_hand(s));
}

TEST(Emva1288Extended, SceneRadianceIsTheSunsReflectedRadianceAveragedOverTheBand) {
  const Report r = run(write_sensor("scene", ""));
  // L_λ = ρ E_λ cos θ_s / π on the E-490 table; averaged with the photon weight λ (flat QE):
  // L̄ = ∫ L_λ λ dλ / ∫ λ dλ. Trapezoid on a 0.01 nm grid of the linearly interpolated table.
  const Spectrum sun = load_spectrum_csv(spectra + "am0_astm_e490_00a.csv", "W m-2 m-1").spectrum;
  const int n = 6000;
  double num = 0, den = 0;
  for (int i = 0; i <= n; ++i) {
    const double l = lo + (hi - lo) * i / n, w = (i == 0 || i == n) ? 0.5 : 1.0;
    num += w * sun(l) * l;
    den += w * l;
  }
  const double radiance = 0.25 * 0.5 / std::numbers::pi * num / den;
  EXPECT_NEAR(v(r, "detector.scene_radiance"), radiance, 1e-4 * radiance);
  // The scene's electrons are that radiance through the étendue.
  const double s = k_by_hand() * radiance;
  EXPECT_NEAR(v(r, "detector.signal_electrons"), s, 1e-4 * s);
  EXPECT_NEAR(v(r, "detector.snr"), snr_by_hand(s), 1e-4 * snr_by_hand(s));
  // No reference given: the reference is the scene itself.
  EXPECT_NEAR(v(r, "detector.reference_radiance"), v(r, "detector.scene_radiance"), 1e-12 * radiance);
  EXPECT_NEAR(v(r, "detector.snr_at_reference"), v(r, "detector.snr"), 1e-9);
  EXPECT_NEAR(v(r, "target.reflectance"), 0.25, 1e-15);
}

TEST(Emva1288Extended, NoiseEquivalentRadianceIsReferenceOverSnr) {
  for (const char* ref : {"10 W m-2 sr-1 um-1", "100 W m-2 sr-1 um-1", "400 W m-2 sr-1 um-1"}) {
    const Report r = run(write_sensor("nedl", std::string("reference_radiance = \"") + ref + "\"\ndark_current = \"500 e-/s\""));
    const double l = v(r, "detector.reference_radiance"), snr = v(r, "detector.snr_at_reference");
    EXPECT_NEAR(v(r, "detector.noise_equivalent_radiance"), l / snr, 1e-12 * l) << ref;
    // and by hand: n/k with the dark shot noise of μ_I t = 1 e-.
    const double k = k_by_hand(), s = k * l;
    const double noise = std::sqrt(s + 1.0 + 400.0 + 1.0 / 0.12);
    EXPECT_NEAR(v(r, "detector.noise_equivalent_radiance"), noise / k, 1e-9 * noise / k) << ref;
  }
}

TEST(Emva1288Extended, NoiseEquivalentReflectanceAtTheTargetsSunAngle) {
  // Reference as a reflectance of this scene: L_ref = ρ_ref L̄/ρ; NEΔρ = NEΔL / (dL/dρ), dL/dρ = L̄/ρ.
  const Report r = run(write_sensor("nedrho", "reference_reflectance = 0.5"));
  const double scene = v(r, "detector.scene_radiance");
  EXPECT_NEAR(v(r, "detector.reference_radiance"), 2.0 * scene, 1e-12 * scene);
  const double nedl = v(r, "detector.noise_equivalent_radiance");
  EXPECT_NEAR(v(r, "detector.noise_equivalent_reflectance"), nedl / (scene / 0.25), 1e-12);
  EXPECT_NEAR(v(r, "detector.noise_equivalent_reflectance"), 0.5 / v(r, "detector.snr_at_reference"), 1e-12);
  // By hand: the noise at L_ref over the electrons per unit reflectance S/ρ of this scene (its sun at 60°).
  const double s = k_by_hand() * scene, s_ref = 2.0 * s;
  const double noise = s_ref / snr_by_hand(s_ref);
  EXPECT_NEAR(v(r, "detector.noise_equivalent_reflectance"), noise / (s / 0.25), 1e-4 * noise / (s / 0.25));
}

TEST(Emva1288Extended, SaturationRadianceFillsTheWellOrTheAdc) {
  // Well-limited: 14 bits at 0.1 DN/e- reach 163 830 e-, above the 80 000 e- well.
  const Report well = run(write_sensor("well", "dark_current = \"1000 e-/s\""));
  const double k = k_by_hand();
  EXPECT_NEAR(v(well, "detector.saturation_capacity"), 80000.0, 1e-9);
  EXPECT_NEAR(v(well, "detector.saturation_radiance"), (80000.0 - 2.0) / k, 1e-9 * 80000.0 / k);
  // ADC-limited: 12 bits at 0.1 DN/e- reach 40 950 e-.
  const Report adc = run(write_sensor("adc", "adc_bits = 12"));
  EXPECT_NEAR(v(adc, "detector.saturation_capacity"), 4095.0 / 0.1, 1e-9);
  EXPECT_NEAR(v(adc, "detector.saturation_radiance"), 40950.0 / k, 1e-9 * 40950.0 / k);
  // A scene at the saturation radiance fills the pixel exactly: the unsaturated criterion's margin is 0.
  const double sat = v(well, "detector.saturation_radiance");
  const double scene = v(well, "detector.scene_radiance");
  const double fill = v(well, "detector.peak_pixel_fill");
  EXPECT_NEAR(fill, (k * scene + 2.0) / 80000.0, 1e-9);
  EXPECT_NEAR((k * sat + 2.0) / 80000.0, 1.0, 1e-12);
  EXPECT_NEAR(v(well, "criteria.unsaturated.margin"), 1.0 / fill - 1.0, 1e-9);
}

TEST(Emva1288Extended, TdiStagesScaleTheShotLimitedSnrAsRootN) {
  // Shot-noise limited (no read noise, K = 100 DN/e-: σ_q/K ≈ 0.003 e-): SNR ∝ √N_tdi.
  const std::string quiet = "read_noise = \"0 e-\"\ngain = \"100 DN/e-\"\nadc_bits = 32\nreference_radiance = \"100 W m-2 sr-1 um-1\"\n";
  const Report one = run(write_sensor("tdi1", quiet));
  const Report many = run(write_sensor("tdi64", quiet + "tdi_stages = 64\n"));
  EXPECT_NEAR(v(many, "detector.reference_signal_electrons"), 64.0 * v(one, "detector.reference_signal_electrons"), 1e-6);
  EXPECT_NEAR(v(many, "detector.snr_at_reference") / v(one, "detector.snr_at_reference"), 8.0, 1e-6);
  EXPECT_NEAR(v(many, "detector.noise_equivalent_radiance") * 8.0, v(one, "detector.noise_equivalent_radiance"),
              1e-6 * v(one, "detector.noise_equivalent_radiance"));
  // With read noise, TDI reads once: SNR = N S / √(N S + σ² + σ_q²/K²).
  const Report read = run(write_sensor("tdi16", "tdi_stages = 16\nreference_radiance = \"100 W m-2 sr-1 um-1\""));
  const double s16 = 16.0 * k_by_hand() * 1e8;
  EXPECT_NEAR(v(read, "detector.snr_at_reference"), snr_by_hand(s16), 1e-9 * snr_by_hand(s16));
  // and the well holds the N stages' charge: L_sat drops as 1/N.
  EXPECT_NEAR(v(read, "detector.saturation_radiance"), 80000.0 / (16.0 * k_by_hand()), 1e-6 * 80000.0 / k_by_hand());
}

TEST(Emva1288Extended, BinningAndCoAddsOnAUniformScene) {
  // 2×2 binning: 4 × signal, 4 × read variance; 4 co-adds: 4 × signal, 4 × temporal variance.
  const Report r = run(write_sensor("bin", "binning = 2\nexposures = 4\nreference_radiance = \"100 W m-2 sr-1 um-1\""));
  const double s1 = 4.0 * k_by_hand() * 1e8;
  const double noise = std::sqrt(4.0 * (s1 + 4.0 * (400.0 + 1.0 / 0.12)));
  EXPECT_NEAR(v(r, "detector.reference_signal_electrons"), 4.0 * s1, 1e-9 * s1);
  EXPECT_NEAR(v(r, "detector.snr_at_reference"), 4.0 * s1 / noise, 1e-9 * s1 / noise);
  EXPECT_NEAR(v(r, "detector.noise_equivalent_radiance"), 1e8 / (4.0 * s1 / noise), 1e-9 * 1e8);
}

TEST(Emva1288Extended, BadInputIsRefusedWithTheKeyNamed) {
  auto message = [](const std::string& name, const std::string& detector, const std::string& target = "") {
    const std::string path = write_sensor(name, detector, target);
    std::string what;
    try {
      load_sensor(path);
    } catch (const InputError& e) {
      what = e.what();
    }
    std::filesystem::remove(path);
    return what;
  };
  // A negative reference radiance: out of range, located at the key.
  EXPECT_NE(message("neg", "reference_radiance = \"-5 W m-2 sr-1 um-1\"").find("reference_radiance"), std::string::npos);
  // The band beyond the QE table: never counted as 0.
  const std::string band = message("band", "qe_curve = \"cmos_sony_imx428_mono_qe.csv\"\nband_max = \"1.2 um\"");
  EXPECT_NE(band.find("band_max"), std::string::npos) << band;
  EXPECT_NE(band.find("reaches past the table qe_curve"), std::string::npos) << band;
  // Both forms of the reference at once.
  EXPECT_NE(message("both", "reference_radiance = \"100 W m-2 sr-1 um-1\"\nreference_reflectance = 0.3").find("not both"),
            std::string::npos);
  // Point-image keys on an extended scene.
  EXPECT_NE(message("window", "window_pixels = 3").find("point image"), std::string::npos);
}

TEST(Emva1288Extended, ReferenceReflectanceNeedsAReflectanceTarget) {
  const std::string path = std::filesystem::temp_directory_path() /
                           ("radchain_emva1288_ext_" + std::to_string(::getpid()) + "_lambertian.toml");
  std::ofstream(path) << R"([sensor]
name = "reference reflectance on a contrast target"
[source]
plugin = "sun"
band_min = "0.5 um"
band_max = "0.76 um"
[atmosphere]
plugin = "none"
[target]
plugin = "lambertian_ground"
albedo = 0.3
contrast = 0.1
contrast_kind = "relative"
[optics]
plugin = "telescope"
aperture = "10 cm"
focal_length = "0.8 m"
[detector]
plugin = "emva1288"
band_min = "0.63 um"
band_max = "0.69 um"
gain = "0.1 DN/e-"
read_noise = "20 e-"
full_well = "80000 e-"
adc_bits = 14
pixel_pitch = "10 um"
integration_time = "2 ms"
reference_reflectance = 0.3
[criteria.unsaturated]
plugin = "unsaturated"
)";
  std::string what;
  try {
    load_sensor(path);
  } catch (const InputError& e) {
    what = e.what();
  }
  std::filesystem::remove(path);
  EXPECT_NE(what.find("reflectance_ground"), std::string::npos) << what;
}

// Path radiance: L = τ↑ ρ E cos θ_s τ↓/π + L_path (Schott 2007 §4.1). The atmosphere's path
// radiance reaches the pupil as a radiance, so the pixel counts it through the same étendue: k L̄_path more
// electrons, by hand; the reflectance's derivative (NEΔρ) and a reference given as a reflectance count the surface
// part only. A flat 5 W m-2 sr-1 over the 630-690 nm band (`constant`, τ = 1) and a tabulated ramp.
TEST(Emva1288Extended, PathRadianceJoinsTheSceneThroughTheEtendue) {
  const std::string band = "band_min = \"0.63 um\"\nband_max = \"0.69 um\"\n";
  const std::string clear = "plugin = \"constant\"\ntransmittance = 1\n";
  const Report without = run(write_sensor("nopath", "reference_reflectance = 0.5", "", clear, band));
  const Report with = run(write_sensor("path", "reference_reflectance = 0.5", "", clear + "path_radiance = \"5 W/(m2 sr)\"\n", band));
  const double path_radiance = 5.0 / (hi - lo);  // W m-2 sr-1 m-1, flat over the band
  const double path_electrons = k_by_hand() * path_radiance;
  EXPECT_NEAR(v(with, "detector.path_radiance_electrons"), path_electrons, 1e-9 * path_electrons);
  EXPECT_EQ(v(without, "detector.path_radiance_electrons"), 0.0);
  EXPECT_NEAR(v(with, "detector.signal_electrons") - v(without, "detector.signal_electrons"), path_electrons, 1e-9 * path_electrons);
  EXPECT_NEAR(v(with, "detector.scene_radiance") - v(without, "detector.scene_radiance"), path_radiance, 1e-9 * path_radiance);
  EXPECT_NEAR(v(with, "target.at_aperture_radiance") - v(with, "target.surface_radiance_at_aperture"), 5.0, 1e-12);
  // L_ref = ρ_ref/ρ L̄_surface + L̄_path; NEΔρ = noise(L_ref) ρ / S_surface.
  const double surface = v(without, "detector.scene_radiance");
  EXPECT_NEAR(v(with, "detector.reference_radiance"), 2.0 * surface + path_radiance, 1e-9 * surface);
  const double s_surface = k_by_hand() * surface, s_ref = k_by_hand() * (2.0 * surface + path_radiance);
  const double noise_ref = s_ref / snr_by_hand(s_ref);
  EXPECT_NEAR(v(with, "detector.noise_equivalent_reflectance"), noise_ref * 0.25 / s_surface, 1e-4 * noise_ref * 0.25 / s_surface);
  EXPECT_GT(v(with, "detector.noise_equivalent_reflectance"), v(without, "detector.noise_equivalent_reflectance"));
  // An optics transmittance curve (0.5 over the band) weights the path radiance as it weights the scene.
  const std::string curve = (std::filesystem::temp_directory_path() / ("radchain_curve_" + std::to_string(::getpid()) + ".csv")).string();
  std::ofstream(curve) << "# test table: a grey optics component\nwavelength_nm,transmittance\n600,0.5\n700,0.5\n";
  const Report halved = run(write_sensor("pathcurve", "", "", clear + "path_radiance = \"5 W/(m2 sr)\"\n", band,
                                         "transmittance_curve = [\"" + curve + "\"]\n"));
  std::filesystem::remove(curve);
  EXPECT_NEAR(v(halved, "detector.path_radiance_electrons"), 0.5 * path_electrons, 1e-9 * path_electrons);

  // A tabulated path radiance (as an RT code writes it): L_path = 0.05 + 0.001 (λ/nm − 600) W m-2 sr-1 nm-1 every
  // nm over 600-700 nm, τ = 1. Electrons: t p² Ω τ qe ∫ L_path λ/(hc) dλ over 630-690 nm in closed form; radchain's
  // band integral is the trapezoid rule on the table's grid, whose error for the quadratic L λ is (1 nm)²/12 ×
  // (L λ)''/(L λ) ≈ 2e-6 relative here (on a 2-point table it would be 0.8 %).
  const auto dir = std::filesystem::temp_directory_path();
  const std::string tau_file = (dir / ("radchain_tau_" + std::to_string(::getpid()) + ".csv")).string();
  const std::string path_file = (dir / ("radchain_path_" + std::to_string(::getpid()) + ".csv")).string();
  std::ofstream(tau_file) << "# test table: a clear atmosphere\nwavelength_nm,transmittance\n600,1\n700,1\n";
  {
    std::ofstream table_out(path_file);
    table_out << "# test table: a linear path radiance\nwavelength_nm,path_radiance_W_m-2_sr-1_nm-1\n";
    for (int nm = 600; nm <= 700; ++nm) table_out << nm << "," << 0.05 + 0.001 * (nm - 600) << "\n";
  }
  const Report table = run(write_sensor("pathtable", "", "",
                                        "plugin = \"tabulated_transmittance\"\ntable = \"" + tau_file + "\"\npath_radiance = \"" +
                                            path_file + "\"\n"));
  std::filesystem::remove(tau_file);
  std::filesystem::remove(path_file);
  // L(λ) = A + B λ in W m-2 sr-1 m-1 (λ in m): A = (0.05 − 0.6) 1e9, B = 1e15; ∫ (A + Bλ) λ dλ = A (λ2² − λ1²)/2 + B (λ2³ − λ1³)/3.
  const double A = (0.05 - 0.001 * 600) * 1e9, B = 0.001 * 1e18;
  const double integral = A * (hi * hi - lo * lo) / 2 + B * (hi * hi * hi - lo * lo * lo) / 3;
  const double omega = std::numbers::pi / (4.0 * 8.0 * 8.0);
  const double by_hand = 2e-3 * 10e-6 * 10e-6 * omega * 0.8 * 0.5 * integral / hc;
  EXPECT_NEAR(v(table, "detector.path_radiance_electrons"), by_hand, 1e-5 * by_hand);
  // In band (no source band: 400-700 nm; the table is 0 below 600 nm): ∫ = 0.05 × 100 + 0.001 × 100²/2 = 10.
  EXPECT_NEAR(v(table, "atmosphere.path_radiance"), 10.0, 1e-9);
}

}  // namespace
