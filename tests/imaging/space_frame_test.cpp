// Point-target frames: photometry of rendered sources against the chain and closed-form ensquared energies,
// noise statistics, determinism, star field, saturation.
#include "radchain/physics/photometry.hpp"
#include "radchain/physics/psf.hpp"
#include "radchain/command_options.hpp"
#include "radchain/imaging/render.hpp"
#include "render_test_helpers.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>

namespace {
using namespace radchain;
using namespace radchain::render;
using radchain::render_tests::load;
using radchain::render_tests::sbv_fine_adc;

// Electrons in the n×n window centred on pixel (x, y) of an expected-electron image, less a uniform background.
double window(const Image& image, int x, int y, int n, double background) {
  double sum = 0;
  for (int j = y - n / 2; j < y - n / 2 + n; ++j)
    for (int i = x - n / 2; i < x - n / 2 + n; ++i) sum += image(i, j) - background;
  return sum;
}

struct Stats {
  double mean = 0, variance = 0;
  long n = 0;
};
Stats stats(const std::vector<float>& values, double scale = 1.0, double shift = 0.0) {
  Stats s;
  double sum = 0, sum2 = 0;
  for (float v : values) {
    const double x = (v - shift) * scale;
    sum += x;
    sum2 += x * x;
  }
  s.n = static_cast<long>(values.size());
  s.mean = sum / s.n;
  s.variance = (sum2 - sum * sum / s.n) / (s.n - 1);
  return s;
}

TEST(RenderSpaceFrame, DefaultTargetIsTheChainsLimitingMagnitude) {
  auto sbv = load("msx-sbv.toml");
  SpaceFrameOptions o;
  o.width = o.height = 32;
  o.noise = NoiseTerms::none();
  const SpaceFrameSetup s = space_frame_setup(sbv.chain, sbv.report, o);
  ASSERT_EQ(s.sources.size(), 1u);
  EXPECT_NEAR(s.limiting_magnitude, *sbv.report.value("target.magnitude"), 1e-12);
  EXPECT_NEAR(s.limiting_magnitude, 15.5565, 5e-4);  // Pan 2010 Table 2: 15.55
  // The chain publishes no PSF: the whole image in one pixel (Pan's EE = 1), so its electrons are the signal.
  EXPECT_EQ(s.psf, PsfModel::pixel);
  EXPECT_NEAR(s.sources[0].electrons, *sbv.report.value("detector.signal_electrons"), 1e-9);
  EXPECT_NEAR(s.dark_electrons, 18.0 * 0.625, 1e-12);
  EXPECT_NEAR(s.gain_e_per_dn, 1e5 / 4096.0, 1e-12);
  EXPECT_DOUBLE_EQ(s.snr_threshold, 5.0);
  // The chain is put back where it was.
  EXPECT_NEAR(sbv.chain.parameter("target.magnitude").value(), s.limiting_magnitude, 1e-12);
  const SpaceFrameRenderer r(s);
  EXPECT_NEAR(r.window_fraction(0, 1), 1.0, 1e-15);
  EXPECT_EQ(r.source_pixel(0), std::make_pair(16, 16));
}

TEST(RenderSpaceFrame, ChainElectronsFollowPogson) {
  // point_source_electrons evaluates the chain: 5 magnitudes are a factor 100 exactly (Pan 2010 eq. 1).
  auto sbv = load("msx-sbv.toml");
  const double e10 = point_source_electrons(sbv.chain, 10.0), e15 = point_source_electrons(sbv.chain, 15.0);
  EXPECT_NEAR(e10 / e15, 100.0, 1e-9);
  EXPECT_NEAR(physics::magnitude_ratio(10.0) / physics::magnitude_ratio(15.0), 100.0, 1e-9);
}

TEST(RenderSpaceFrame, AiryPhotometryMatchesEnsquaredEnergy) {
  // Windows of the rendered (expected) frame against the Airy ensquared energy by quadrature of the encircled
  // energy (physics/psf.hpp, Born & Wolf) — an independent computation of the FFT-built pixel-integrated PSF.
  auto sbv = load("msx-sbv.toml");
  for (const double pitch : {27e-6, 4e-6}) {  // PSF core far inside a pixel; PSF about two pixels wide
    SpaceFrameOptions o;
    o.width = o.height = 96;
    o.noise = NoiseTerms::none();
    o.focal_length_m = 0.45;  // f/3 with the 15 cm pupil
    o.pixel_pitch_m = pitch;
    o.psf = PsfModel::airy;
    o.psf_wavelength_m = 0.6e-6;
    o.obscuration = 0.3;
    o.targets = {{48.5, 48.5, 12.0}};  // on a pixel centre
    const SpaceFrameRenderer r(space_frame_setup(sbv.chain, sbv.report, o));
    const Image expected = r.expected_electrons();
    const double total = r.setup().sources[0].electrons, background = r.setup().dark_electrons;
    for (int n : {1, 3, 5, 9}) {
      const double ee = physics::airy_ensquared_energy(n * pitch, 0.6e-6, 3.0, 0.3);
      EXPECT_NEAR(window(expected, 48, 48, n, background) / total, ee, 2e-3 * ee) << "pitch " << pitch << " window " << n;
      EXPECT_NEAR(r.window_fraction(0, n), ee, 2e-3 * ee);
    }
  }
}

TEST(RenderSpaceFrame, GaussianPhotometryIsExact) {
  auto sbv = load("msx-sbv.toml");
  SpaceFrameOptions o;
  o.width = o.height = 48;
  o.noise = NoiseTerms::none();
  o.pixel_pitch_m = 10e-6;
  o.psf = PsfModel::gaussian;
  o.gaussian_fwhm_m = 18e-6;
  o.targets = {{24.5, 24.5, 12.0}, {10.25, 30.625, 12.0}};  // a centre, and a position on the 1/8-pixel grid
  const SpaceFrameRenderer r(space_frame_setup(sbv.chain, sbv.report, o));
  for (int n : {1, 3, 5}) EXPECT_NEAR(r.window_fraction(0, n), physics::gaussian_ensquared_energy(n * 10e-6, 18e-6), 1e-12);
  // Off-centre: the product of the two 1-D pixel integrals.
  const double sigma = 1.8 / (2.0 * std::sqrt(2.0 * std::log(2.0)));
  auto axis = [&](double offset) { return 0.5 * (std::erf((0.5 - offset) / (std::sqrt(2.0) * sigma)) + std::erf((0.5 + offset) / (std::sqrt(2.0) * sigma))); };
  EXPECT_EQ(r.source_pixel(1), std::make_pair(10, 30));
  EXPECT_NEAR(r.window_fraction(1, 1), axis(-0.25) * axis(0.125), 1e-12);
}

TEST(RenderSpaceFrame, ChainPsfClosesTheLoop) {
  // The sensor's own PSF and window (telescope psf = "airy", ccd_frame pixel_pitch and window_pixels): the rendered
  // window holds the chain's detector.signal_electrons.
  Chain chain;
  Report report;
  try {
    auto l = load("msx-sbv.toml", {{"optics.focal_length", "45 cm"}, {"optics.psf", "airy"}, {"optics.psf_wavelength", "0.6 um"},
                                   {"optics.obscuration", "0.3"}, {"detector.pixel_pitch", "5 um"}, {"detector.window_pixels", "3"}});
    chain = std::move(l.chain);
    report = std::move(l.report);
  } catch (const InputError& e) {
    GTEST_SKIP() << "this build's plugins have no PSF keys: " << e.what();
  }
  SpaceFrameOptions o;
  o.width = o.height = 64;
  o.noise = NoiseTerms::none();
  const SpaceFrameRenderer r(space_frame_setup(chain, report, o));
  EXPECT_EQ(r.setup().psf, PsfModel::airy);
  EXPECT_EQ(r.setup().window_pixels, 9);
  const double background = r.setup().dark_electrons;
  const double rendered = window(r.expected_electrons(), 32, 32, 3, background);
  EXPECT_NEAR(rendered, *report.value("detector.signal_electrons"), 2e-3 * rendered);
  EXPECT_NEAR(r.window_fraction(0, 3), *report.value("detector.ensquared_energy"), 2e-3);
}

TEST(RenderSpaceFrame, DarkAndReadNoiseStatistics) {
  // A frame with neither sources nor sky: DN × gain has mean N_d and variance N_d + σ_read² + g²/12 (EMVA 1288
  // quantisation noise; g = 1e5/65536 = 1.53 e-/DN is fine enough for Sheppard's correction to hold).
  auto sbv = sbv_fine_adc();
  SpaceFrameOptions o;
  o.width = o.height = 256;
  o.no_default_target = true;
  o.offset_dn = 100;
  const SpaceFrameRenderer r(space_frame_setup(sbv.chain, sbv.report, o));
  const SpaceFrameSetup& s = r.setup();
  const Image frame = r.render(7);
  const Stats st = stats(frame.pixels, s.gain_e_per_dn, s.offset_dn);
  const double variance = s.dark_electrons + 36.0 + s.gain_e_per_dn * s.gain_e_per_dn / 12.0;
  EXPECT_NEAR(st.mean, s.dark_electrons, 4.0 * std::sqrt(variance / st.n));
  EXPECT_NEAR(st.variance, variance, 4.0 * variance * std::sqrt(2.0 / st.n));
  // Per term: dark alone (no read noise, no ADC) is Poisson: variance = mean.
  o.noise.read = o.noise.quantisation = false;
  const SpaceFrameRenderer dark_only(space_frame_setup(sbv.chain, sbv.report, o));
  const Stats d = stats(dark_only.render(8).pixels);
  EXPECT_NEAR(d.mean, 11.25, 4.0 * std::sqrt(11.25 / d.n));
  EXPECT_NEAR(d.variance, 11.25, 4.0 * 11.25 * std::sqrt(2.0 / d.n));
  // Read noise alone: Gaussian of σ = 6 e- about the (noise-free) dark level.
  o.noise = NoiseTerms::none();
  o.noise.read = true;
  const SpaceFrameRenderer read_only(space_frame_setup(sbv.chain, sbv.report, o));
  const Stats rd = stats(read_only.render(9).pixels);
  EXPECT_NEAR(rd.mean, 11.25, 4.0 * 6.0 / std::sqrt(rd.n));
  EXPECT_NEAR(rd.variance, 36.0, 4.0 * 36.0 * std::sqrt(2.0 / rd.n));
}

TEST(RenderSpaceFrame, PoissonSamplersAgreeWithTheLaw) {
  // Shot noise through both paths: a flat field (the tabulated background law) and one target per pixel (drawn
  // term by term: inversion below a mean of 10, PTRS above). Mean and variance of a Poisson law are its mean.
  auto sbv = load("msx-sbv.toml");
  for (const double magnitude : {17.5, 12.0}) {  // about 8 and 1250 electrons
    SpaceFrameOptions o;
    o.width = o.height = 64;
    o.noise = NoiseTerms::none();
    o.noise.shot = true;
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) o.targets.push_back({x + 0.5, y + 0.5, magnitude});
    const SpaceFrameRenderer each(space_frame_setup(sbv.chain, sbv.report, o));
    const double mu = each.setup().sources[0].electrons;
    const double dark = each.setup().dark_electrons;
    const Stats a = stats(each.render(3).pixels, 1.0, dark);
    EXPECT_NEAR(a.mean, mu, 4.0 * std::sqrt(mu / a.n)) << magnitude;
    EXPECT_NEAR(a.variance, mu, 4.0 * mu * std::sqrt(2.0 / a.n)) << magnitude;
    SpaceFrameOptions f = o;
    f.targets.clear();
    f.no_default_target = true;
    f.flat_field_electrons = mu;
    const SpaceFrameRenderer flat(space_frame_setup(sbv.chain, sbv.report, f));
    const Stats b = stats(flat.render(4).pixels, 1.0, dark);
    EXPECT_NEAR(b.mean, mu, 4.0 * std::sqrt(mu / b.n)) << magnitude;
    EXPECT_NEAR(b.variance, mu, 4.0 * mu * std::sqrt(2.0 / b.n)) << magnitude;
  }
}

