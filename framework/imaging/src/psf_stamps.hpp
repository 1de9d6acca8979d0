#pragma once
// Pixel-integrated PSFs ("effective PSFs", Anderson & King 2000, PASP 112, 1360) on a grid of sub-pixel source
// positions (private to framework/src/render). A source at a position rounded to 1/k pixel (k = oversampling)
// adds its electrons times one precomputed stamp of (2R+1)² pixel fractions.
//   pixel:    the whole image in the pixel that holds the source;
//   gaussian: the exact pixel integral, [Φ((d+½)p/σ) − Φ((d−½)p/σ)] per axis;
//   airy:     E(s) = ∫ OTF(ν) sinc(pν_x) sinc(pν_y) e^{2πiν·s} dν, the PSF convolved with the pixel, computed
//             by one inverse FFT on the grid of sub-pixel positions (spacing p/k) over a periodic domain of
//             D ≥ 2(2R+1) pixels. The OTF of the annular pupil (physics::diffraction_mtf_normalized) vanishes
//             beyond ν_c = 1/(λN), so the spectrum of the samples is the OTF·sinc product folded with period
//             k/p — summed exactly over its aliases — and the samples are exact up to the energy that lies
//             farther than D − R pixels (it wraps around; < 0.05 % for the default R).
#include "radchain/imaging/space_frame.hpp"

#include <vector>

namespace radchain::render::detail {

struct PsfSpec {
  PsfModel model = PsfModel::pixel;
  double pitch_m = 0;
  double wavelength_m = 0, f_number = 0, obscuration = 0;  // airy
  double fwhm_m = 0;                                       // gaussian
  int oversampling = 8;
  int radius_px = 0;
};

// The stamp half-size that holds 99.9 % of the energy: Airy from its tail 1 − EE(v) ≈ 2/(π v) (Born & Wolf
// §8.5.2; heavier by 1/(1 − ε) with an obscuration, roughly), Gaussian 4σ; at most 32 pixels.
int default_stamp_radius(const PsfSpec& spec);

class PsfStamps {
 public:
  PsfStamps() = default;
  explicit PsfStamps(const PsfSpec& spec);
  int radius() const { return radius_; }
  int side() const { return 2 * radius_ + 1; }
  int phases() const { return phases_; }
  // side² fractions, row-major, centre = the pixel that holds the source.
  const double* stamp(int phase_x, int phase_y) const {
    const std::size_t n = static_cast<std::size_t>(side()) * static_cast<std::size_t>(side());
    return values_.data() + (static_cast<std::size_t>(phase_y) * static_cast<std::size_t>(phases_) + static_cast<std::size_t>(phase_x)) * n;
  }
  // A coordinate (pixel centres at i + ½) → the pixel that holds it and the phase of its rounded position.
  void locate(double position_px, int& pixel, int& phase) const;

 private:
  void build_pixel();
  void build_gaussian(const PsfSpec& spec);
  void build_airy(const PsfSpec& spec);
  int radius_ = 0, phases_ = 1;
  std::vector<double> values_;
};

}  // namespace radchain::render::detail
