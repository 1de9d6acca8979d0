#pragma once
// Point spread functions in the focal plane and the fraction of a point image's energy that falls in a
// detection window (encircled and ensquared energy). Lengths in metres on the focal plane, f_number N = f'/D,
// all PSFs normalised to unit total energy. Sources:
//   Airy pattern of a circular pupil: Born & Wolf, Principles of Optics, 7th ed. (1999), §8.5.2:
//     I(v) = I0 [2 J1(v)/v]², v = π D r/(λ f') = π r/(λ N); encircled energy 1 − J0²(v) − J1²(v) (Rayleigh),
//     0.838 inside the first dark ring v = 3.8317, 0.910 inside the second, 0.938 inside the third.
//   Annular pupil (central obscuration ε): amplitude [2J1(v)/v − ε² 2J1(εv)/(εv)]/(1 − ε²), encircled energy
//       [1 − J0²(v) − J1²(v) + ε²(1 − J0²(εv) − J1²(εv)) − 4ε ∫0^v J1(x) J1(εx)/x dx] / (1 − ε²)
//     (V. N. Mahajan, Optical Imaging and Aberrations, Part II: Wave Diffraction Optics, SPIE 2001; the cross
//     term is integrated numerically and tends to ε/2, so the total is 1). tests/core/physics/physics_psf_test.cpp
//     checks both forms against a brute-force integral of the PSF itself.
//   Gaussian PSF of standard deviation σ = FWHM / (2 √(2 ln 2)): encircled 1 − exp(−R²/2σ²), ensquared over a
//     centred square of side a: erf(a / (2√2 σ))² (separable).
// Ensquared energy of a radially symmetric PSF over a centred square of side a (half side h) from its
// encircled energy EC(R), by the eight-fold symmetry of the square in polar coordinates:
//   EE(a) = 8 ∫0^{π/4} ∫0^{h/cos θ} p(r) r dr dθ = (4/π) ∫0^{π/4} EC(h / cos θ) dθ,
// a one-dimensional adaptive Gauss-Kronrod quadrature (Boost.Math) that is the exact 2D integral.
#include <functional>

namespace radchain::physics {

// ---- Airy (diffraction-limited, monochromatic, on axis, in focus) -----------------------------------------

// The optical coordinate v = π r / (λ N).
double airy_optical_coordinate(double radius_m, double wavelength_m, double f_number);
// I(v)/I(0) for a pupil with central obscuration ε (0 ≤ ε < 1): 1 at v = 0, [2 J1(v)/v]² for ε = 0.
double airy_normalized_intensity(double v, double obscuration = 0.0);
// PSF per unit area with unit total energy, W m^-2 per W: peak π (1 − ε²) / (4 (λN)²).
double airy_psf_per_m2(double radius_m, double wavelength_m, double f_number, double obscuration = 0.0);
// First zero of the amplitude (first dark ring) in v: 3.831706 for ε = 0, moving inwards with ε.
double airy_first_dark_ring_v(double obscuration = 0.0);
double airy_first_dark_ring_radius_m(double wavelength_m, double f_number, double obscuration = 0.0);
// Fraction of the energy within a circle of radius R (the closed forms above).
double airy_encircled_energy_v(double v, double obscuration = 0.0);
double airy_encircled_energy(double radius_m, double wavelength_m, double f_number, double obscuration = 0.0);
// Fraction within a centred square of side a.
double airy_ensquared_energy(double side_m, double wavelength_m, double f_number, double obscuration = 0.0);
// The noise-equivalent area n_eff = 1/Σ f_ij² (pixels) of an Airy PSF centred on a pixel of side `pitch` (the best
// case: a star on a pixel corner spreads over more pixels when p ≳ λN), f_ij the
// energy in pixel (i, j) (the photometric weight of PSF fitting: King 1983, PASP 95, 163). For pitch ≤ λN/2 the
// sum is exact in the frequency domain (Poisson summation: the squared, pixel-integrated PSF is band-limited to
// 2/(λN), so no alias reaches the sampling): Σ f² = p² ∫∫ OTF(ν)² sinc²(p ν_x) sinc²(p ν_y) d²ν. Coarser pixels
// by airy_noise_equivalent_area_by_pixels.
double airy_noise_equivalent_area_px(double pitch_m, double wavelength_m, double f_number, double obscuration = 0.0);
// The same summed over pixels (any pitch): each pixel's energy from the closed-form encircled energy by the polar
// form of a rectangle (as ensquared_from_encircled), out to (K + ½) p ≥ 12 λN, plus the r⁻⁶ tail of the squares
// beyond (from the ring-averaged intensity (λN)/(π³ (1 − ε) r³) per unit area: ~2e-7 of the sum or less).
// Milliseconds for p ≳ 2 λN; 40 ms (clear) to 0.3 s (ε = 0.3) just above λN/2.
double airy_noise_equivalent_area_by_pixels(double pitch_m, double wavelength_m, double f_number, double obscuration = 0.0);

// ---- Gaussian ------------------------------------------------------------------------------------------

double gaussian_sigma_from_fwhm(double fwhm_m);
double gaussian_fwhm_from_sigma(double sigma_m);  // 2 √(2 ln 2) σ
double gaussian_encircled_energy(double radius_m, double fwhm_m);
double gaussian_ensquared_energy(double side_m, double fwhm_m);

// ---- Any radially symmetric PSF ------------------------------------------------------------------------

// (4/π) ∫0^{π/4} EC(a / (2 cos θ)) dθ for an encircled-energy function EC(R) (R in metres).
double ensquared_from_encircled(const std::function<double(double)>& encircled_energy, double side_m);

}  // namespace radchain::physics