TEST(RenderSpaceFrame, SameSeedSameFrame) {
  auto sbv = load("msx-sbv.toml");
  SpaceFrameOptions o;
  o.width = o.height = 64;
  o.stars.count = 20;
  o.stars.seed = 5;
  o.focal_length_m = 0.45;
  o.pixel_pitch_m = 8e-6;
  o.psf = PsfModel::airy;
  o.psf_wavelength_m = 0.6e-6;
  const SpaceFrameRenderer r(space_frame_setup(sbv.chain, sbv.report, o));
  const Image a = r.render(42), b = r.render(42), c = r.render(43);
  EXPECT_EQ(a.pixels, b.pixels);
  EXPECT_NE(a.pixels, c.pixels);
  // A second renderer from the same options gives the same frame (star field from its own seed).
  const SpaceFrameRenderer r2(space_frame_setup(sbv.chain, sbv.report, o));
  EXPECT_EQ(r2.render(42).pixels, a.pixels);
  // The sequence is pinned: std::mt19937_64 and the distributions here are fully specified, so this sum is the
  // same with any standard library (a change of algorithm shows up here).
  double checksum = 0;  // position-weighted, so that moved values count too
  for (std::size_t i = 0; i < a.size(); ++i) checksum += static_cast<double>(i % 101 + 1) * a.pixels[i];
  EXPECT_EQ(checksum, 101768.0) << "the frame for seed 42 changed";
}

