// Can the objective be matched to the detector (Kolobrodov 1996 eqs. 7, 11-12)? Matching both MTFs at contrast
// 0.5 at the same frequency requires an objective quality
//   η = k (f'/D) λ / V_D,   k = 2·1.218·u  (eq. 12; 1.46 printed for u = 0.6, which paper mode pins)
// and η ≤ 1 (no objective beats diffraction). margin = η_max/η − 1 ≥ 0 where η_max is the quality the designer
// can build (1 for a diffraction-limited objective). The smallest pupil that still matches is
//   D_min = k f' λ / (η_max V_D).
// Also reported: the diffraction cut-off, and the exact diffraction MTF and the linear model (eq. 7) at ν_x1.
#include "radchain/physics/mtf.hpp"
#include "radchain/plugin.hpp"

namespace {
using namespace radchain;

const Schema& schema() {
  static const Schema s = {
      quantity("wavelength", "m", "0.76 um").needed().above(0)
          .described("design wavelength λ for eq. (12) (the band's long end is the demanding one)"),
      number("max_quality", "0.8").fallback("1").above(0).at_most(1)
          .described("η_max, the best objective quality available (1 = diffraction-limited; Fig. 2 uses 0.8)"),
      choice("sinc_root", {"paper", "exact"}).fallback("exact")
          .described("u in eq. (12)'s coefficient 2·1.218·u: the paper's 0.6 (1.4616) or 0.603355 (1.4698)"),
      number("eta_coefficient", "1.46").above(0)
          .described("paper value: pin the coefficient k of eq. (12) (printed 1.46; default: 2·1.218·u)"),
  };
  return s;
}

class MtfMatch final : public Stage {
 public:
  explicit MtfMatch(const Params& p)
      : wavelength_(p.handle("wavelength")), max_quality_(p.handle("max_quality")),
        coefficient_computed_(physics::kolobrodov_eta_coefficient(p.text("sinc_root") == "paper"
                                                                       ? physics::kolobrodov_sinc_half_root_printed
                                                                       : physics::sinc_half_contrast_root())),
        pinned_coefficient_(p.has("eta_coefficient") ? p.handle("eta_coefficient") : nullptr) {}

  void prepare(Context& c) override {
    aperture_ = c.require(vocabulary::optics_aperture);
    focal_ = c.require(vocabulary::optics_focal_length);
    element_ = c.require(vocabulary::detector_element_size_for_mtf);
    nu_half_ = c.require(vocabulary::detector_nu_half_contrast);
    id_wavelength_ = c.declare(vocabulary::criterion_wavelength, "input λ", "um");
    if (pinned_coefficient_) {
      id_coefficient_ = c.declare("eta_coefficient", "1", "k of eq. (12) (pinned paper value)");
      id_coefficient_computed_ = c.declare("eta_coefficient_computed", "1", "2·1.218·u (eq. 12)");
    } else {
      id_coefficient_ = c.declare("eta_coefficient", "1", "2·1.218·u (eq. 12)");
    }
    id_eta_ = c.declare(vocabulary::criterion_required_quality, "Kolobrodov 1996 eq. (12): η = k (f'/D) λ / V_D");
    id_margin_ = c.declare(vocabulary::criterion_margin, "η_max / η − 1 (≥ 0: the objective can be matched)");
    id_min_aperture_ = c.declare("min_aperture", "m", "eq. (12) for D at η = η_max: D = k f' λ / (η_max V_D)", "mm");
    id_cutoff_ = c.declare("diffraction_cutoff", "m-1", "ν_c = D / (λ f')", "mm-1");
    id_diffraction_ = c.declare("diffraction_mtf_at_nu_half", "1", "exact circular-pupil MTF at ν_x1 (Goodman)");
    id_linear_ = c.declare("linear_mtf_at_nu_half", "1", "eq. (7) at ν_x1 with η = required quality (0.5 by construction)");
  }

  void evaluate(Context& c) override {
    const double d = c.results.value(aperture_), f = c.results.value(focal_), vd = c.results.value(element_);
    const double n = f / d;
    const double coefficient = pinned_coefficient_ ? *pinned_coefficient_ : coefficient_computed_;
    const double eta = physics::kolobrodov_eta(*wavelength_, n, vd, coefficient);
    const double nu = c.results.value(nu_half_);
    c.results.set(id_wavelength_, *wavelength_);
    c.results.set(id_coefficient_, coefficient);
    if (id_coefficient_computed_) c.results.set(*id_coefficient_computed_, coefficient_computed_);
    c.results.set(id_eta_, eta);
    c.results.set(id_margin_, *max_quality_ / eta - 1.0);
    c.results.set(id_min_aperture_, coefficient * f * *wavelength_ / (*max_quality_ * vd));
    c.results.set(id_cutoff_, physics::diffraction_cutoff_frequency_per_m(*wavelength_, n));
    c.results.set(id_diffraction_, physics::diffraction_mtf(nu, *wavelength_, n));
    c.results.set(id_linear_, physics::kolobrodov_linear_mtf(nu, *wavelength_, n, eta));
  }

 private:
  const double *wavelength_, *max_quality_;
  double coefficient_computed_;
  const double* pinned_coefficient_;  // the printed 1.46, or null: 2·1.218·u
  std::optional<ResultId> id_coefficient_computed_;
  ResultId aperture_{}, focal_{}, element_{}, nu_half_{};
  ResultId id_wavelength_{}, id_coefficient_{}, id_eta_{}, id_margin_{}, id_min_aperture_{}, id_cutoff_{}, id_diffraction_{}, id_linear_{};
};

}  // namespace

RADCHAIN_PLUGIN(MtfMatch, {
    .summary = "objective-detector resolution matching at contrast 0.5: required η ≤ η_max, smallest pupil",
    .reference = "Kolobrodov 1996 eqs. (7), (11), (12)",
    .schema = schema,
    .publishes = {vocabulary::criterion_wavelength, vocabulary::criterion_required_quality,
                  vocabulary::criterion_margin},
    .needs = {vocabulary::optics_aperture, vocabulary::optics_focal_length, vocabulary::detector_element_size_for_mtf,
              vocabulary::detector_nu_half_contrast},
})
