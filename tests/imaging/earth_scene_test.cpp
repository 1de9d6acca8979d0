// Pushbroom Earth scenes: radiometry from the chain, the MTF model, sampling, determinism, the test scene.
#include "radchain/physics/mtf.hpp"
#include "radchain/imaging/render.hpp"
#include "render_test_helpers.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>

namespace {
using namespace radchain;
using namespace radchain::render;
using radchain::render_tests::load;

const char* kolobrodov = "kolobrodov-1996-ccd151-computed.toml";

EarthSceneOptions options(double input_sampling_m) {
  EarthSceneOptions o;
  o.input_sampling_m = input_sampling_m;
  return o;
}

TEST(RenderEarth, RadiometryComesFromTheChain) {
  auto k = load(kolobrodov);
  const EarthSceneSetup s = earth_scene_setup(k.chain, k.report, options(1.25));
  // A step Δρ against the noise-equivalent exposure is the report's SNR (Kolobrodov eqs. 20-21).
  EXPECT_NEAR(s.exposure_per_reflectance() * s.reflectance_difference / s.nee_J_m2, *k.report.value("detector.snr"), 1e-12);
  // The background ρ0 against the saturation exposure is the detector's own background_saturation_fraction.
  EXPECT_NEAR(s.background_reflectance, 0.3, 1e-15);
  EXPECT_NEAR(s.exposure_per_reflectance() * 0.3 / s.saturation_J_m2, *k.report.value("detector.background_saturation_fraction"), 1e-12);
  // Geometry and MTF inputs of the design.
  // One output pixel per detector sample: the pixel-pitch GSD p h / f' (3.35 m), not Kolobrodov's element
  // V_s h / f' (5 m), which stays in the header as GRNDELEM.
  EXPECT_NEAR(s.output_sampling_m, *k.report.value("criteria.resolution.gsd_nadir"), 1e-12);
  EXPECT_NEAR(s.output_sampling_m, 7e-6 * 400e3 / *k.report.value("optics.focal_length"), 1e-12);
  EXPECT_NEAR(s.ground_element_m, 5.0, 1e-9);
  const Header h = earth_scene_header(s, 1);
  EXPECT_NEAR(*card_number(h, "GSD"), s.output_sampling_m, 1e-9);
  EXPECT_NEAR(*card_number(h, "PIXGSD"), s.output_sampling_m, 1e-9);
  EXPECT_NEAR(*card_number(h, "GRNDELEM"), 5.0, 1e-9);
  EXPECT_NEAR(s.wavelength_m, 0.76e-6, 1e-18);
  EXPECT_NEAR(s.f_number, *k.report.value("optics.f_number"), 1e-12);
  EXPECT_NEAR(s.element_m, 7e-6, 1e-18);
  EXPECT_NEAR(s.eta, 0.8, 1e-9);
  EXPECT_NEAR(s.ground_to_focal(), *k.report.value("optics.focal_length") / 400e3, 1e-15);
}

TEST(RenderEarth, SystemMtfIsOpticsTimesElement) {
  auto k = load(kolobrodov);
  EarthSceneOptions o = options(1.25);
  EarthSceneSetup s = earth_scene_setup(k.chain, k.report, o);
  EXPECT_DOUBLE_EQ(system_mtf(s, 0, 0), 1.0);
  const double scale = 400e3 / s.focal_length_m;  // ground → focal plane frequency
  for (double nu : {0.02, 0.05, 0.1, 0.149}) {
    const double f = nu * scale;
    EXPECT_NEAR(system_mtf(s, nu, 0), physics::diffraction_mtf(f, 0.76e-6, s.f_number) * physics::detector_pixel_mtf(f, 7e-6), 1e-12);
  }
  // At the detector's Nyquist frequency (1/(2 pitch) on the focal plane) the element gives 2/π.
  const double nyquist_ground = 0.5 / 7e-6 / scale;
  EXPECT_NEAR(system_mtf(s, nyquist_ground, 0) / physics::diffraction_mtf(0.5 / 7e-6, 0.76e-6, s.f_number), 2.0 / M_PI, 1e-12);
  o.optics = OpticsMtf::kolobrodov_eq7;
  s = earth_scene_setup(k.chain, k.report, o);
  const double nu_half = *k.report.value("detector.nu_half_contrast");  // ν_x1: eq. (7) gives 0.5 there (η from eq. 12)
  EXPECT_NEAR(system_mtf(s, nu_half / scale, 0) / physics::detector_pixel_mtf(nu_half, 7e-6), 0.5, 1e-9);
}

TEST(RenderEarth, FlatStaysFlatAndSizesFollowTheSampling) {
  auto k = load(kolobrodov);
  EarthSceneOptions o = options(1.25);
  o.output_sampling_m = 5.0;  // Kolobrodov's element: 4 input pixels per output pixel
  o.noise = o.saturation = o.quantisation = false;
  const EarthSceneSetup s = earth_scene_setup(k.chain, k.report, o);
  const Image out = filtered_reflectance(s, make_flat_scene(81, 41, 0.3));
  ASSERT_EQ(out.width, 21);  // (81 − 1)/4 + 1
  ASSERT_EQ(out.height, 11);
  for (float v : out.pixels) EXPECT_NEAR(v, 0.3, 1e-6);
  const Image exposure = render_earth_scene(s, make_flat_scene(81, 41, 0.3), 1);
  EXPECT_NEAR(exposure(10, 5), 0.3 * s.exposure_per_reflectance(), 1e-6 * exposure(10, 5));
  // A non-integer ratio (5 m from 1.5 m: Keys' cubic) keeps a ramp a ramp away from the sides.
  o.input_sampling_m = 1.5;
  o.optics = OpticsMtf::none;
  o.detector_mtf = false;
  const EarthSceneSetup t = earth_scene_setup(k.chain, k.report, o);
  Image ramp(100, 20);
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 100; ++x) ramp(x, y) = static_cast<float>(0.2 + 0.004 * x);
  const Image r = filtered_reflectance(t, ramp);
  EXPECT_EQ(r.width, earth_output_size(t, 100));
  EXPECT_EQ(r.width, 30);  // floor(99 / 3.333) + 1
  for (int i = 2; i < r.width - 2; ++i) EXPECT_NEAR(r(i, 3), 0.2 + 0.004 * i * 5.0 / 1.5, 1e-5) << i;
}