TEST(RenderSpaceFrame, StarFieldFollowsItsCounts) {
  auto sbv = load("msx-sbv.toml");
  SpaceFrameOptions o;
  o.width = o.height = 512;
  o.no_default_target = true;
  o.stars = {4000, 8.0, 16.0, 0.4, 11};
  o.noise = NoiseTerms::none();
  const SpaceFrameSetup s = space_frame_setup(sbv.chain, sbv.report, o);
  ASSERT_EQ(s.sources.size(), 4000u);
  long fainter_than_14 = 0;
  for (const auto& src : s.sources) {
    EXPECT_GE(src.magnitude, 8.0);
    EXPECT_LE(src.magnitude, 16.0);
    EXPECT_GE(src.x_px, 0.0);
    EXPECT_LT(src.x_px, 512.0);
    fainter_than_14 += src.magnitude > 14.0;
    EXPECT_NEAR(src.electrons / point_source_electrons(sbv.chain, 16.0), std::pow(10.0, 0.4 * (16.0 - src.magnitude)), 1e-9 * src.electrons);
  }
  // N(<m) ∝ 10^{0.4 m}: P(m > 14) = 1 − (10^{0.4·6} − 1)/(10^{0.4·8} − 1) = 0.6024.
  const double p = 1.0 - (std::pow(10.0, 2.4) - 1.0) / (std::pow(10.0, 3.2) - 1.0);
  EXPECT_NEAR(fainter_than_14 / 4000.0, p, 4.0 * std::sqrt(p * (1 - p) / 4000.0));
}

