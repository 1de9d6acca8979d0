#pragma once
// An Earth scene seen by a pushbroom sensor: a ground reflectance map in, the simulated image out. Two
// radiometries, chosen by what the chain publishes:
//   - exposure (a ccd_line chain, Kolobrodov 1996): the lamp-referenced noise-equivalent exposure;
//   - electrons (a datasheet detector, emva1288 on a reflectance_ground scene): electrons per unit reflectance,
//     the path radiance, dark, read, shot and fixed-pattern noise, the well and the detector's own ADC.
//
//   1. reflectance ρ(x, y) on the input grid (input_sampling_m per pixel on the ground, nadir view; rows are
//      image lines, so y is the along-track direction);
//   2. the system OTF applied in the Fourier domain (FFTW, the map mirror-padded):
//        optics:   the diffraction OTF of the annular pupil at the design f-number N and wavelength λ
//                  (Goodman 2005 ch. 6; criteria.<mtf_match>.wavelength by default), or Kolobrodov's eq. (7)
//                  line with the design quality η (criteria.<mtf_match>.required_quality), or the chain's MTF
//                  budget (a giqe criterion, physics/mtf_budget.hpp): diffraction × wavefront error × jitter ×
//                  diffusion radially, linear smear and TDI synchronisation along track (y), or none;
//        detector: sinc(V_D ν_x) · sinc(V_D ν_y), the square element of eq. (8) (signed: contrast reversal
//                  beyond 1/V_D is kept);
//      ground frequency ν_g ↔ focal-plane frequency ν = ν_g h / f' (platform.altitude, optics.focal_length);
//   3. point samples of the filtered field every output_sampling_m (default one detector sample, the
//      pixel-pitch GSD criteria.<name>.gsd_nadir = p h / f', else the designed ground element
//      criteria.<name>.ground_element = V_s h / f' of Kolobrodov's eq. 16): an integer
//      ratio of the two samplings takes every r-th input pixel, exactly; otherwise Keys' cubic interpolation;
//   4. exposure radiometry: H = ρ · K · t_i with K = detector.signal_irradiance / target.reflectance_difference,
//      the image-plane irradiance per unit reflectance (the chain is linear in ρ); noise H + H_nr · Z,
//      Z ~ N(0, 1), H_nr = detector.nee_working, so a step Δρ has SNR = K Δρ t_i / H_nr = detector.snr
//      (eqs. 20-21); saturation at H_m (detector.saturation_exposure × k_i/k_c) and an ADC of adc_bits over
//      [0, H_m]: DN = clamp(floor(H / q + ½) + offset, 0, 2^bits − 1), q = H_m / 2^bits;
//   5. electron radiometry (EMVA 1288 R4.0 eqs. 1-6, 18): the photo signal S = ρ k_ρ + S_path with
//      k_ρ = (detector.signal_electrons − detector.path_radiance_electrons) / target.reflectance (the chain is
//      linear in ρ; the path radiance does not depend on it); each pixel gets
//        e = S (1 + s_g G) + μ_d + σ_o D + √(S (1 + s_g G) + μ_d + σ_d²) Z
//      (G, D ~ N(0, 1) fixed per pixel and seed: PRNU and DSNU; Z temporal; μ_d = dark rate × N_tdi t), is
//      clipped at detector.saturation_capacity and read as DN = clamp(floor(K e + ½) + offset, 0, 2^bits − 1)
//      with the detector's K and bits; so a flat field at the chain's reflectance has the chain's detector.snr.
//      Binned (b×b, detector.binning) and co-added (M frames, detector.exposures) detectors: steps 1-3 give the
//      native pixels (one native sample = output sample / b), each of the M frames draws every native pixel as
//      above (its own well and ADC; the fixed pattern the same in every frame) and an output pixel is the sum of
//      its b×b native pixels over the M frames, digital binning and co-adding as the detector's noise model
//      counts them (EMVA 1288 eqs. 5, 6, 18 over b² pixels and M frames); the sum of b shifted pixel apertures
//      gives the binned pixel's MTF sinc(p ν) sin(π b p ν)/(b sin(π p ν)) per axis.
// Without the ADC the image is the exposure in J m-2 or the charge in electrons (float).
#include "radchain/chain.hpp"
#include "radchain/imaging/image.hpp"
#include "radchain/physics/mtf_budget.hpp"

#include <cstdint>
#include <optional>
#include <string>

