#pragma once
// A spectrum is a value: an explicit, strictly increasing wavelength grid (metres) and an Eigen array of
// values in absolute SI units (e.g. W m^-2 m^-1 for spectral irradiance, "1" for a relative response).
// Between grid points it is piecewise linear; outside the grid it follows a named extrapolation rule.
// Combining spectra on different grids is explicit: product() works on the union of both grids.
// The data are immutable and shared: copying a spectrum (a 1,697-point solar table handed from stage to stage
// at every spectral phase) copies a pointer.
#include <Eigen/Core>
#include <functional>
#include <initializer_list>
#include <memory>
#include <string>
#include <vector>

namespace radchain {

enum class Extrapolation {
  zero,   // 0 outside the grid (tables of emission or response: nothing is known, nothing is counted)
  clamp,  // the end values (e.g. a transmittance known to be flat)
};

// What the integrand is weighted by.
enum class Weight {
  energy,   // 1: W → W
  photons,  // λ/(h c), photons per joule at λ (Pan 2010 eq. 6): W → photons s⁻¹
};

class Spectrum {
 public:
  Spectrum() = default;
  // Throws std::invalid_argument when sizes differ, fewer than 2 points, or the grid is not strictly increasing.
  Spectrum(Eigen::ArrayXd wavelength_m, Eigen::ArrayXd value, std::string unit,
           Extrapolation extrapolation = Extrapolation::zero);

  // A spectrum with the same value everywhere (clamped), e.g. a constant transmittance.
  static Spectrum constant(double value, std::string unit, double lo_m = 1e-7, double hi_m = 1e-4);
  // Samples f on a grid.
  static Spectrum sampled(const Eigen::ArrayXd& wavelength_m, const std::function<double(double)>& f,
                          std::string unit, Extrapolation extrapolation = Extrapolation::zero);

  const Eigen::ArrayXd& wavelength_m() const { return data().wavelength_m; }
  const Eigen::ArrayXd& value() const { return data().value; }
  const std::string& unit() const { return data().unit; }
  Extrapolation extrapolation() const { return data().extrapolation; }
  double min_wavelength_m() const { return wavelength_m()(0); }
  double max_wavelength_m() const { return wavelength_m()(size() - 1); }
  Eigen::Index size() const { return wavelength_m().size(); }
  bool empty() const { return size() == 0; }

  double operator()(double wavelength_m) const;  // linear interpolation + extrapolation rule
  Eigen::ArrayXd operator()(const Eigen::ArrayXd& wavelength_m) const;

  // Same grid, values times k; the unit string is replaced when given.
  Spectrum scaled(double k, std::string unit = {}) const;
  // Values re-expressed on another grid (linear interpolation).
  Spectrum resampled(const Eigen::ArrayXd& wavelength_m) const;
  // Pointwise product on the union of both grids (restricted to where either is non-zero by extrapolation
  // rules); the unit is "<a> <b>" unless given.
  Spectrum product(const Spectrum& other, std::string unit = {}) const;
  // Value at the grid maximum.
  double peak_value() const;
  double peak_wavelength_m() const;

  // ∫ value dλ over [lo, hi] (metres), exact for the piecewise-linear function (trapezoid on the grid with
  // the limits inserted as nodes).
  double integral(double lo_m, double hi_m) const;
  double integral() const { return integral(min_wavelength_m(), max_wavelength_m()); }

 private:
  friend double band_integral(std::initializer_list<const Spectrum*>, double, double, Weight);
  struct Data {
    Eigen::ArrayXd wavelength_m, value;
    Eigen::ArrayXd slope;  // (v[i+1] − v[i]) / (λ[i+1] − λ[i]): interpolation without a division
    std::string unit;
    Extrapolation extrapolation = Extrapolation::zero;
  };
  // The empty spectrum's data when default-constructed. Inline: every accessor goes through it, from plugins too.
  const Data& data() const { return data_ ? *data_ : empty_data(); }
  static const Data& empty_data();
  std::shared_ptr<const Data> data_;
};

// The sorted union of several grids, clipped to [lo, hi] with lo and hi included.
Eigen::ArrayXd union_grid(std::initializer_list<const Spectrum*> spectra, double lo_m, double hi_m);

// ∫_lo^hi  Π_i s_i(λ) · weight(λ) dλ by the trapezoid rule on the union of the spectra's grids (limits
// included). Deterministic; this is the one band integral every plugin uses. One pass, no allocation: a
// spectral phase integrates 1,000-point tables several times and must stay in microseconds.
double band_integral(std::initializer_list<const Spectrum*> spectra, double lo_m, double hi_m,
                     Weight weight = Weight::energy);

}  // namespace radchain