TEST(RenderSpaceFrame, SaturationAndAdcRange) {
  auto sbv = load("msx-sbv.toml");
  SpaceFrameOptions o;
  o.width = o.height = 16;
  o.targets = {{8.5, 8.5, 3.0}};  // ~1e7 electrons: far over the 1e5 e- well
  const SpaceFrameRenderer r(space_frame_setup(sbv.chain, sbv.report, o));
  const Image frame = r.render(1);
  EXPECT_EQ(frame(8, 8), 4095.0f);
  for (float v : frame.pixels) {
    EXPECT_GE(v, 0.0f);
    EXPECT_LE(v, 4095.0f);
    EXPECT_EQ(v, std::floor(v));
  }
  o.noise.quantisation = false;
  o.noise.read = false;
  const Image electrons = SpaceFrameRenderer(space_frame_setup(sbv.chain, sbv.report, o)).render(1);
  EXPECT_EQ(electrons(8, 8), 1e5f);
}

TEST(RenderSpaceFrame, RefusesSensorsItCannotRender) {
  auto kolobrodov = load("kolobrodov-1996-ccd151-computed.toml");
  EXPECT_THROW(space_frame_setup(kolobrodov.chain, kolobrodov.report, SpaceFrameOptions{}), InputError);
  auto sbv = load("msx-sbv.toml");
  SpaceFrameOptions o;
  o.psf = PsfModel::airy;  // no focal length, pitch or wavelength in the file
  EXPECT_THROW(space_frame_setup(sbv.chain, sbv.report, o), InputError);
  // A circular photometric aperture: the frame checks count n×n windows, so it is refused, not mismeasured.
  auto circle = load("rubin-lsst-r-m5.toml", {{"detector.photometry", "circle"}, {"detector.aperture_radius", "1 arcsec"}});
  try {
    space_frame_setup(circle.chain, circle.report, SpaceFrameOptions{});
    ADD_FAILURE() << "a circular aperture was rendered";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("photometry = \"circle\" is not measured on frames"), std::string::npos) << e.what();
  }
}

}  // namespace

