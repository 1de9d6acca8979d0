#include "radchain/physics/pushbroom.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace radchain::physics {

// ---- Earth and orbit --------------------------------------------------------------------------------------

double circular_orbit_speed_m_s(double altitude_m, double gm_m3_s2, double earth_radius_m) {
  // Circular orbit: v² / r = GM / r².
  return std::sqrt(gm_m3_s2 / (earth_radius_m + altitude_m));
}

double ground_track_speed_m_s(double altitude_m, double gm_m3_s2, double earth_radius_m) {
  // The sub-satellite point moves with the same angular rate v/(R + h) on a sphere of radius R.
  return circular_orbit_speed_m_s(altitude_m, gm_m3_s2, earth_radius_m) * earth_radius_m /
         (earth_radius_m + altitude_m);
}

double rotating_earth_ground_speed_m_s(double v0, double inclination_rad, double latitude_rad, double earth_radius_m,
                                       double rotation_rate_rad_s) {
  const double cos_lat = std::cos(latitude_rad), cos_i = std::cos(inclination_rad);
  if (cos_lat < std::abs(cos_i) * (1 - 1e-12))
    throw std::invalid_argument("the ground track of an orbit inclined " + std::to_string(inclination_rad * 180 / std::numbers::pi) +
                                " deg never reaches latitude " + std::to_string(latitude_rad * 180 / std::numbers::pi) + " deg");
  const double u = rotation_rate_rad_s * earth_radius_m;
  return std::sqrt(v0 * v0 - 2 * v0 * u * cos_i + u * u * cos_lat * cos_lat);
}

// ---- Scene ------------------------------------------------------------------------------------------------

double band_solar_irradiance_W_m2(double total_solar_irradiance_W_m2, double fraction_below_lo,
                                  double fraction_below_hi) {
  // Kolobrodov 1996 (after Pavlov 1974): E's = E_s [z(λ2) − z(λ1)].
  return total_solar_irradiance_W_m2 * (fraction_below_hi - fraction_below_lo);
}

double ground_irradiance_W_m2(double band_solar_irradiance_W_m2, double atmospheric_transmittance) {
  // Kolobrodov 1996: E_0 = E's τ_A.
  return band_solar_irradiance_W_m2 * atmospheric_transmittance;
}

double relative_reflectance_difference(double target_reflectance, double background_reflectance) {
  // Eq. (1).
  return (target_reflectance - background_reflectance) / background_reflectance;
}

double lambertian_exitance_W_m2(double ground_irradiance_W_m2, double reflectance) {
  // Eq. (2): M = E_0 ρ.
  return ground_irradiance_W_m2 * reflectance;
}

double threshold_exitance_W_m2(double ground_irradiance_W_m2, double absolute_reflectance_difference) {
  // Eq. (4): ΔM_n = E_0 Δρ.
  return ground_irradiance_W_m2 * absolute_reflectance_difference;
}

// ---- Focal plane ------------------------------------------------------------------------------------------

double image_irradiance_W_m2(double aperture_m, double focal_length_m, double atmospheric_transmittance,
                             double optics_transmittance, double exitance_W_m2) {
  // Eq. (5): E' = ¼ (D_0/f')² τ_A τ_0 M.
  const double relative_aperture = aperture_m / focal_length_m;
  return 0.25 * relative_aperture * relative_aperture * atmospheric_transmittance * optics_transmittance *
         exitance_W_m2;
}


double line_integration_time_s(double element_count, double readout_clock_Hz) {
  // Kolobrodov 1996: t_i = t_0 N, t_0 = 1/f_D.
  return element_count / readout_clock_Hz;
}

double threshold_image_irradiance_W_m2(double noise_equivalent_exposure_J_m2, double integration_time_s) {
  // Eq. (20): E_n = H_n / t_i.
  return noise_equivalent_exposure_J_m2 / integration_time_s;
}

double entrance_pupil_diameter_m(double focal_length_m, double threshold_image_irradiance_W_m2,
                                 double atmospheric_transmittance, double optics_transmittance,
                                 double threshold_exitance_W_m2) {
  // Eq. (22): D_0 = f' √(4 E_n / (τ_A τ_0 ΔM_n)).
  return focal_length_m * std::sqrt(4.0 * threshold_image_irradiance_W_m2 /
                                    (atmospheric_transmittance * optics_transmittance * threshold_exitance_W_m2));
}

// ---- Geometry ---------------------------------------------------------------------------------------------

double focal_length_for_ground_element_m(double system_element_m, double altitude_m, double ground_element_m) {
  // Eq. (16): f' = V_s h / δV.
  return system_element_m * altitude_m / ground_element_m;
}

double detector_line_length_m(double pixel_pitch_m, double element_count) {
  // Kolobrodov 1996: l_D = V_D N (= pitch × N for the CCD151, whose element equals its pitch).
  return pixel_pitch_m * element_count;
}

double full_angular_field_rad(double image_extent_m, double focal_length_m) {
  // Eq. (17): 2ω = 2 arctg(l / (2 f')).
  return 2.0 * std::atan(image_extent_m / (2.0 * focal_length_m));
}

double ground_extent_m(double image_extent_m, double altitude_m, double focal_length_m) {
  // Eq. (18): V = l_D h / f', W = V_s h / f'.
  return image_extent_m * altitude_m / focal_length_m;
}

double off_nadir_element_in_plane_m(double system_element_m, double altitude_m, double focal_length_m,
                                    double off_nadir_rad) {
  // Eq. (19): δV = V_s h / (f' cos² ω).
  const double c = std::cos(off_nadir_rad);
  return system_element_m * altitude_m / (focal_length_m * c * c);
}

double off_nadir_element_cross_plane_m(double system_element_m, double altitude_m, double focal_length_m,
                                       double off_nadir_rad) {
  // Eq. (19): δW = V_s h / (f' cos ω).
  return system_element_m * altitude_m / (focal_length_m * std::cos(off_nadir_rad));
}

double along_track_sample_m(double ground_speed_m_s, double line_period_s) {
  // Eq. (23): δy = v_f t_p.
  return ground_speed_m_s * line_period_s;
}

double line_period_for_along_track_sample_s(double along_track_sample_m, double ground_speed_m_s) {
  // Eq. (23) solved for t_p.
  return along_track_sample_m / ground_speed_m_s;
}

}  // namespace radchain::physics
