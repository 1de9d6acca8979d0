#pragma once
// A detector frame of a point-target sensor (a ccd_frame chain): what the designed sensor would see.
//
// Per pixel, in this order (docs/rendering.md):
//   mean     μ = Σ_sources S_k · ePSF_k(pixel) + B_sky + N_d           electrons
//            S_k from the chain (target.magnitude set, chain evaluated, detector.image_electrons read — the whole
//            point image; detector.signal_electrons when the detector publishes no image_electrons, i.e. EE = 1)
//            ePSF = the optics PSF integrated over the pixel (Airy of the annular pupil, Gaussian, or "pixel":
//            the whole image in one pixel as Pan 2010 assumes), for the source's position rounded to
//            1/oversampling pixel; N_d = dark rate × t per pixel
//   collect  n = Poisson(S·ePSF + B_sky) + Poisson(N_d)   (one Poisson draw of the sum: the same law)
//   well     n = min(n, full well)
//   read     e = n + σ_read · Z,  Z ~ N(0, 1)
//   ADC      DN = clamp(floor(e / g + ½) + offset, 0, 2^bits − 1),  g = full well / 2^bits  e-/DN
// Each term can be switched off (NoiseTerms): off, a fluctuation is replaced by its mean; without the ADC the
// frame is electrons (float).
//
// Random numbers: std::mt19937_64 (its output sequence is fixed by the C++ standard) and distributions written
// here (Poisson: inversion below a mean of 10, Hörmann's PTRS above; normal: Marsaglia's polar method), so a
// seed gives the same frame with any standard library; std::poisson_distribution and normal_distribution are
// implementation-defined (they would be reproducible only within one libstdc++). Pixels that no source
// reaches all have the same law (Poisson ⊛ normal through the ADC), which is tabulated once and sampled with
// Walker's alias method from 32 random bits (two pixels per 64-bit draw): every value's probability is held to
// within 2^-32, so values rarer than that per pixel are not drawn. Pixels with source light take their
// background counts from the same law's Poisson table and draw the source's share, the read noise and the
// ADC term by term (53-bit uniforms).
#include "radchain/chain.hpp"
#include "radchain/imaging/image.hpp"

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace radchain::render {

enum class PsfModel {
  pixel,     // the whole point image in the pixel that holds it (Pan 2010: ensquared energy 1)
  airy,      // diffraction-limited annular pupil at one wavelength (Born & Wolf §8.5.2; obscuration ε)
  gaussian,  // Gaussian of a given FWHM on the focal plane
};
std::string to_string(PsfModel model);
std::optional<PsfModel> psf_model_from_string(const std::string& name);  // "pixel", "airy", "gaussian"

// Which fluctuations and limits are simulated (all by default; none() gives the expected frame).
struct NoiseTerms {
  bool shot = true;          // Poisson photon noise of sources and sky
  bool dark = true;          // Poisson dark-current noise
  bool read = true;          // Gaussian read noise
  bool saturation = true;    // collected charge clipped at the full well
  bool quantisation = true;  // ADC: the frame is in DN; off: electrons
  static NoiseTerms none() { return {false, false, false, false, false}; }
};

// A point target in pixel coordinates: pixel (i, j) covers [i, i+1) × [j, j+1), its centre is (i + ½, j + ½).
struct PointTarget {
  double x_px = 0, y_px = 0;
  double magnitude = 0;  // visual magnitude, as the chain's target.magnitude; NaN: the limiting magnitude
};

// A synthetic star field: `count` stars uniform over the frame with cumulative counts N(<m) ∝ 10^(slope·m)
// between bright_magnitude and faint_magnitude. slope = 0.6 is a uniform Euclidean distribution of stars;
// the Galaxy's counts are flatter at faint magnitudes — d log N/dm ≈ 0.3-0.4 at V ≈ 14-20 toward
// intermediate and high galactic latitudes (Bahcall & Soneira 1980, ApJS 44, 73, the model counts of their
// Galaxy model) — hence the default 0.4. A single power law is a simple model, not a star catalogue.
struct StarField {
  int count = 0;
  double bright_magnitude = 8.0;
  std::optional<double> faint_magnitude;  // default: the limiting magnitude + 1
  double slope = 0.4;                     // d log10 N(<m) / dm
  std::uint64_t seed = 1;                 // positions and magnitudes (the noise has its own seed)
};

struct SpaceFrameOptions {
  int width = 256, height = 256;
  // Point targets; none given (and no flat field): one at the solved limiting magnitude in the frame centre.
  std::vector<PointTarget> targets;
  bool no_default_target = false;  // a frame of only stars / sky / dark
  StarField stars;
  // Uniform signal in every pixel, electrons per pixel per frame (shot noise as a source): a flat field.
  double flat_field_electrons = 0.0;

  // Geometry and PSF; unset = from the chain: optics.focal_length, detector.pixel_pitch, optics.psf_wavelength
  // (Airy) or optics.gaussian_fwhm (Gaussian), optics.obscuration. A chain without a PSF renders psf = pixel.
  std::optional<double> focal_length_m, pixel_pitch_m;
  std::optional<PsfModel> psf;
  std::optional<double> psf_wavelength_m, gaussian_fwhm_m, obscuration;
  int oversampling = 8;                  // PSF phases per pixel: positions are rounded to 1/oversampling pixel
  // Moving targets: streak lengths along +x per frame in pixels (targets: sidereal tracking; stars: rate
  // tracking); unset = from the chain (detector.target_streak_pixels, detector.star_streak_pixels), else 0.
  // A streak is the Gaussian PSF convolved with the segment, exact per pixel (physics/streak.hpp), starting
  // half a streak before the position given and ending half a streak after it.
  std::optional<double> target_streak_px, star_streak_px;
  std::optional<int> stamp_radius_px;    // PSF stamp half-size (default: 99.9 % of the energy, at most 32)

  // Detector; unset = from the chain (detector.sky_electrons_per_pixel, else 0; full_well / 2^adc_bits).
  std::optional<double> sky_electrons_per_pixel;
  std::optional<double> gain_e_per_dn;
  double offset_dn = 0.0;  // ADC pedestal
  NoiseTerms noise;
};

struct RenderedSource {
  double x_px = 0, y_px = 0;  // as requested
  double magnitude = 0;
  double electrons = 0;  // the whole point image, from the chain
  bool target = false;   // a target (not a field star)
};

// Everything a frame depends on, resolved from the chain and the options: plain numbers (SI unless named).
struct SpaceFrameSetup {
  std::string sensor_name, sensor_file;
  int width = 0, height = 0;
  // optics and PSF
  double aperture_m = 0, focal_length_m = 0, f_number = 0, obscuration = 0, pixel_pitch_m = 0;
  PsfModel psf = PsfModel::pixel;
  double psf_wavelength_m = 0, gaussian_fwhm_m = 0;
  int oversampling = 8, stamp_radius_px = 0;
  double target_streak_px = 0, star_streak_px = 0;  // along +x, pixels per frame
  // detector, per pixel and frame
  double integration_time_s = 0, dark_electrons = 0, read_noise_electrons = 0, sky_electrons = 0;
  double full_well_electrons = 0, gain_e_per_dn = 0, offset_dn = 0;
  int adc_bits = 0;
  double flat_field_electrons = 0;
  NoiseTerms noise;
  // the chain's answer, for the header and the checks
  double limiting_magnitude = 0;     // the solved target.magnitude (or as given when not solved)
  double snr_threshold = 0;          // the detection criterion's T (NaN when there is none)
  double limit_signal_electrons = 0; // detector.signal_electrons at the limiting magnitude (window sum)
  double limit_noise_electrons = 0;  // detector.noise_electrons there
  int window_pixels = 1;             // detector.window_pixel_count (n²), 1 when not published
  double chain_ensquared_energy = 1; // detector.ensquared_energy (1 when not published)
  std::vector<RenderedSource> sources;
  std::uint64_t star_seed = 0;
};

// Electrons of a point image at `magnitude`: sets target.magnitude, evaluates, reads detector.image_electrons
// (else detector.signal_electrons), and puts the magnitude back.
double point_source_electrons(Chain& chain, double magnitude);

// Resolves the options against a chain that has run (its Report gives the limiting magnitude). Throws
// InputError when the sensor is not a point-target frame sensor or lacks what the PSF needs (focal length,
// pixel pitch: give them as options).
SpaceFrameSetup space_frame_setup(Chain& chain, const Report& report, const SpaceFrameOptions& options);

class SpaceFrameRenderer {
 public:
  explicit SpaceFrameRenderer(SpaceFrameSetup setup);
  ~SpaceFrameRenderer();
  SpaceFrameRenderer(SpaceFrameRenderer&&) noexcept;
  SpaceFrameRenderer& operator=(SpaceFrameRenderer&&) noexcept;

  const SpaceFrameSetup& setup() const;
  // One frame: DN (or electrons without the ADC). The same seed gives the same frame.
  Image render(std::uint64_t seed) const;
  void render(std::uint64_t seed, Image& frame) const;  // into an existing image (no allocation when sized)
  // The mean electrons per pixel (sources + sky + dark + flat field), before any noise.
  Image expected_electrons() const;
  // Fraction of source k's image in the n×n window centred on the pixel that holds it, from the rendered ePSF.
  double window_fraction(std::size_t source, int window) const;
  // The pixel that holds source k (its rounded position).
  std::pair<int, int> source_pixel(std::size_t source) const;
  // "adu" with the ADC, else "electron".
  std::string unit() const;
  // The FITS cards of a frame rendered with `seed`.
  Header header(std::uint64_t seed) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace radchain::render