namespace {

// The README's render example (msx-sbv, 45 cm, 27 µm, 200 stars, 512²) through render_image and its preview: the
// noise is 0/1 DN at 24 e-/DN, so a median-to-99.99 % asinh stretch drew 44 % of the pixels as grey salt and the
// stars could not be told from it. With the black point at the background + 2σ the sky is black and the stars are
// the bright pixels: a picture a user recognises as a star field.
TEST(RenderPreview, TheReadmeStarFieldShowsStarsOnABlackSky) {
  auto sbv = load("msx-sbv.toml");
  OptionValues given;
  given.given = {{"--focal-length", "45 cm"}, {"--pixel-pitch", "27 um"}, {"--stars", "200"}};
  const RenderRequest request{validated_options(render_option_schema(), given, "radchain render"), {}, {}, 1, 1};
  const RenderedImage r = render_image(sbv.chain, sbv.report, request);
  ASSERT_EQ(r.kind, SensorImage::point_frame);
  const std::string png = (std::filesystem::temp_directory_path() /
                           ("radchain-preview-" + std::to_string(::getpid()) + ".png")).string();
  write_preview(png, r.image, preview_options(request.options, r.kind));
  const Image preview = read_image(png).image;
  std::filesystem::remove(png);
  ASSERT_EQ(preview.width, 512);
  long black = 0, bright = 0, bright_on_a_star = 0;
  for (int y = 0; y < preview.height; ++y)
    for (int x = 0; x < preview.width; ++x) {
      black += preview(x, y) <= 10;
      if (preview(x, y) >= 128) {
        ++bright;
        bright_on_a_star += r.image(x, y) >= 3;  // ≥ 3 DN: 5σ above the 0.45 DN background, a star
      }
    }
  const double pixels = 512.0 * 512.0;
  EXPECT_GT(black / pixels, 0.99) << "the background is not dark";
  EXPECT_GE(bright, 20) << "too few stars show";
  EXPECT_EQ(bright_on_a_star, bright) << "bright preview pixels that are noise, not stars";
}

}  // namespace
