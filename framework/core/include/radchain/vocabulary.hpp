#pragma once
// The results stages exchange. A stage publishes "<section>.<name>" results; every one that another stage, the
// framework or the imaging library reads is a Term here, with its SI unit and meaning, so that publisher and
// reader agree on one spelling and one unit. A plugin declares such a result with Context::declare(term, ...)
// and reads one with Context::require(term) / find(term); both check the plugin's PluginInfo lists.
// A new shared result: add a Term here (and to `all` below), list it in the publisher's `publishes` and in the
// reader's `needs`. Results nobody else reads (a noise term for the report) stay plain strings in their plugin.
#include <array>
#include <string>
#include <string_view>

namespace radchain {

struct Term {
  std::string_view name;     // "detector.snr"; a criterion's result: "criteria.*.margin" (any criterion)
  std::string_view unit;     // SI, as udunits spells it ("1" for a ratio)
  std::string_view meaning;  // one line

  constexpr std::string_view section() const { return name.substr(0, name.rfind('.')); }  // "detector", "criteria.*"
  constexpr std::string_view key() const { return name.substr(name.rfind('.') + 1); }     // "snr"
  constexpr bool per_criterion() const { return name.starts_with("criteria.*."); }
  // The result of this term in one criterion's section: "criteria.detection.margin".
  std::string in_criterion(std::string_view criterion) const {
    return "criteria." + std::string(criterion) + "." + std::string(key());
  }
  // Whether a qualified result name is this term (for a per-criterion term: in any criterion).
  constexpr bool matches(std::string_view qualified) const {
    if (!per_criterion()) return qualified == name;
    return qualified.starts_with("criteria.") && qualified.size() > 9 + key().size() + 1 &&
           qualified.ends_with(key()) && qualified[qualified.size() - key().size() - 1] == '.' &&
           qualified.substr(9, qualified.size() - 9 - key().size() - 1).find('.') == std::string_view::npos;
  }
  friend constexpr bool operator==(const Term& a, const Term& b) { return a.name == b.name; }
};

namespace vocabulary {

// platform
inline constexpr Term platform_altitude{"platform.altitude", "m", "height of the platform above the ground"};
inline constexpr Term platform_ground_speed{"platform.ground_speed", "m/s", "speed of the sub-platform point over the ground"};
inline constexpr Term platform_tilt{"platform.tilt", "rad", "line-of-sight tilt from nadir"};

// source
inline constexpr Term source_visual_magnitude{"source.visual_magnitude", "1",
                                              "the source's apparent V magnitude (reference for a target's magnitude)"};
inline constexpr Term source_illuminance{"source.illuminance", "lx", "the source's illuminance (at 1 AU for the Sun)"};
inline constexpr Term source_distance{"source.distance", "m", "distance of the source from the target"};
inline constexpr Term source_solar_declination{"source.solar_declination", "rad",
                                               "the Sun's declination δ on the scene's day (Spencer 1971)"};
inline constexpr Term source_solar_zenith{"source.solar_zenith", "rad",
                                          "the Sun's zenith angle at the scene, when the source is given it (spectral: "
                                          "an atmosphere's down path reads it in its spectral phase)"};
inline constexpr Term source_band_irradiance{"source.band_irradiance", "W m-2",
                                             "the source's irradiance in the reporting band E'_s"};

// atmosphere
inline constexpr Term atmosphere_ground_irradiance{"atmosphere.ground_irradiance", "W m-2",
                                                   "in-band irradiance on the ground after the down path E_0"};

// target
inline constexpr Term target_illuminance{"target.illuminance", "lx", "illuminance at the pupil from the point target"};
inline constexpr Term target_reflectance_difference{"target.reflectance_difference", "1",
                                                    "reflectance contrast of target and background Δρ"};
inline constexpr Term target_background_exitance{"target.background_exitance", "W m-2",
                                                 "in-band exitance of the background M_b"};

// optics
inline constexpr Term optics_aperture{"optics.aperture", "m", "entrance pupil diameter D"};
inline constexpr Term optics_obscuration{"optics.obscuration", "1", "linear central obscuration ratio ε"};
inline constexpr Term optics_collecting_area{"optics.collecting_area", "m2", "unobscured pupil area"};
inline constexpr Term optics_transmittance{"optics.transmittance", "1", "optics transmittance τ"};
inline constexpr Term optics_focal_length{"optics.focal_length", "m", "effective focal length f'"};
inline constexpr Term optics_f_number{"optics.f_number", "1", "focal ratio N = f'/D"};
inline constexpr Term optics_psf_wavelength{"optics.psf_wavelength", "m", "wavelength of an Airy point-spread function"};
inline constexpr Term optics_gaussian_fwhm{"optics.gaussian_fwhm", "m", "FWHM of a Gaussian point-spread function"};

// detector
inline constexpr Term detector_snr{"detector.snr", "1", "signal-to-noise ratio of the target in the detection window"};
inline constexpr Term detector_integration_time{"detector.integration_time", "s", "integration time of one frame or line"};
inline constexpr Term detector_signal_electrons{"detector.signal_electrons", "electron",
                                                "the target's electrons in the detection window"};
inline constexpr Term detector_image_electrons{"detector.image_electrons", "electron",
                                               "all of the point image's electrons (before the window's ensquared energy)"};
inline constexpr Term detector_noise_electrons{"detector.noise_electrons", "electron", "total noise in the detection window"};
inline constexpr Term detector_sky_electrons_per_pixel{"detector.sky_electrons_per_pixel", "electron",
                                                       "one pixel's sky background per frame"};
inline constexpr Term detector_window_pixel_count{"detector.window_pixel_count", "1", "pixels in the detection window"};
inline constexpr Term detector_ensquared_energy{"detector.ensquared_energy", "1",
                                                "fraction of the point image inside the detection window"};
inline constexpr Term detector_aperture_radius_pixels{"detector.aperture_radius_pixels", "1",
                                                      "radius of a circular photometric aperture in (binned) pixels"};
inline constexpr Term detector_signal_irradiance{"detector.signal_irradiance", "W m-2",
                                                 "in-band focal-plane irradiance of the target contrast E'"};
inline constexpr Term detector_nee_working{"detector.nee_working", "J m-2", "working noise-equivalent exposure H_nr"};
inline constexpr Term detector_utilisation_ratio{"detector.utilisation_ratio", "1",
                                                 "spectral utilisation ratio k_i/k_c of the detector"};
inline constexpr Term detector_element_size_for_mtf{"detector.element_size_for_mtf", "m",
                                                    "detector element size V_D in the MTF (Kolobrodov eq. 8)"};
inline constexpr Term detector_nu_half_contrast{"detector.nu_half_contrast", "m-1",
                                                "spatial frequency at which the detector MTF is 0.5"};
inline constexpr Term detector_system_element{"detector.system_element", "m", "system resolution element V_s in the focal plane"};
inline constexpr Term detector_line_length{"detector.line_length", "m", "length of the detector line l_D"};

// What render and validate read of a detector and a ground target (any detector that publishes these
// renders; saturation capacity and pixel pitch are terms of their own, below)
inline constexpr Term detector_adc_bits{"detector.adc_bits", "1", "ADC resolution N (bits)"};
inline constexpr Term detector_dark_rate{"detector.dark_rate", "electron s-1", "dark current of one pixel"};
inline constexpr Term detector_read_noise_per_pixel{"detector.read_noise_per_pixel", "electron",
                                                    "read noise of one pixel (rms)"};
inline constexpr Term detector_band_min{"detector.band_min", "m", "lower limit λ1 of the detector band"};
inline constexpr Term detector_band_max{"detector.band_max", "m", "upper limit λ2 of the detector band"};
inline constexpr Term detector_saturation_exposure{"detector.saturation_exposure", "J m-2",
                                                   "saturation exposure H_m of a line detector (reference lamp)"};
inline constexpr Term target_background_reflectance{"target.background_reflectance", "1",
                                                    "reflectance ρ_b of the background around a ground target"};

// Datasheet detectors and telescopes
inline constexpr Term detector_peak_pixel_fill{"detector.peak_pixel_fill", "1",
                                               "brightest pixel's charge / saturation capacity (> 1: saturated)"};
inline constexpr Term detector_saturation_capacity{"detector.saturation_capacity", "electron",
                                                   "saturation capacity of one pixel μ_e.sat (EMVA 1288)"};
inline constexpr Term detector_peak_pixel_electrons{"detector.peak_pixel_electrons", "electron",
                                                    "charge in the brightest pixel (target + sky + dark) per exposure"};
inline constexpr Term detector_noise_equivalent_area{"detector.noise_equivalent_area", "1",
                                                     "PSF-weighted photometry's noise-equivalent area n_eff in pixels"};
inline constexpr Term detector_system_gain{"detector.system_gain", "electron-1", "system gain K in DN per electron"};
inline constexpr Term detector_tdi_stages{"detector.tdi_stages", "1", "TDI stages N summed in the charge domain"};
inline constexpr Term target_zero_point_photon_rate{"target.zero_point_photon_rate", "m-2 s-1",
                                                    "photons per second and m² of magnitude 0 in the target's band"};
inline constexpr Term target_band_magnitude{"target.band_magnitude", "1", "target magnitude in its band and system"};
inline constexpr Term atmosphere_airmass{"atmosphere.airmass", "1", "airmass X of the line of sight"};
inline constexpr Term atmosphere_seeing_fwhm{"atmosphere.seeing_fwhm", "rad", "seeing FWHM at the line of sight's airmass"};
inline constexpr Term atmosphere_sky_brightness{"atmosphere.sky_brightness", "1",
                                                "sky surface brightness in AB mag/arcsec² as measured at the site"};
// Moving targets: streak lengths per exposure and the PSF they smear, for render and validate
inline constexpr Term detector_target_streak_pixels{"detector.target_streak_pixels", "1",
                                                    "length of the moving target's streak per exposure in pixels as read out (binned)"};
inline constexpr Term detector_star_streak_pixels{"detector.star_streak_pixels", "1",
                                                  "length of the stars' streaks per exposure in pixels as read out (rate tracking)"};
inline constexpr Term detector_trailing_loss{"detector.trailing_loss", "1",
                                             "magnitudes a streak loses against the still PSF, background-limited"};
inline constexpr Term detector_psf_fwhm{"detector.psf_fwhm", "m",
                                        "FWHM of the Gaussian PSF on the focal plane that the detector counts with"};

// every criterion ("criteria.<name>.…")
inline constexpr Term criterion_margin{"criteria.*.margin", "1",
                                       "achieved/required − 1: ≥ 0 passes; the root a [[solve]] finds"};
inline constexpr Term criterion_threshold{"criteria.*.threshold", "1", "SNR threshold T of a detection criterion"};
inline constexpr Term criterion_required_quality{"criteria.*.required_quality", "1",
                                                 "objective quality η that matches the detector MTF"};
inline constexpr Term criterion_wavelength{"criteria.*.wavelength", "m", "wavelength of the MTF match"};
inline constexpr Term criterion_ground_element{"criteria.*.ground_element", "m", "ground resolution element δV"};

// Earth-observation geometry
inline constexpr Term platform_roll{"platform.roll", "rad", "look angle about the along-track axis (across-track)"};
inline constexpr Term platform_pitch{"platform.pitch", "rad", "look angle about the across-track axis (along-track)"};
inline constexpr Term platform_slant_range{"platform.slant_range", "m",
                                           "distance from the platform to the ground point of the look (spherical Earth)"};
inline constexpr Term platform_view_zenith_angle{"platform.view_zenith_angle", "rad",
                                                 "zenith angle of the line of sight at the ground point (set in the "
                                                 "platform's spectral phase too: an atmosphere's view airmass reads it there)"};
inline constexpr Term platform_earth_radius{"platform.earth_radius", "m",
                                            "radius of the spherical Earth of the geometry"};
inline constexpr Term detector_pixel_pitch{"detector.pixel_pitch", "m",
                                           "centre-to-centre distance of the pixels (one sample)"};
inline constexpr Term criterion_gsd_nadir{"criteria.*.gsd_nadir", "m",
                                          "pixel-pitch ground sample distance at nadir h p/f'"};
inline constexpr Term criterion_gsd_across_track{"criteria.*.gsd_across_track", "m",
                                                 "across-track ground sample distance at the look"};
inline constexpr Term criterion_gsd_along_track{"criteria.*.gsd_along_track", "m",
                                                "along-track ground sample distance at the look"};
inline constexpr Term criterion_niirs{"criteria.*.niirs", "1", "predicted NIIRS (General Image Quality Equation)"};
inline constexpr Term criterion_rer{"criteria.*.rer", "1", "relative edge response of the system MTF (per sample)"};
// Radiometry of Earth-observation cameras: an extended scene counted by étendue in a
// datasheet detector; the SNR at a reference radiance as mission requirements state it (band-averaged
// spectral radiance, W m-2 sr-1 µm-1 in the documents; SI here)
inline constexpr Term target_reflectance{"target.reflectance", "1", "Lambertian reflectance ρ of a ground target"};
inline constexpr Term detector_scene_radiance{"detector.scene_radiance", "W m-2 sr-1 m-1",
                                              "the scene's at-aperture spectral radiance averaged over the band (RSR-weighted)"};
inline constexpr Term detector_reference_radiance{"detector.reference_radiance", "W m-2 sr-1 m-1",
                                                  "band-averaged spectral radiance L_ref at which the SNR is stated"};
inline constexpr Term detector_reference_signal_electrons{"detector.reference_signal_electrons", "electron",
                                                          "signal electrons of one pixel at L_ref"};
inline constexpr Term detector_snr_at_reference{"detector.snr_at_reference", "1",
                                                "signal-to-noise ratio of one pixel at L_ref"};
inline constexpr Term detector_noise_equivalent_radiance{"detector.noise_equivalent_radiance", "W m-2 sr-1 m-1",
                                                         "NEΔL at L_ref: the radiance change equal to the noise (L_ref/SNR)"};
inline constexpr Term detector_noise_equivalent_reflectance{"detector.noise_equivalent_reflectance", "1",
                                                            "NEΔρ at L_ref: the reflectance change equal to the noise, "
                                                            "at the target's sun angle"};
inline constexpr Term detector_saturation_radiance{"detector.saturation_radiance", "W m-2 sr-1 m-1",
                                                   "band-averaged spectral radiance that fills the well or the ADC"};
// What `render` needs to draw an Earth scene with a datasheet detector: the scene's pixel
// splits into the ground's light (∝ ρ) and the path radiance, plus the detector's fixed-pattern terms
inline constexpr Term detector_path_radiance_electrons{"detector.path_radiance_electrons", "electron",
                                                       "the atmosphere's path radiance in the scene's pixel (0 without one)"};
inline constexpr Term detector_binning{"detector.binning", "1", "pixels binned per side b (b × b native pixels read as one)"};
inline constexpr Term detector_exposures{"detector.exposures", "1", "frames co-added M"};
inline constexpr Term detector_prnu{"detector.prnu", "1", "photo-response non-uniformity s_g (EMVA 1288 §2.4), a fraction"};
inline constexpr Term detector_dsnu{"detector.dsnu", "electron", "dark-signal non-uniformity σ_o of one native pixel (EMVA 1288 §2.4)"};
// The noise variance that does not scale with the target's signal, source by source (n² = S + PRNU² + Σ of these,
// over the photometric aperture and M frames): what a grid factors by (radchain/batch/factored_grid.hpp), and what
// tells a reader which noise limits the result.
inline constexpr Term detector_floor_variance_sky{"detector.floor_variance_sky", "electron2",
                                                  "the sky background's share of the noise variance (Poisson: its electrons)"};
inline constexpr Term detector_floor_variance_dark{"detector.floor_variance_dark", "electron2",
                                                   "the dark current's share of the noise variance (Poisson: its electrons)"};
inline constexpr Term detector_floor_variance_read{"detector.floor_variance_read", "electron2",
                                                   "read, quantisation and other temporal noise's share of the noise variance"};
inline constexpr Term detector_floor_variance_fixed_pattern{"detector.floor_variance_fixed_pattern", "electron2",
                                                            "dark-signal non-uniformity's share of the noise variance"};
// Every floor term, in the order a factored grid reads them.
inline constexpr std::array floor_variances{detector_floor_variance_sky, detector_floor_variance_dark,
                                            detector_floor_variance_read, detector_floor_variance_fixed_pattern};
// How a point image is counted, for validate: PSF-weighted (the whole image over n_eff pixels) or an aperture
inline constexpr Term detector_psf_weighted{"detector.psf_weighted", "1",
                                            "1: PSF-weighted photometry (all of the image over n_eff pixels); 0: a window or circle"};

// Every term, for look-ups by name (describe, the check that a plugin does not declare a term as a plain string).
inline constexpr std::array all{
    platform_altitude, platform_ground_speed, platform_tilt, source_visual_magnitude, source_illuminance,
    source_distance, source_solar_declination, source_solar_zenith, source_band_irradiance, atmosphere_ground_irradiance, target_illuminance,
    target_reflectance_difference, target_background_exitance, optics_aperture, optics_obscuration,
    optics_collecting_area, optics_transmittance, optics_focal_length, optics_f_number, optics_psf_wavelength,
    optics_gaussian_fwhm, detector_snr, detector_integration_time, detector_signal_electrons, detector_image_electrons,
    detector_noise_electrons, detector_sky_electrons_per_pixel, detector_window_pixel_count, detector_ensquared_energy,
    detector_aperture_radius_pixels,
    detector_signal_irradiance, detector_nee_working, detector_utilisation_ratio, detector_element_size_for_mtf,
    detector_nu_half_contrast, detector_system_element, detector_line_length, criterion_margin, criterion_threshold,
    criterion_required_quality, criterion_wavelength, criterion_ground_element,
    // What render and validate read
    detector_adc_bits, detector_dark_rate, detector_read_noise_per_pixel, detector_band_min, detector_band_max,
    detector_saturation_exposure, target_background_reflectance,
    // Earth-observation geometry
    platform_roll, platform_pitch, platform_slant_range, platform_view_zenith_angle, platform_earth_radius,
    detector_pixel_pitch, criterion_gsd_nadir, criterion_gsd_across_track, criterion_gsd_along_track,
    criterion_niirs, criterion_rer,
    // Radiometry of Earth-observation cameras
    target_reflectance, detector_scene_radiance, detector_reference_radiance, detector_reference_signal_electrons,
    detector_snr_at_reference, detector_noise_equivalent_radiance, detector_noise_equivalent_reflectance,
    detector_saturation_radiance, detector_path_radiance_electrons, detector_binning, detector_exposures,
    detector_prnu, detector_dsnu, detector_psf_weighted,
    // Datasheet detectors and telescopes
    detector_peak_pixel_fill, detector_saturation_capacity, detector_peak_pixel_electrons,
    detector_noise_equivalent_area, detector_system_gain, detector_tdi_stages, target_zero_point_photon_rate,
    target_band_magnitude, atmosphere_airmass, atmosphere_seeing_fwhm, atmosphere_sky_brightness,
    // Moving targets
    detector_target_streak_pixels, detector_star_streak_pixels, detector_trailing_loss, detector_psf_fwhm,
    // The noise floor, source by source
    detector_floor_variance_sky, detector_floor_variance_dark, detector_floor_variance_read,
    detector_floor_variance_fixed_pattern,
};

// The term a qualified result name is, if any.
constexpr const Term* term_of(std::string_view qualified) {
  for (const Term& t : all)
    if (t.matches(qualified)) return &t;
  return nullptr;
}

}  // namespace vocabulary
}  // namespace radchain