TEST(RenderEarth, NoiseQuantisationAndSeeds) {
  auto k = load(kolobrodov);
  EarthSceneOptions o = options(5.0);
  o.output_sampling_m = 5.0;  // one input pixel per output pixel
  const EarthSceneSetup s = earth_scene_setup(k.chain, k.report, o);
  const Image map = make_test_scene({256, 5.0, 5.0, 0.3, 0.6, 0.003, 5.0});
  const Image a = render_earth_scene(s, map, 11), b = render_earth_scene(s, map, 11), c = render_earth_scene(s, map, 12);
  EXPECT_EQ(a.pixels, b.pixels);
  EXPECT_NE(a.pixels, c.pixels);
  for (float v : a.pixels) {
    EXPECT_GE(v, 0.0f);
    EXPECT_LE(v, 4095.0f);
    EXPECT_EQ(v, std::floor(v));
  }
  // ρ0 = 0.3 lands at 17.5 % of the ADC range (the background_saturation_fraction): DN ≈ 0.175 × 4096.
  EXPECT_NEAR(a(10, 200), 0.174916 * 4096, 8.0);
  EXPECT_EQ(earth_unit(s), "adu");
  const Header h = earth_scene_header(s, 11);
  EXPECT_NEAR(*card_number(h, "GSD"), 5.0, 1e-9);
  EXPECT_NEAR(*card_number(h, "SNR"), *k.report.value("detector.snr"), 1e-12);
}

TEST(RenderEarth, CommittedSceneIsTheGeneratorsOutput) {
  // examples/scenes/bars-edges.png is make_test_scene() with its defaults, as a 16-bit PNG.
  const std::string path = std::string(RADCHAIN_SOURCE_DIR) + "/examples/scenes/bars-edges.png";
  ASSERT_TRUE(std::filesystem::exists(path));
  EXPECT_LT(std::filesystem::file_size(path), 100u * 1024u);
  const Image committed = read_reflectance_map(path);
  const Image generated = make_test_scene();
  ASSERT_EQ(committed.width, generated.width);
  ASSERT_EQ(committed.height, generated.height);
  double worst = 0;
  for (std::size_t i = 0; i < generated.size(); ++i) worst = std::max(worst, std::abs(double(committed.pixels[i]) - generated.pixels[i]));
  EXPECT_LE(worst, 0.5 / 65535.0 + 1e-7);
  // The edge scene covers each pixel exactly: its mean is the mean of both sides.
  const Image edge = make_edge_scene(64, 64, 5.0, 0.2, 0.6);
  double sum = 0;
  for (float v : edge.pixels) sum += v;
  EXPECT_NEAR(sum / edge.size(), 0.4, 1e-6);
}

