#pragma once
// Design relations of a pushbroom (line-array) Earth-imaging camera: ground irradiance and object contrast,
// focal length, field of view, entrance pupil from the threshold exposure, along-track sampling, and the
// ground-track speed of a circular orbit. SI units throughout (m, s, W m^-2, J m^-2; 1 W/cm² = 1e4 W m^-2).
// Source: Kolobrodov 1996, "Design of the optical system of a satellite-borne CCD camera"
// (seed 000_b315c29ce1517a86), eqs. (1)-(5), (16)-(23) and the worked example; Earth constants as noted below.
// Geometry is that of the paper: a flat Earth under a nadir-looking (or tilted) camera.

namespace radchain::physics {

// ---- Earth and orbit --------------------------------------------------------------------------------------

// Geocentric gravitational constant including the atmosphere, GM = 3.986004418e14 m³ s⁻²: the WGS 84 value
// (NIMA TR8350.2, 3rd ed., 2000, Table 3.1; identical to the IERS Conventions 2010, Table 1.1, TT-compatible).
inline constexpr double earth_gm_m3_s2 = 3.986004418e14;
// Mean Earth radius 6371.0 km: the IUGG mean radius R1 = (2a + b)/3 of the WGS 84 / GRS 80 ellipsoid is
// 6371.0088 km (Moritz, Geodetic Reference System 1980, J. Geodesy 74 (2000) 128); rounded to 6371.0 km as in
// common use — the 8.8 m changes speeds by ~1e-6.
inline constexpr double earth_mean_radius_m = 6371.0e3;
// The paper's v_f = 7.9 km/s in eq. (23): the first cosmic velocity at the Earth's surface, √(GM/R) = 7.91 km/s,
// not the ground speed of an orbit at altitude.
inline constexpr double kolobrodov_first_cosmic_velocity_m_s = 7.9e3;

// Speed of a circular orbit at altitude h over a spherical Earth: √(GM/(R + h)).
double circular_orbit_speed_m_s(double altitude_m, double gm_m3_s2 = earth_gm_m3_s2,
                                double earth_radius_m = earth_mean_radius_m);
// Speed of the sub-satellite point over a non-rotating spherical Earth: √(GM/(R + h)) · R/(R + h).
// The Earth's rotation (≤ 465 m/s at the equator) adds or removes a part that depends on inclination and
// latitude; it is left out, as the paper leaves it out.
double ground_track_speed_m_s(double altitude_m, double gm_m3_s2 = earth_gm_m3_s2,
                              double earth_radius_m = earth_mean_radius_m);

// WGS 84 rotation rate of the Earth ω_E (rad s-1, NIMA TR8350.2).
inline constexpr double earth_rotation_rate_rad_s = 7.292115e-5;

// Speed of the sub-satellite point over the rotating Earth's surface, at latitude φ on a circular orbit of
// inclination i. On the inertial sphere the point moves at v₀ (above) along a great circle whose azimuth α
// obeys Clairaut's relation cos φ sin α = cos i; the surface moves east at ω R cos φ. The difference:
//   v² = v₀² − 2 v₀ ω R cos i + (ω R cos φ)²
// (prograde orbits gain less than ω R over the ground, retrograde sun-synchronous ones more). Throws
// std::invalid_argument when the ground track never reaches φ (cos φ < |cos i|).
double rotating_earth_ground_speed_m_s(double inertial_ground_speed_m_s, double inclination_rad, double latitude_rad,
                                       double earth_radius_m = earth_mean_radius_m,
                                       double rotation_rate_rad_s = earth_rotation_rate_rad_s);

// ---- Scene: Sun, atmosphere, ground contrast --------------------------------------------------------------

// Solar irradiance in the band λ1..λ2 (Kolobrodov, after Pavlov 1974): E's = E_s [z(λ2) − z(λ1)], z the fraction
// of the Sun's irradiance below λ.
double band_solar_irradiance_W_m2(double total_solar_irradiance_W_m2, double fraction_below_lo,
                                  double fraction_below_hi);
// Ground irradiance in the band: E_0 = E's τ_A (τ_A the band-integral atmospheric transmittance).
double ground_irradiance_W_m2(double band_solar_irradiance_W_m2, double atmospheric_transmittance);
// Eq. (1): relative reflectance difference Δρ = (ρ_t − ρ_b)/ρ_b. Note that eq. (4) and the worked example use
// the absolute difference ρ_t − ρ_b (1 % of albedo 0.3 → Δρ = 3e-3), not this ratio.
double relative_reflectance_difference(double target_reflectance, double background_reflectance);
// Eqs. (2)-(4): Lambertian exitance M = E_0 ρ and the threshold exitance ΔM_n = E_0 Δρ (Δρ absolute).
double lambertian_exitance_W_m2(double ground_irradiance_W_m2, double reflectance);
double threshold_exitance_W_m2(double ground_irradiance_W_m2, double absolute_reflectance_difference);

// ---- Focal plane ------------------------------------------------------------------------------------------

// Eq. (5)/(21): image irradiance of a Lambertian scene of exitance M, E' = ¼ (D/f')² τ_A τ_0 M.
double image_irradiance_W_m2(double aperture_m, double focal_length_m, double atmospheric_transmittance,
                             double optics_transmittance, double exitance_W_m2);
// (H_nr = H_nt k_i / k_c, the noise-equivalent exposure for the real source: physics/band.hpp,
// exposure_for_working_source.)
// Integration time of a line read out element by element: t_i = N / f_D (= N t_0, t_0 = 1/f_D).
double line_integration_time_s(double element_count, double readout_clock_Hz);
// Eq. (20): threshold image irradiance E_n = H_n / t_i.
double threshold_image_irradiance_W_m2(double noise_equivalent_exposure_J_m2, double integration_time_s);
// Eq. (22): D_0 = f' √(4 E_n / (τ_A τ_0 ΔM_n)), the pupil at which eq. (21) gives E' = E_n for ΔM_n.
double entrance_pupil_diameter_m(double focal_length_m, double threshold_image_irradiance_W_m2,
                                 double atmospheric_transmittance, double optics_transmittance,
                                 double threshold_exitance_W_m2);

// ---- Geometry -------------------------------------------------------------------------------------------

// Eq. (16): f' = V_s h / δV for a system resolution element V_s (image plane) and a ground element δV.
double focal_length_for_ground_element_m(double system_element_m, double altitude_m, double ground_element_m);
// Length of the line array as the paper counts it: l_D = N × pitch. The paper writes V_D·N (element size ×
// count), which is the same only because the CCD151's element equals its pitch (7 µm); with gaps between
// elements the sampled field is N × pitch (and the outer-edge length (N − 1) × pitch + V_D).
double detector_line_length_m(double pixel_pitch_m, double element_count);
// Eq. (17): full angular field 2ω = 2 atan(l / (2 f')) for an image-plane extent l (l_D along the line, V_s across).
double full_angular_field_rad(double image_extent_m, double focal_length_m);
// Eq. (18) (and (16) turned round): ground extent l h / f' of an image-plane extent l at nadir: the swath
// V = l_D h/f' and the element W = V_s h/f'.
double ground_extent_m(double image_extent_m, double altitude_m, double focal_length_m);
// Eq. (19): ground element at off-nadir angle ω (field angle or tilted line of sight), flat Earth: the range
// grows as h/cos ω, and in the plane of ω the footprint is foreshortened by a further 1/cos ω.
//   in the plane of ω (the paper's δV, across track for a field angle): V_s h / (f' cos² ω)
//   perpendicular to it (the paper's δW):                              V_s h / (f' cos ω)
double off_nadir_element_in_plane_m(double system_element_m, double altitude_m, double focal_length_m,
                                    double off_nadir_rad);
double off_nadir_element_cross_plane_m(double system_element_m, double altitude_m, double focal_length_m,
                                       double off_nadir_rad);
// Eq. (23): along-track shift of the line's footprint in one line period, δy = v t_p.
double along_track_sample_m(double ground_speed_m_s, double line_period_s);
// Eq. (23) turned round: the line period that gives a wanted along-track sample, t_p = δy / v.
double line_period_for_along_track_sample_s(double along_track_sample_m, double ground_speed_m_s);

}  // namespace radchain::physics
