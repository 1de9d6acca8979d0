// Spherical-Earth viewing geometry (see earth_geometry.hpp for the sources).
#include "radchain/physics/earth_geometry.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

namespace radchain::physics {

namespace {

using Vec = std::array<double, 3>;

double dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double norm(const Vec& a) { return std::sqrt(dot(a, a)); }

void require_positive(double value, const char* what) {
  if (!(value > 0)) throw std::invalid_argument(fmt::format("{} must be positive, got {}", what, value));
}

// Line of sight of a pixel at angle `across` from the centre of a line detector (camera frame: along the line,
// the rotation Rx(across) of the boresight) in a camera turned by pitch ψ about the across-track axis and then by
// roll φ about the along-track axis: d = Rx(φ) Ry(ψ) Rx(across) ẑ, in (along, across, nadir) axes
//   d = (cos a sin ψ,  sin a cos φ + cos a cos ψ sin φ,  −sin a sin φ + cos a cos ψ cos φ).
// At a = 0 this is (sin ψ, cos ψ sin φ, cos ψ cos φ); a neighbouring line (along track) is ψ ± b.
Vec look_direction(double roll, double pitch, double across) {
  const double ca = std::cos(across), sa = std::sin(across);
  return {ca * std::sin(pitch), sa * std::cos(roll) + ca * std::cos(pitch) * std::sin(roll),
          -sa * std::sin(roll) + ca * std::cos(pitch) * std::cos(roll)};
}

// Ground point of a line of sight d (nadir component d[2] > 0): Earth centre at the origin, satellite at
// (0, 0, R + h), the ray S + t (d0, d1, −d2) meets the sphere at the slant range of θ = acos d[2].
Vec ground_point(double altitude_m, const Vec& d, double earth_radius_m) {
  const double s = earth_radius_m + altitude_m;
  const double t = slant_range_m(altitude_m, std::acos(std::clamp(d[2], -1.0, 1.0)), earth_radius_m);
  return {t * d[0], t * d[1], s - t * d[2]};
}

double arc_between(const Vec& a, const Vec& b, double earth_radius_m) {
  // The angle between the two radius vectors by atan2(|a × b|, a · b): accurate for metre-scale separations.
  return earth_radius_m * std::atan2(norm(cross(a, b)), dot(a, b));
}

}  // namespace

double pixel_pitch_gsd_m(double altitude_m, double pixel_pitch_m, double focal_length_m) {
  require_positive(focal_length_m, "focal length");
  return altitude_m * pixel_pitch_m / focal_length_m;
}

double off_nadir_angle_rad(double roll_rad, double pitch_rad) {
  // cos θ = cos φ cos ψ, but acos of a cosine loses the angle near nadir (a roll of 2e-6 rad came out 4e-7
  // relative off, a view zenith 1e-12 rad off). The half-angle form is exact there: 1 − cos φ cos ψ = 2a + 2b − 4ab
  // with a = sin²(φ/2), b = sin²(ψ/2), so sin²(θ/2) = a + b − 2ab; θ stays below 90° on the Earth.
  const double a = std::pow(std::sin(roll_rad / 2), 2), b = std::pow(std::sin(pitch_rad / 2), 2);
  return 2 * std::asin(std::sqrt(std::clamp(a + b - 2 * a * b, 0.0, 1.0)));
}

double horizon_off_nadir_angle_rad(double altitude_m, double earth_radius_m) {
  require_positive(altitude_m, "altitude");
  return std::asin(earth_radius_m / (earth_radius_m + altitude_m));
}

double slant_range_m(double altitude_m, double off_nadir_rad, double earth_radius_m) {
  require_positive(altitude_m, "altitude");
  require_positive(earth_radius_m, "Earth radius");
  const double s = earth_radius_m + altitude_m;
  const double sin_t = std::sin(off_nadir_rad), cos_t = std::cos(off_nadir_rad);
  const double discriminant = earth_radius_m * earth_radius_m - s * s * sin_t * sin_t;
  if (discriminant < 0 || cos_t <= 0)
    throw LookPastHorizon(fmt::format(
        "a line of sight {:.4g} deg off nadir misses the Earth: the horizon is {:.4g} deg off nadir at {:.4g} km",
        off_nadir_rad * 180 / 3.141592653589793, horizon_off_nadir_angle_rad(altitude_m, earth_radius_m) * 180 / 3.141592653589793,
        altitude_m / 1e3));
  // The nearer root of |S + t d|² = R²; written as (s² − R²)/(s cos θ + √·) to keep precision at nadir.
  return (s * s - earth_radius_m * earth_radius_m) / (s * cos_t + std::sqrt(discriminant));
}

double view_zenith_angle_rad(double altitude_m, double off_nadir_rad, double earth_radius_m) {
  slant_range_m(altitude_m, off_nadir_rad, earth_radius_m);  // the horizon check
  return std::asin(std::min(1.0, (earth_radius_m + altitude_m) * std::sin(off_nadir_rad) / earth_radius_m));
}

double earth_central_angle_rad(double altitude_m, double off_nadir_rad, double earth_radius_m) {
  return view_zenith_angle_rad(altitude_m, off_nadir_rad, earth_radius_m) - off_nadir_rad;
}

double gsd_in_look_plane_m(double altitude_m, double off_nadir_rad, double angular_sample_rad, double earth_radius_m) {
  const double rho = slant_range_m(altitude_m, off_nadir_rad, earth_radius_m);
  return rho * angular_sample_rad / std::cos(view_zenith_angle_rad(altitude_m, off_nadir_rad, earth_radius_m));
}

double gsd_across_look_plane_m(double altitude_m, double off_nadir_rad, double angular_sample_rad,
                               double earth_radius_m) {
  return slant_range_m(altitude_m, off_nadir_rad, earth_radius_m) * angular_sample_rad;
}

double ground_distance_between_looks_m(double altitude_m, double roll1_rad, double pitch1_rad, double roll2_rad,
                                       double pitch2_rad, double earth_radius_m) {
  // In order (a refusal names the first look past the horizon whichever compiler evaluated it).
  const auto first = ground_point(altitude_m, look_direction(roll1_rad, pitch1_rad, 0), earth_radius_m);
  const auto second = ground_point(altitude_m, look_direction(roll2_rad, pitch2_rad, 0), earth_radius_m);
  return arc_between(first, second, earth_radius_m);
}

double gsd_across_track_m(double altitude_m, double roll_rad, double pitch_rad, double angular_sample_rad,
                          double earth_radius_m) {
  return swath_m(altitude_m, roll_rad, pitch_rad, angular_sample_rad / 2, earth_radius_m);
}

double gsd_along_track_m(double altitude_m, double roll_rad, double pitch_rad, double angular_sample_rad,
                         double earth_radius_m) {
  return ground_distance_between_looks_m(altitude_m, roll_rad, pitch_rad - angular_sample_rad / 2, roll_rad,
                                         pitch_rad + angular_sample_rad / 2, earth_radius_m);
}

double swath_m(double altitude_m, double roll_rad, double pitch_rad, double half_field_rad, double earth_radius_m) {
  // The edge further off nadir first, so that a swath reaching past the horizon is refused naming that edge (two
  // statements: the order in which a call's arguments are evaluated is unspecified, and GCC and clang differ).
  const double far = std::abs(roll_rad + half_field_rad) >= std::abs(roll_rad - half_field_rad) ? half_field_rad : -half_field_rad;
  const auto far_edge = ground_point(altitude_m, look_direction(roll_rad, pitch_rad, far), earth_radius_m);
  const auto near_edge = ground_point(altitude_m, look_direction(roll_rad, pitch_rad, -far), earth_radius_m);
  return arc_between(near_edge, far_edge, earth_radius_m);
}

double half_field_angle_rad(double line_length_m, double focal_length_m) {
  require_positive(focal_length_m, "focal length");
  return std::atan(line_length_m / (2 * focal_length_m));
}

double line_time_s(double along_track_gsd_m, double ground_speed_m_s) {
  require_positive(ground_speed_m_s, "ground speed");
  return along_track_gsd_m / ground_speed_m_s;
}

}  // namespace radchain::physics