TEST(RenderEarth, RefusesSensorsItCannotRender) {
  auto sbv = load("msx-sbv.toml");
  EXPECT_THROW(earth_scene_setup(sbv.chain, sbv.report, options(1.0)), InputError);
  auto k = load(kolobrodov);
  EXPECT_THROW(earth_scene_setup(k.chain, k.report, options(0.0)), InputError);
}

}  // namespace

// ---- A datasheet detector (emva1288 on a reflectance target) and the chain's MTF budget ----

namespace datasheet {
const char* s2 = "sentinel-2a-msi-b4.toml";

TEST(RenderEarthDatasheet, ElectronsPerReflectanceComeFromTheChain) {
  auto k = load(s2);
  EarthSceneOptions o = options(9.825);
  const EarthSceneSetup s = earth_scene_setup(k.chain, k.report, o);
  ASSERT_EQ(s.radiometry, EarthRadiometry::electrons);
  // The chain's own scene: ρ = 0.3 gives detector.signal_electrons (no atmosphere: no path radiance).
  EXPECT_NEAR(s.scene_reflectance, 0.3, 1e-15);
  EXPECT_NEAR(s.photo_electrons(0.3), *k.report.value("detector.signal_electrons"), 1e-9 * s.photo_electrons(0.3));
  EXPECT_EQ(s.path_electrons, 0.0);
  EXPECT_NEAR(s.gain_dn_per_e, 0.06825, 1e-12);
  EXPECT_NEAR(s.capacity_e, std::min(60000.0, 4095 / 0.06825), 1e-6);
  EXPECT_EQ(s.adc_bits, 12);  // the detector's, not the option's old default
  EXPECT_NEAR(s.read_noise_e, 40.0, 1e-12);
  // Independent of the render code: k_ρ = S(ρ)/ρ is the same at another reflectance of the same scene.
  auto half = load(s2, {{"target.reflectance", "0.15"}});
  EXPECT_NEAR(s.photo_electrons(0.15), *half.report.value("detector.signal_electrons"), 1e-9 * s.photo_electrons(0.15));
  // A flat map without noise or ADC is the photo signal itself, pixel for pixel.
  o.noise = o.saturation = o.quantisation = false;
  const EarthSceneSetup clean = earth_scene_setup(k.chain, k.report, o);
  const Image flat = render_earth_scene(clean, make_flat_scene(16, 16, 0.3), 1);
  for (float v : flat.pixels) EXPECT_NEAR(v, s.photo_electrons(0.3), 1e-4 * s.photo_electrons(0.3));
  EXPECT_EQ(earth_unit(clean), "electron");
}

TEST(RenderEarthDatasheet, FlatFieldHasTheChainsSnr) {
  auto k = load(s2);
  const FlatFieldCheck flat = check_earth_flat_field(k.chain, k.report, EarthSceneOptions{}, 256, 7);
  // The renderer's noise law is the chain's (EMVA 1288 eq. 6 with the ADC's 1/(12 K²)): the same number.
  EXPECT_NEAR(flat.predicted_snr, *k.report.value("detector.snr"), 1e-9 * flat.predicted_snr);
  // And the rendered frame measures it (65 536 pixels: σ(SNR) ≈ 0.27 at SNR ≈ 100).
  EXPECT_TRUE(flat.passed(4.0)) << flat.measured_snr << " ± " << flat.snr_sigma << " vs " << flat.predicted_snr;
  // With PRNU and DSNU the fixed pattern adds to the noise as EMVA 1288 eq. 18 says, and the chain agrees.
  auto fpn = load(s2, {{"detector.prnu", "0.01"}, {"detector.dsnu", "20 e-"}});
  const FlatFieldCheck with = check_earth_flat_field(fpn.chain, fpn.report, EarthSceneOptions{}, 256, 7);
  EXPECT_NEAR(with.predicted_snr, *fpn.report.value("detector.snr"), 1e-9 * with.predicted_snr);
  EXPECT_LT(with.predicted_snr, 0.9 * flat.predicted_snr);
  EXPECT_TRUE(with.passed(4.0)) << with.measured_snr << " ± " << with.snr_sigma << " vs " << with.predicted_snr;
}

TEST(RenderEarthDatasheet, TheMtfBudgetIsTheGiqeCriterionsCascade) {
  // Jitter, smear, diffusion, wavefront error and TDI, so every term of the budget is in play.
  auto k = load(s2, {{"criteria.iq.jitter_rms", "0.8 um"}, {"criteria.iq.smear_pixels", "0.4"}, {"criteria.iq.diffusion_rms", "1 um"},
                     {"criteria.iq.wavefront_error", "0.05"}, {"detector.tdi_stages", "8"}, {"criteria.iq.tdi_mismatch", "0.05"},
                     {"criteria.iq.fried_parameter", "\"20 cm\""}});
  const EarthSceneSetup s = earth_scene_setup(k.chain, k.report, options(2.0));
  ASSERT_EQ(s.optics, OpticsMtf::budget);
  const double nyquist_ground = 0.5 / s.budget.pitch_m * s.ground_to_focal();
  // Along track (y) every component acts: the giqe criterion's system MTF at Nyquist.
  EXPECT_NEAR(system_mtf(s, 0, nyquist_ground), *k.report.value("criteria.iq.mtf_nyquist_system"), 1e-9);
  // Across track the smear and TDI terms do not.
  const physics::MtfComponents m = physics::mtf_components(s.budget, 0.5 / s.budget.pitch_m);
  EXPECT_NEAR(system_mtf(s, nyquist_ground, 0), m.system() / (m.smear * m.tdi), 1e-9);
  EXPECT_LT(system_mtf(s, 0, nyquist_ground), system_mtf(s, nyquist_ground, 0));
  // "diffraction" leaves the budget's other terms out.
  EarthSceneOptions o = options(2.0);
  o.optics = OpticsMtf::diffraction;
  const EarthSceneSetup d = earth_scene_setup(k.chain, k.report, o);
  EXPECT_NEAR(system_mtf(d, 0, nyquist_ground), m.diffraction * m.pixel, 1e-9);
}

TEST(RenderEarthDatasheet, ARenderedEdgeMeasuresTheBudget) {
  auto k = load(s2, {{"criteria.iq.jitter_rms", "1.5 um"}, {"criteria.iq.smear_pixels", "0.5"}});
  const EdgeCheck edge = check_edge_mtf(k.chain, k.report, EarthSceneOptions{});
  EXPECT_TRUE(edge.passed()) << "max relative error " << edge.max_relative_error;
  EXPECT_NEAR(edge.mtf_at_nyquist_measured, edge.mtf_at_nyquist_model, 0.02);
}

TEST(RenderEarthDatasheet, BinnedAndCoaddedFramesSumTheirNativeReads) {
  // 2×2 digital binning over 3 co-added frames with a fixed pattern: the chain's EMVA 1288 noise of a binned,
  // co-added pixel (M b² temporal reads, the fixed pattern M² b² times) is what the rendered flat field measures.
  auto k = load(s2, {{"detector.binning", "2"}, {"detector.exposures", "3"}, {"detector.prnu", "0.01"}, {"detector.dsnu", "20 e-"}});
  auto native = load(s2, {{"detector.prnu", "0.01"}, {"detector.dsnu", "20 e-"}});
  EarthSceneOptions o = options(9.825);
  const EarthSceneSetup s = earth_scene_setup(k.chain, k.report, o);
  const EarthSceneSetup one = earth_scene_setup(native.chain, native.report, o);
  EXPECT_EQ(s.binning, 2);
  EXPECT_EQ(s.exposures, 3);
  EXPECT_DOUBLE_EQ(s.native_sums(), 12.0);
  // Per native pixel and frame the terms are the unbinned detector's.
  EXPECT_NEAR(s.electrons_per_reflectance, one.electrons_per_reflectance, 1e-12 * one.electrons_per_reflectance);
  EXPECT_NEAR(s.read_noise_e, one.read_noise_e, 1e-12);
  EXPECT_NEAR(s.dark_electrons, one.dark_electrons, 1e-12);
  // One output pixel is a binned pixel: twice the native GSD.
  EXPECT_NEAR(s.output_sampling_m, 2.0 * *k.report.value("criteria.gsd.gsd_nadir"), 1e-12);
  // Without noise or ADC a flat map gives the chain's signal of the binned, co-added pixel.
  o.noise = o.saturation = o.quantisation = false;
  const EarthSceneSetup clean = earth_scene_setup(k.chain, k.report, o);
  const Image flat = render_earth_scene(clean, make_flat_scene(32, 32, 0.3), 1);
  EXPECT_EQ(flat.width, 16);  // 32 native samples (the native sampling is the map's 9.825 m), 2 per output pixel
  for (float v : flat.pixels) EXPECT_NEAR(v, *k.report.value("detector.signal_electrons"), 1e-4 * *k.report.value("detector.signal_electrons"));
  const FlatFieldCheck check = check_earth_flat_field(k.chain, k.report, EarthSceneOptions{}, 256, 11);
  EXPECT_NEAR(check.predicted_snr, *k.report.value("detector.snr"), 1e-9 * check.predicted_snr);
  EXPECT_TRUE(check.passed(4.0)) << check.measured_snr << " ± " << check.snr_sigma << " vs " << check.predicted_snr;
  // By hand from one native pixel's terms: M b² = 12 reads of the temporal variance T, the fixed pattern F
  // M² b² = 36 times (it does not average over co-adds), so SNR₁₂/SNR₁ = 12 √(T + F) / √(12 T + 36 F) < √12.
  const FlatFieldCheck single = check_earth_flat_field(native.chain, native.report, EarthSceneOptions{}, 256, 11);
  const double photo = one.photo_electrons(0.3), q = 1.0 / one.gain_dn_per_e;
  const double temporal = photo + one.dark_electrons + one.read_noise_e * one.read_noise_e + q * q / 12;
  const double fixed = one.dsnu_e * one.dsnu_e + one.prnu * one.prnu * photo * photo;
  EXPECT_NEAR(check.predicted_snr / single.predicted_snr, 12 * std::sqrt(temporal + fixed) / std::sqrt(12 * temporal + 36 * fixed),
              1e-9);
  const Header h = earth_scene_header(s, 1);
  EXPECT_EQ(card_number(h, "BINNING"), 2.0);
  EXPECT_EQ(card_number(h, "NCOADD"), 3.0);
}

TEST(RenderEarthDatasheet, ABinnedPixelHasTheArrayFactorOfItsNativePixels) {
  // b native apertures p apart summed: sin(π b p ν)/(b sin(π p ν)) per axis; at ν = 1/(4p), the binned pixel's
  // Nyquist for b = 2, that is sin(π/2)/(2 sin(π/4)) = 1/√2 (Holst 2008 §10: the MTF of summed samples).
  auto binned = load(s2, {{"detector.binning", "2"}});
  auto native = load(s2);
  const EarthSceneSetup b = earth_scene_setup(binned.chain, binned.report, options(2.0));
  const EarthSceneSetup n = earth_scene_setup(native.chain, native.report, options(2.0));
  const double nu_ground = 0.25 / b.pitch_m * b.ground_to_focal();
  EXPECT_NEAR(system_mtf(b, nu_ground, 0) / system_mtf(n, nu_ground, 0), 1.0 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(system_mtf(b, 0, nu_ground) / system_mtf(n, 0, nu_ground), 1.0 / std::sqrt(2.0), 1e-12);
  // A rendered edge of binned pixels measures that model up to the binned Nyquist.
  const EdgeCheck edge = check_edge_mtf(binned.chain, binned.report, EarthSceneOptions{});
  EXPECT_TRUE(edge.passed()) << "max relative error " << edge.max_relative_error;
  EXPECT_NEAR(edge.mtf_at_nyquist_measured, edge.mtf_at_nyquist_model, 0.02);
  // An output sampling given by hand: the native samples are 1.5 pitches apart, and two of them sum to
  // cos(π δ ν) with δ = 1.5 p on the focal plane.
  EarthSceneOptions o = options(2.0);
  o.output_sampling_m = 3.0 * *binned.report.value("criteria.gsd.gsd_nadir");
  const EarthSceneSetup wide = earth_scene_setup(binned.chain, binned.report, o);
  EXPECT_NEAR(system_mtf(wide, nu_ground, 0) / system_mtf(n, nu_ground, 0), std::abs(std::cos(std::numbers::pi * 1.5 * 0.25)), 1e-12);
}

TEST(RenderEarthDatasheet, AMapTooSmallForOneBinnedPixelIsRefused) {
  auto k = load(s2, {{"detector.binning", "2"}});
  const EarthSceneSetup s = earth_scene_setup(k.chain, k.report, options(9.825));
  try {
    render_earth_scene(s, make_flat_scene(1, 1, 0.3), 1);
    ADD_FAILURE() << "a 1×1 map gave a binned image";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("too few for one 2×2 binned pixel"), std::string::npos) << e.what();
  }
}

TEST(RenderEarthDatasheet, TooManyNativeReadsAreRefusedBeforeDrawing) {
  auto k = load(s2, {{"detector.exposures", "100000"}});
  const EarthSceneSetup s = earth_scene_setup(k.chain, k.report, options(9.825));
  try {
    render_earth_scene(s, make_flat_scene(256, 256, 0.3), 1);
    ADD_FAILURE() << "10⁵ co-adds of 256×256 pixels accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("detector.exposures"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("native reads"), std::string::npos) << e.what();
  }
}
}  // namespace datasheet