namespace radchain::render {

enum class OpticsMtf {
  diffraction,     // exact diffraction OTF of the (annular) pupil
  kolobrodov_eq7,  // Kolobrodov 1996 eq. (7): 1 − 1.218 N λ ν / η, clamped at 0
  budget,          // the chain's MTF budget (a giqe criterion)
  none,
};
std::string to_string(OpticsMtf model);
std::optional<OpticsMtf> optics_mtf_from_string(const std::string& name);  // "diffraction", "eq7", "budget", "none"

enum class EarthRadiometry { exposure, electrons };

struct EarthSceneOptions {
  double input_sampling_m = 0;              // required: ground size of one input pixel
  std::optional<double> output_sampling_m;  // default criteria.<name>.gsd_nadir, else .ground_element
  std::optional<OpticsMtf> optics;     // default: the MTF budget when the chain has one, else diffraction
  std::optional<double> wavelength_m;  // default the budget's or mtf_match criterion's wavelength, else the band centre
  bool detector_mtf = true;
  std::optional<int> adc_bits;         // default: the detector's (detector.adc_bits), else 12
  std::optional<double> saturation_exposure_J_m2;  // working source; default from the detector
  double offset_dn = 0.0;
  bool noise = true;                   // exposure radiometry: the NEE; electrons: shot, dark and read (below)
  bool shot = true, dark = true, read = true;  // electron radiometry only (dark: its mean and shot noise, DSNU)
  bool saturation = true;
  bool quantisation = true;
};

struct EarthSceneSetup {
  std::string sensor_name, sensor_file;
  double altitude_m = 0, focal_length_m = 0, aperture_m = 0, f_number = 0, obscuration = 0;
  double wavelength_m = 0, element_m = 0, pitch_m = 0, eta = 1;
  OpticsMtf optics = OpticsMtf::diffraction;
  physics::MtfBudget budget;  // optics == budget
  bool detector_mtf = true;
  double input_sampling_m = 0, output_sampling_m = 0;
  EarthRadiometry radiometry = EarthRadiometry::exposure;
  // electron radiometry (one native pixel, one frame; an output pixel sums binning² of them over `exposures` frames)
  double electrons_per_reflectance = 0, path_electrons = 0, dark_electrons = 0, read_noise_e = 0;
  int binning = 1, exposures = 1;
  double prnu = 0, dsnu_e = 0, gain_dn_per_e = 0, capacity_e = 0, scene_reflectance = 0;
  bool shot = true, dark = true, read = true;
  double irradiance_per_reflectance_W_m2 = 0;  // K
  double integration_time_s = 0, nee_J_m2 = 0, saturation_J_m2 = 0;
  int adc_bits = 12;
  double offset_dn = 0;
  bool noise = true, saturation = true, quantisation = true;
  // the chain's answer
  double reflectance_difference = 0, background_reflectance = 0, snr = 0;
  double ground_element_m = 0;  // criteria.resolution.ground_element
  double pixel_gsd_m = 0;       // criteria.<name>.gsd_nadir (0: not published)

  double exposure_per_reflectance() const { return irradiance_per_reflectance_W_m2 * integration_time_s; }
  double exposure_per_dn() const;  // q = H_m / 2^bits (exposure); 1/K electrons (electrons)
  // Mean photo signal (electrons) of a pixel of reflectance ρ: ρ k_ρ + S_path.
  double photo_electrons(double rho) const { return rho * electrons_per_reflectance + path_electrons; }
  double ground_to_focal() const { return focal_length_m / altitude_m; }  // focal-plane length per ground length
  double native_sampling_m() const { return output_sampling_m / binning; }  // one native pixel on the ground
  double native_sums() const { return static_cast<double>(exposures) * binning * binning; }  // M b² reads per output pixel
};

// Throws InputError when the chain is not a pushbroom design (names the missing result) or the options are bad.
EarthSceneSetup earth_scene_setup(Chain& chain, const Report& report, const EarthSceneOptions& options);

// The model's system MTF at a ground frequency (cycles per ground metre, components along x and y): the
// product in step 2 above, as a modulus.
double system_mtf(const EarthSceneSetup& setup, double nu_x_per_m, double nu_y_per_m);

// Output size for an input of `input_px` pixels: native samples floor((input_px − 1) / r) + 1 (r = native/input
// sampling), then floor(native / b) binned pixels.
int earth_output_size(const EarthSceneSetup& setup, int input_px);

// The simulated image of a reflectance map (DN, or exposure in J m-2 without the ADC). Same seed, same image.
Image render_earth_scene(const EarthSceneSetup& setup, const Image& reflectance, std::uint64_t seed);
// Steps 1-3 only: the filtered reflectance at the native samples (no radiometry, no noise, not binned).
Image filtered_reflectance(const EarthSceneSetup& setup, const Image& reflectance);
// "adu" with the ADC, else "J m-2" (exposure) or "electron".
std::string earth_unit(const EarthSceneSetup& setup);
Header earth_scene_header(const EarthSceneSetup& setup, std::uint64_t seed);

// ---- The project's test scene --------------------------------------------------------------------------

// Bar and edge targets on a uniform background, exact area coverage per pixel (so the map is the scene
// averaged over each input pixel):
//   top left: a slanted edge (angle from the vertical) between `background` and `bright`;
//   top right: three-bar groups (bars of `bright` on `background`) with bar widths 0.5, 0.7, 1, 1.4, 2, 2.8 and
//     4 × `bar_unit_m` (vertical and horizontal bars);
//   bottom left: low-contrast squares, background + k·`contrast` (k = 1, 2, 4, 8);
//   bottom right: a Siemens-star-like sector pattern of 16 sectors.
struct TestSceneOptions {
  int size_px = 1024;
  double sampling_m = 1.25;   // ground size of one pixel
  double bar_unit_m = 5.0;    // the designed ground element of the Kolobrodov camera
  double background = 0.3;    // ρ_0
  double bright = 0.6;
  double contrast = 0.003;    // Δρ (Kolobrodov: 1 % of 0.3)
  double edge_angle_deg = 5.0;
};
Image make_test_scene(const TestSceneOptions& options = {});
// A straight edge through the image centre at `angle_deg` from the vertical: `left` on the left, `right` on
// the right, each pixel the exact area fraction.
Image make_edge_scene(int width_px, int height_px, double angle_deg, double left, double right);
// A uniform map.
Image make_flat_scene(int width_px, int height_px, double reflectance);

}  // namespace radchain::render
