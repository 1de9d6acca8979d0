#pragma once
// Viewing geometry of an Earth-observation camera over a spherical Earth: pixel-pitch ground sample distance,
// slant range, view zenith angle, across- and along-track GSD and swath at a look angle (roll, pitch), line
// time. SI units (m, rad, s). Earth radius and GM: physics/pushbroom.hpp (R = 6371.0 km mean, WGS 84 GM).
// Sources:
//   Closed-form spherical trigonometry of a ray from a satellite at R + h to a sphere of radius R: the law of
//   sines in the triangle Earth centre – satellite – ground point, sin η = (R + h)/R · sin θ, and the slant range
//   ρ = (R + h) cos θ − √(R² − (R + h)² sin² θ); J. R. Wertz & W. J. Larson (eds.), Space Mission Analysis and
//   Design, 3rd ed. (1999), §5.2 "Earth geometry viewed from space", eqs. (5-17)-(5-27) (η is their ε's
//   complement: the view zenith angle at the ground; their "nadir angle" is θ here).
//   Pixel footprint in the plane of the look: R dλ/dθ = ρ / cos η (differentiate the triangle; SMAD §5.2, and
//   R. A. Schowengerdt, Remote Sensing, 3rd ed. (2007), §3.3 for the flat-Earth limit h/cos²θ).
//   Nadir ground sample distance GSD = h · p / f' (pixel pitch p, focal length f'): Schowengerdt §3.3 (GIFOV).

#include <stdexcept>

namespace radchain::physics {

// Thrown when a line of sight misses the Earth (look angle past the horizon).
struct LookPastHorizon : std::domain_error {
  using std::domain_error::domain_error;
};

// Nadir GSD of a pixel: h p / f' (instantaneous field of view p/f' times the altitude).
double pixel_pitch_gsd_m(double altitude_m, double pixel_pitch_m, double focal_length_m);

// Off-nadir angle θ of a line of sight rotated by roll φ about the along-track axis and pitch ψ: the look
// direction (sin ψ, cos ψ sin φ, cos ψ cos φ) in (along, across, nadir) axes, so cos θ = cos φ cos ψ.
double off_nadir_angle_rad(double roll_rad, double pitch_rad);
// Largest off-nadir angle that still meets the Earth: sin θ_h = R/(R + h).
double horizon_off_nadir_angle_rad(double altitude_m, double earth_radius_m);
// Slant range ρ to the ground along a line of sight θ off nadir (throws LookPastHorizon beyond θ_h).
double slant_range_m(double altitude_m, double off_nadir_rad, double earth_radius_m);
// View zenith angle η at the ground: sin η = (R + h) sin θ / R.
double view_zenith_angle_rad(double altitude_m, double off_nadir_rad, double earth_radius_m);
// Earth central angle λ = η − θ between the sub-satellite point and the ground point.
double earth_central_angle_rad(double altitude_m, double off_nadir_rad, double earth_radius_m);

// Ground sample distance of an angular sample Δθ (= p/f') at off-nadir angle θ, closed form (small Δθ):
//   in the plane of the look:       ρ Δθ / cos η        (flat-Earth limit h Δθ / cos² θ)
//   perpendicular to that plane:    ρ Δθ                (flat-Earth limit h Δθ / cos θ)
double gsd_in_look_plane_m(double altitude_m, double off_nadir_rad, double angular_sample_rad, double earth_radius_m);
double gsd_across_look_plane_m(double altitude_m, double off_nadir_rad, double angular_sample_rad,
                               double earth_radius_m);

// Great-circle distance on the sphere between the ground points of two boresights given by (roll, pitch), the
// look direction Rx(roll) Ry(pitch) ẑ: exact ray–sphere intersections (the quadratic above), then R · angle.
double ground_distance_between_looks_m(double altitude_m, double roll1_rad, double pitch1_rad, double roll2_rad,
                                       double pitch2_rad, double earth_radius_m);

// Across-track and along-track GSD of a pixel of angular size Δθ in a line camera turned by (roll φ, pitch ψ):
// the ground distance between the centres of neighbouring pixels along the line (camera-frame angles ± Δθ/2,
// direction Rx(φ) Ry(ψ) Rx(±Δθ/2) ẑ) and between neighbouring lines (pitch ψ ± Δθ/2). For a pure roll these
// equal the closed forms above (in-plane across, perpendicular along); for a pure pitch the other way round.
double gsd_across_track_m(double altitude_m, double roll_rad, double pitch_rad, double angular_sample_rad,
                          double earth_radius_m);
double gsd_along_track_m(double altitude_m, double roll_rad, double pitch_rad, double angular_sample_rad,
                         double earth_radius_m);
// Swath of a line of full angular width 2α (α = atan(l / 2f'), l the line length) in the camera turned by
// (roll, pitch): the ground distance between the edge pixels' ground points (camera-frame angles ± α).
// Throws LookPastHorizon if either edge misses the Earth.
double swath_m(double altitude_m, double roll_rad, double pitch_rad, double half_field_rad, double earth_radius_m);
// Half field angle of a line of length l behind focal length f': atan(l / 2f').
double half_field_angle_rad(double line_length_m, double focal_length_m);

// Line time of a pushbroom camera that samples the ground at `along_track_gsd` while its footprint moves at
// `ground_speed`: t = GSD / v (square samples; Schowengerdt §3.3, "dwell time").
double line_time_s(double along_track_gsd_m, double ground_speed_m_s);

}  // namespace radchain::physics
