// Pushbroom design relations (radchain/physics/pushbroom.hpp) and Kolobrodov 1996's worked example, every
// printed number checked against the paper's own formulas and inputs. Where a printed number does not follow,
// the test asserts the value that does and says in a comment what was printed (docs/errata-kolobrodov-1996.md).
#include "radchain/physics/band.hpp"
#include "radchain/physics/pushbroom.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "radchain/physics/mtf.hpp"

namespace {

using namespace radchain::physics;
constexpr double pi = std::numbers::pi;
constexpr double um = 1e-6, mm = 1e-3, km = 1e3;
constexpr double W_cm2 = 1e4;  // W/cm² in W/m²
constexpr double J_cm2 = 1e4;  // J/cm² in J/m²
constexpr double deg = pi / 180;

// A printed value holds "at the paper's rounding": within half a unit of its last printed digit.
#define EXPECT_PRINTED(computed, printed, half_unit) EXPECT_NEAR(computed, printed, half_unit)

// ---- Inputs of the worked example (Kolobrodov 1996, "Пример проектирования объектива") -----------------------
constexpr double ground_element_m = 5.0;              // δV = 5 m
constexpr double altitude_m = 400 * km;               // h = 400 km
constexpr double albedo = 0.3;                        // ρ_0 = 0.3
constexpr double reflectance_difference = 3e-3;       // Δρ = 1 % of 0.3, absolute
constexpr double element_m = 7 * um;                  // V_D = W_D = 7 µm, pitch 7 µm
constexpr double element_count = 5000;                // N
constexpr double clock_Hz = 5e6;                      // f_D (typical)
constexpr double reference_exposure_J_m2 = 0.0002e-6 * J_cm2;  // H_nt = 0.0002 µJ/cm² (2854 K lamp)
constexpr double k_i = 0.187, k_c = 0.852;           // utilisation coefficients
constexpr double solar_total_W_m2 = 0.14 * W_cm2;    // E_s
constexpr double z_lo = 0.236, z_hi = 0.58;           // z(0.5 µm), z(0.76 µm)
constexpr double tau_atm = 0.5, tau_optics = 0.8;     // τ_A, τ_0

// ---- Orbit ----------------------------------------------------------------------------------------------

TEST(PushbroomOrbit, CircularOrbitAt400km) {
  // √(3.986004418e14 / 6.771e6) = 7672.60 m/s; sub-satellite point × 6371/6771 = 7219.34 m/s.
  EXPECT_NEAR(circular_orbit_speed_m_s(altitude_m), 7672.599, 1e-3);
  EXPECT_NEAR(ground_track_speed_m_s(altitude_m), 7219.336, 1e-3);
  // Kepler's third law: the period 2π √(a³/GM) = 5544.8 s (92.41 min) equals 2π a / v.
  const double a = earth_mean_radius_m + altitude_m;
  const double period_s = 2 * pi * std::sqrt(a * a * a / earth_gm_m3_s2);
  EXPECT_NEAR(2 * pi * a / circular_orbit_speed_m_s(altitude_m), period_s, 1e-9);
  EXPECT_NEAR(period_s / 60, 92.41, 0.01);
  // The ground track covers 2π R in one period.
  EXPECT_NEAR(ground_track_speed_m_s(altitude_m) * period_s, 2 * pi * earth_mean_radius_m, 1e-3);
}

TEST(PushbroomOrbit, PaperVelocityIsFirstCosmicVelocityAtSurface) {
  // v_f = 7.9 km/s of eq. (23) is √(GM/R) = 7909.8 m/s, the orbit speed at h = 0.
  EXPECT_NEAR(circular_orbit_speed_m_s(0.0), 7909.8, 0.05);
  EXPECT_PRINTED(circular_orbit_speed_m_s(0.0) / km, kolobrodov_first_cosmic_velocity_m_s / km, 0.05);
}

// ---- Geometry ----------------------------------------------------------------------------------------------

TEST(PushbroomGeometry, FieldAndFootprint) {
  EXPECT_NEAR(focal_length_for_ground_element_m(10 * um, 500 * km, 5.0), 1.0, 1e-15);
  EXPECT_NEAR(detector_line_length_m(7 * um, 5000), 35 * mm, 1e-15);
  EXPECT_NEAR(full_angular_field_rad(2.0, 1.0), pi / 2, 1e-15);  // 2 atan(1)
  EXPECT_NEAR(ground_extent_m(35 * mm, 400 * km, 0.8), 17.5 * km, 1e-9);
  // Eq. (19): at nadir both equal the nadir element; at 60° the in-plane element is 4×, the other 2×.
  const double nadir = ground_extent_m(10 * um, 400 * km, 0.8);
  EXPECT_NEAR(off_nadir_element_in_plane_m(10 * um, 400 * km, 0.8, 0.0), nadir, 1e-15);
  EXPECT_NEAR(off_nadir_element_cross_plane_m(10 * um, 400 * km, 0.8, 0.0), nadir, 1e-15);
  EXPECT_NEAR(off_nadir_element_in_plane_m(10 * um, 400 * km, 0.8, 60 * deg), 4 * nadir, 1e-12);
  EXPECT_NEAR(off_nadir_element_cross_plane_m(10 * um, 400 * km, 0.8, 60 * deg), 2 * nadir, 1e-12);
  // Independent flat-Earth geometry: a ray at ω hits the ground at x = h tan ω; the in-plane footprint of an
  // angular element dω is h d(tan ω) = h dω / cos² ω.
  const double omega = 20 * deg, d_omega = 10 * um / 0.8;
  EXPECT_NEAR(altitude_m * (std::tan(omega + d_omega / 2) - std::tan(omega - d_omega / 2)),
              off_nadir_element_in_plane_m(10 * um, altitude_m, 0.8, omega), 1e-6);
}

TEST(PushbroomRadiometry, PupilInvertsImageIrradiance) {
  // Eq. (22) is eq. (21) solved for D_0: the image irradiance at that pupil is E_n.
  const double f = 0.9, en = 3e-4, dm = 0.7;
  const double d0 = entrance_pupil_diameter_m(f, en, 0.6, 0.75, dm);
  EXPECT_NEAR(image_irradiance_W_m2(d0, f, 0.6, 0.75, dm), en, 1e-18);
  EXPECT_NEAR(image_irradiance_W_m2(0.1, 0.4, 1.0, 1.0, 16.0), 0.25, 1e-15);  // ¼ (1/4)² 16
  EXPECT_NEAR(relative_reflectance_difference(0.303, 0.3), 0.01, 1e-12);
  EXPECT_NEAR(lambertian_exitance_W_m2(240, 0.3), 72, 1e-12);
  EXPECT_NEAR(line_integration_time_s(5000, 5e6), 1e-3, 1e-18);
  EXPECT_NEAR(along_track_sample_m(7000, 1e-3), 7.0, 1e-12);
  EXPECT_NEAR(line_period_for_along_track_sample_s(7.0, 7000), 1e-3, 1e-18);
}

// ---- Kolobrodov 1996 worked example ----------------------------------------------------------------------

TEST(KolobrodovWorkedExample, ResolutionAt05) {
  // Step 1, eq. (11): ν_x1 = 0.6 / 7e-3 mm = 86 mm^-1 (printed). 85.71 mm^-1 → 86. Follows.
  EXPECT_PRINTED(kolobrodov_sinc_half_root_printed / element_m * mm, 86, 0.5);
  // Eq. (15): V_s = 1.49 V_D (printed). 1.4877 (u = 0.6) and 1.4922 (exact u) → 1.49. Follows.
  EXPECT_PRINTED(kolobrodov_system_element_ratio(kolobrodov_sinc_half_root_printed), 1.49, 0.005);
  EXPECT_PRINTED(kolobrodov_system_element_ratio(sinc_half_contrast_root()), 1.49, 0.005);
}

TEST(KolobrodovWorkedExample, FocalLength) {
  // Step 2, eq. (16): "f' = 1.49 · 7·10⁻³ · 400·10³ / 5 = 832 mm" (printed). The product as written is
  // 834.4 mm; 832 mm = 10.4 µm × 80 000 follows from V_s rounded to 10.4 µm first (−2.4 mm, −0.29 %).
  const double f_printed_ratio = focal_length_for_ground_element_m(1.49 * element_m, altitude_m, ground_element_m);
  EXPECT_NEAR(f_printed_ratio / mm, 834.4, 1e-9);
  EXPECT_NEAR(focal_length_for_ground_element_m(10.4 * um, altitude_m, ground_element_m) / mm, 832.0, 1e-9);
  // With the unrounded roots of eq. (15): 833.1 mm (u = 0.6) and 835.6 mm (exact u).
  EXPECT_NEAR(focal_length_for_ground_element_m(kolobrodov_system_element_ratio(0.6) * element_m, altitude_m,
                                                ground_element_m) / mm, 833.12, 0.01);
  EXPECT_NEAR(focal_length_for_ground_element_m(kolobrodov_system_element_ratio(sinc_half_contrast_root()) *
                                                    element_m, altitude_m, ground_element_m) / mm, 835.65, 0.01);
}

TEST(KolobrodovWorkedExample, FieldOfView) {
  const double line_m = detector_line_length_m(element_m, element_count);
  EXPECT_NEAR(line_m / mm, 35.0, 1e-12);  // l_D = 7·10⁻³ · 5000 = 35 mm (printed)
  // Step 3, eq. (17): 2ω = 2 arctg(35/(2·832)) = 2.4° (printed). 2.410° with 832 mm, 2.403° with 834.4 mm. Follows.
  EXPECT_PRINTED(full_angular_field_rad(line_m, 832 * mm) / deg, 2.4, 0.05);
  EXPECT_PRINTED(full_angular_field_rad(line_m, 834.4 * mm) / deg, 2.4, 0.05);
  EXPECT_NEAR(full_angular_field_rad(line_m, 832 * mm) / deg, 2.4099, 1e-4);
  // Eq. (18): V = 35/832 · 400 = 16.8 km (printed): 16.83 km; with 834.4 mm 16.78 km. Follows.
  EXPECT_PRINTED(ground_extent_m(line_m, altitude_m, 832 * mm) / km, 16.8, 0.05);
  EXPECT_PRINTED(ground_extent_m(line_m, altitude_m, 834.4 * mm) / km, 16.8, 0.05);
  // W = 10.4/832 · 400 = 5 m (printed); equals δV by construction of eq. (16). Follows.
  EXPECT_PRINTED(ground_extent_m(10.4 * um, altitude_m, 832 * mm), 5.0, 0.05);
  EXPECT_NEAR(ground_extent_m(1.49 * element_m, altitude_m, 834.4 * mm), 5.0, 1e-12);
  // Eq. (19) at the edge of the field (ω = 1.205°): 5.0022 m and 5.0011 m, 0.04 % and 0.02 % growth.
  const double omega = full_angular_field_rad(line_m, 832 * mm) / 2;
  EXPECT_NEAR(off_nadir_element_in_plane_m(10.4 * um, altitude_m, 832 * mm, omega), 5.0022, 1e-4);
  EXPECT_NEAR(off_nadir_element_cross_plane_m(10.4 * um, altitude_m, 832 * mm, omega), 5.0011, 1e-4);
}

TEST(KolobrodovWorkedExample, SceneRadiometry) {
  // E's = 0.14 (0.58 − 0.236) = 4.8·10⁻² W/cm² (printed): 4.816e-2. Follows.
  const double band = band_solar_irradiance_W_m2(solar_total_W_m2, z_lo, z_hi);
  EXPECT_NEAR(band / W_cm2, 0.04816, 1e-12);
  EXPECT_PRINTED(band / W_cm2, 4.8e-2, 0.05e-2);
  // E_0 = 4.8·10⁻² · 0.5 = 2.4·10⁻² W/cm² (printed): 2.408e-2. Follows.
  const double e0 = ground_irradiance_W_m2(band, tau_atm);
  EXPECT_PRINTED(e0 / W_cm2, 2.4e-2, 0.05e-2);
  // ΔM_n = 3·10⁻³ · 2.4·10⁻² = 7.2·10⁻⁵ W/cm² (printed): 7.224e-5 unrounded. Follows.
  const double dm = threshold_exitance_W_m2(e0, reflectance_difference);
  EXPECT_NEAR(dm / W_cm2, 7.224e-5, 1e-12);
  EXPECT_PRINTED(dm / W_cm2, 7.2e-5, 0.05e-5);
  EXPECT_NEAR(threshold_exitance_W_m2(2.4e-2, 3e-3), 7.2e-5, 1e-18);
  // The example's Δρ = 3·10⁻³ is the absolute difference 1 % × 0.3 (eq. 4), not eq. (1)'s relative one.
  EXPECT_NEAR(reflectance_difference, relative_reflectance_difference(albedo * 1.01, albedo) * albedo, 1e-15);
}

TEST(KolobrodovWorkedExample, ThresholdIrradiance) {
  // t_i = N / f_D = 5000 / 5 MHz = 10⁻³ s (printed). Follows.
  const double ti = line_integration_time_s(element_count, clock_Hz);
  EXPECT_NEAR(ti, 1e-3, 1e-18);
  // k_i/k_c = 0.187/0.852 = 0.2195 → "0.22" (printed). Follows.
  EXPECT_PRINTED(k_i / k_c, 0.22, 0.005);
  // H_nr = 2·10⁻¹⁰ J/cm² × 0.2195 = 4.39·10⁻¹¹ → 4.4·10⁻¹¹ J/cm² (printed). Follows.
  const double hnr = exposure_for_working_source(reference_exposure_J_m2, k_i, k_c);
  EXPECT_NEAR(hnr / J_cm2, 4.38967e-11, 1e-16);
  EXPECT_PRINTED(hnr / J_cm2, 4.4e-11, 0.05e-11);
  // Eq. (20): E_n = 4.39·10⁻⁸ → 4.4·10⁻⁸ W/cm² (printed). Follows.
  const double en = threshold_image_irradiance_W_m2(hnr, ti);
  EXPECT_PRINTED(en / W_cm2, 4.4e-8, 0.05e-8);
}

TEST(KolobrodovWorkedExample, EntrancePupil) {
  // Step 4, eq. (22): D_0 = 206 mm (printed). DOES NOT FOLLOW. From the paper's printed inputs,
  // 832 mm × √(4 · 4.4e-8 / (0.5 · 0.8 · 7.2e-5)) = 832 mm × 0.07817 = 65.0 mm; from the unrounded chain
  // (f' = 834.4 mm, E_n = 4.390e-8, ΔM_n = 7.224e-5 W/cm²) also 65.0 mm. Printed 206 mm is 3.17× (√10.03×)
  // larger: the radicand is a factor 10 too large, e.g. ΔM_n = 7.2e-6 W/cm² gives 205.7 mm. See the errata.
  const double from_printed = entrance_pupil_diameter_m(832 * mm, 4.4e-8 * W_cm2, tau_atm, tau_optics, 7.2e-5 * W_cm2);
  EXPECT_NEAR(from_printed / mm, 65.04, 0.005);
  const double band = band_solar_irradiance_W_m2(solar_total_W_m2, z_lo, z_hi);
  const double dm = threshold_exitance_W_m2(ground_irradiance_W_m2(band, tau_atm), reflectance_difference);
  const double en = threshold_image_irradiance_W_m2(exposure_for_working_source(reference_exposure_J_m2, k_i, k_c),
                                                    line_integration_time_s(element_count, clock_Hz));
  const double f = focal_length_for_ground_element_m(1.49 * element_m, altitude_m, ground_element_m);
  EXPECT_NEAR(entrance_pupil_diameter_m(f, en, tau_atm, tau_optics, dm) / mm, 65.04, 0.005);
  EXPECT_NEAR(entrance_pupil_diameter_m(832 * mm, en, tau_atm, tau_optics, dm) / mm, 64.86, 0.005);
  // The printed value misses by a factor of 3.17 (ratio of radicands 10.03).
  EXPECT_NEAR(206 * mm / from_printed, 3.167, 0.001);
  EXPECT_NEAR((206 * mm / from_printed) * (206 * mm / from_printed), 10.03, 0.01);
}

// ---- What would reproduce the printed numbers, and the questions the paper leaves open ----------------------

TEST(KolobrodovErrata, InputsThatReproduceThePrintedPupil) {
  // Any one factor of 10 in the radicand of eq. (22) gives the printed 206 mm (to its rounding):
  // ΔM_n = 7.2e-6 W/cm² (Δρ = 3e-4, i.e. 0.1 % of 0.3):                       205.7 mm
  EXPECT_PRINTED(entrance_pupil_diameter_m(832 * mm, 4.4e-8 * W_cm2, 0.5, 0.8, 7.2e-6 * W_cm2) / mm, 206, 0.5);
  EXPECT_PRINTED(entrance_pupil_diameter_m(832 * mm, 4.4e-8 * W_cm2, 0.5, 0.8,
                                           threshold_exitance_W_m2(2.4e-2 * W_cm2, 3e-4)) / mm, 206, 0.5);
  // E_n = 4.4e-7 W/cm² (t_i = 0.1 ms: N = 500 or f_D = 50 MHz, or H_nr = 4.4e-10 J/cm²): 205.7 mm
  EXPECT_PRINTED(entrance_pupil_diameter_m(832 * mm, threshold_image_irradiance_W_m2(4.4e-11 * J_cm2, 1e-4), 0.5, 0.8,
                                           7.2e-5 * W_cm2) / mm, 206, 0.5);
  // τ_A = 0.05 (τ_A τ_0 = 0.04):                                               205.7 mm
  EXPECT_PRINTED(entrance_pupil_diameter_m(832 * mm, 4.4e-8 * W_cm2, 0.05, 0.8, 7.2e-5 * W_cm2) / mm, 206, 0.5);
  // The exact ΔM_n (other inputs as printed) that gives 206 mm: 7.177e-6 W/cm²; the band 205.5..206.5 mm
  // needs 7.143e-6..7.212e-6, which contains 7.2e-6 and not 7.2e-5.
  const double needed_dm = 4 * 4.4e-8 / (0.5 * 0.8 * (206.0 / 832) * (206.0 / 832));
  EXPECT_NEAR(needed_dm, 7.177e-6, 1e-9);
}

TEST(KolobrodovErrata, FocalLengthFromRoundedElement) {
  // 832 mm follows from V_s = 10.4 µm (1.49 × 7 = 10.43 rounded); V_s/V_D = 10.4/7 = 1.4857.
  EXPECT_NEAR(focal_length_for_ground_element_m(10.4 * um, altitude_m, ground_element_m) / mm, 832.0, 1e-9);
  EXPECT_NEAR(focal_length_for_ground_element_m(1.49 * element_m, altitude_m, ground_element_m) / mm - 832.0, 2.4, 1e-9);
}

TEST(KolobrodovErrata, AtmosphericTransmittanceFromQuotedIlluminance) {
  // The paper: τ_A = E_0/E's with E_0 = 0.06..0.09 W/cm² in clear weather. Against the band's
  // E's = 0.048 W/cm² that is 1.25..1.87 (> 1, impossible); against the whole-spectrum E_s = 0.14 W/cm² it is
  // 0.43..0.64, the range the preliminary τ_A = 0.5 sits in. So 0.06..0.09 is a whole-spectrum value.
  const double band = band_solar_irradiance_W_m2(solar_total_W_m2, z_lo, z_hi);
  EXPECT_GT(0.06 * W_cm2 / band, 1.0);
  EXPECT_NEAR(0.06 * W_cm2 / band, 1.246, 1e-3);
  EXPECT_NEAR(0.09 * W_cm2 / band, 1.869, 1e-3);
  EXPECT_NEAR(0.06 / 0.14, 0.429, 1e-3);
  EXPECT_NEAR(0.09 / 0.14, 0.643, 1e-3);
}

TEST(KolobrodovErrata, AlongTrackSamplingAtOneMillisecond) {
  const double tp = line_integration_time_s(element_count, clock_Hz);  // line period = integration time, 1 ms
  // With the paper's v_f = 7.9 km/s: δy = 7.9 m, not δV = 5 m (58 % longer).
  EXPECT_NEAR(along_track_sample_m(kolobrodov_first_cosmic_velocity_m_s, tp), 7.9, 1e-12);
  // With the real ground-track speed of a 400 km circular orbit (7.219 km/s): δy = 7.22 m (44 % longer).
  const double v = ground_track_speed_m_s(altitude_m);
  EXPECT_NEAR(along_track_sample_m(v, tp), 7.219, 1e-3);
  // Line periods that give δy = 5 m: 0.633 ms at 7.9 km/s, 0.6926 ms at 7.219 km/s, i.e. readout clocks
  // N/t_p = 7.90 MHz and 7.22 MHz (inside the CCD151's 2..10 MHz).
  const double tp_paper = line_period_for_along_track_sample_s(ground_element_m, kolobrodov_first_cosmic_velocity_m_s);
  const double tp_real = line_period_for_along_track_sample_s(ground_element_m, v);
  EXPECT_NEAR(tp_paper * 1e3, 0.63291, 1e-5);
  EXPECT_NEAR(tp_real * 1e3, 0.69258, 1e-5);
  EXPECT_NEAR(element_count / tp_paper / 1e6, 7.9, 1e-12);
  EXPECT_NEAR(element_count / tp_real / 1e6, 7.2193, 1e-4);
  // The shorter integration time raises E_n by 1/0.6926 and the pupil by √ of that (×1.2016): 65.0 → 78.2 mm.
  const double en = threshold_image_irradiance_W_m2(exposure_for_working_source(reference_exposure_J_m2, k_i, k_c),
                                                    tp_real);
  const double band = band_solar_irradiance_W_m2(solar_total_W_m2, z_lo, z_hi);
  const double dm = threshold_exitance_W_m2(ground_irradiance_W_m2(band, tau_atm), reflectance_difference);
  EXPECT_NEAR(entrance_pupil_diameter_m(834.4 * mm, en, tau_atm, tau_optics, dm) / mm, 78.16, 0.01);
  // Across track the sampling pitch on the ground is 7 µm × h/f' = 3.37 m; matching that along track needs
  // t_p = 0.466 ms.
  const double gsd = ground_extent_m(element_m, altitude_m, 832 * mm);
  EXPECT_NEAR(gsd, 3.365, 1e-3);
  EXPECT_NEAR(line_period_for_along_track_sample_s(gsd, v) * 1e3, 0.4662, 1e-4);
}

TEST(KolobrodovErrata, ResolutionNotEnergyBindsThePupil) {
  // With the corrected D_0 = 65 mm (f'/D = 12.8) eq. (12) would need η > 1 over the whole band, which the
  // definition η ≤ 1 forbids: the objective cannot match the detector at 0.5. Matching needs
  // f'/D ≤ η V_D/(1.4616 λ): at λ2 = 0.76 µm, D_0 ≥ 132.0 mm for η = 1 (a diffraction-limited lens) and
  // ≥ 165.0 mm for the η = 0.8 of the paper's Fig. 2. The printed 206 mm (f/4.04) satisfies this (η = 0.64).
  const double coef = kolobrodov_eta_coefficient(kolobrodov_sinc_half_root_printed);
  const double n_energy = 832.0 / 65.04;
  EXPECT_GT(kolobrodov_eta(0.50 * um, n_energy, element_m, coef), 1.0);
  EXPECT_NEAR(kolobrodov_eta(0.76 * um, n_energy, element_m, coef), 2.03, 0.005);
  EXPECT_NEAR(832.0 / kolobrodov_max_f_number(0.76 * um, element_m, 1.0, coef), 132.03, 0.01);
  EXPECT_NEAR(832.0 / kolobrodov_max_f_number(0.76 * um, element_m, 0.8, coef), 165.04, 0.01);
  EXPECT_NEAR(kolobrodov_eta(0.76 * um, 832.0 / 206, element_m, coef), 0.641, 0.001);
  // Exact diffraction MTF at ν_x1 = 86.19 mm^-1 (exact root), λ = 0.76 µm: 0.076 at f/12.8, 0.667 at f/4.04.
  const double nu = detector_frequency_at_contrast_per_m(0.5, element_m);
  EXPECT_NEAR(diffraction_mtf(nu, 0.76 * um, n_energy), 0.0764, 0.0001);
  EXPECT_NEAR(diffraction_mtf(nu, 0.76 * um, 832.0 / 206), 0.6671, 0.0001);
}

}  // namespace
