// Image-quality requirement as a NIIRS from the General Image Quality Equation (GIQE-5, NGA 2015; GIQE-4,
// Leachtenauer et al. 1997 as an option), evaluated from
//   GSD  GIQE-5: the weighted GSD of NGA eq. (5), GSD_NP / sin(elevation)^¼ with GSD_NP = p R / f' at the look's
//        slant range R and the target's elevation (spherical Earth); GIQE-4: the ground-plane GSD, the geometric
//        mean of the across- and along-track pixel-pitch GSDs (Leachtenauer 1997),
//   RER  the relative edge response of the system MTF in each direction: across track diffraction of the
//        (obscured) pupil at `wavelength` × the pixel aperture × jitter × diffusion × wavefront error × the
//        long-exposure turbulence of a given Fried parameter (none by default); along
//        track also × linear smear × TDI synchronisation (physics/mtf.hpp); the edge integrated from the MTF
//        (physics/giqe.hpp). GIQE-5 takes the weighted RER of NGA eq. (7), (RER_cs RER_as²)^⅓; GIQE-4 the
//        geometric mean — or a measured `rer` in the equation's own definition,
//   H    the geometric mean of the two directions' edge overshoots (GIQE-4 only),
//   SNR  the detector's detector.snr, or `snr` given here.
//   margin = NIIRS / NIIRS_required − 1   (≥ 0 passes)
// A [[solve]] on optics.aperture (the diffraction MTF, hence RER) or platform.altitude (GSD) finds the design for a
// NIIRS. Mode "giqe5" is the default (DESIGN.md §8: the standard a practitioner uses today).
#include "radchain/physics/earth_geometry.hpp"
#include "radchain/physics/giqe.hpp"
#include "radchain/physics/mtf_budget.hpp"
#include "radchain/physics/pushbroom.hpp"
#include "radchain/look.hpp"
#include "radchain/plugin.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <numbers>

namespace {
using namespace radchain;

const Schema& schema() {
  static const Schema s = {
      number("niirs", "5").needed().above(0).at_most(10).described("required NIIRS"),
      choice("equation", {"giqe5", "giqe4"}).fallback("giqe5").described("GIQE version: 5 (NGA 2015) or 4 (Leachtenauer 1997)"),
      quantity("pixel_pitch", "m", "8 um").above(0)
          .described("pixel pitch p, one sample (default: the detector's detector.pixel_pitch)"),
      quantity("wavelength", "m", "0.65 um").needed().above(0).described("wavelength of the diffraction MTF (band centre)"),
      quantity("jitter_rms", "m", "1 um").fallback("0 m").at_least(0).described("rms line-of-sight jitter on the focal plane"),
      number("smear_pixels", "0.2").fallback("0").at_least(0)
          .described("linear smear during the integration, in pixels (default: the ground's motion beyond one line "
                     "during the detector's integration time, 0 when it is the line time)"),
      quantity("diffusion_rms", "m", "1 um").fallback("0 m").at_least(0).described("rms of a Gaussian charge-diffusion spread"),
      number("wavefront_error", "0.05").fallback("0").at_least(0).below(0.18)
          .described("rms wavefront error in waves (Shannon's aberration transfer factor)"),
      number("tdi_stages", "32").fallback("1").at_least(1)
          .described("TDI stages for the synchronisation MTF (default: the detector's detector.tdi_stages, else 1)"),
      number("tdi_mismatch", "0.01").fallback("0").at_least(0).below(1)
          .described("TDI line-rate mismatch per stage, as a fraction of a pixel"),
      quantity("fried_parameter", "m", "0.5 m").above(0)
          .described("Fried parameter r0 of the line of sight at the pupil, at the MTF wavelength: long-exposure turbulence MTF (default none)"),
      number("rer", "0.5").above(0).at_most(1.5).described("measured relative edge response (replaces the MTF budget's)"),
      number("snr", "50").above(0).described("SNR of the reference target (default: the detector's detector.snr)"),
      number("noise_gain", "1").fallback("1").above(0).described("GIQE-4 noise gain G of the processing (1: none)"),
      // Conventions of a peer tool, to reproduce its numbers (validation/pybsm); the defaults are the converged
      // integral and the elevation NGA's GIQE-5 defines.
      choice("edge_integration", {"simpson", "pybsm"}).fallback("simpson")
          .described("how the edge response integrates the MTF: Simpson on 1000 panels to the cut-off, or pyBSM's "
                     "50-node trapezoid to 0.98 of it (RER ~2e-4 higher; GIQE-4's H sampled every 0.25 sample)"),
      choice("elevation", {"target", "sensor"}).fallback("target")
          .described("the elevation of GIQE-5's weighted GSD: the target's, 90° − the view zenith angle (NGA eq. 5), "
                     "or pyBSM's 90° − the off-nadir angle at the sensor"),
  };
  return s;
}

class Giqe final : public Stage {
 public:
  explicit Giqe(const Params& p)
      : params_(p), required_(p.handle("niirs")), wavelength_(p.handle("wavelength")),
        jitter_(p.handle("jitter_rms")), smear_(p.handle("smear_pixels")), diffusion_(p.handle("diffusion_rms")),
        wfe_(p.handle("wavefront_error")), tdi_stages_(p.handle("tdi_stages")), tdi_mismatch_(p.handle("tdi_mismatch")),
        rer_(p.handle("rer")), snr_(p.handle("snr")), noise_gain_(p.handle("noise_gain")), fried_(p.handle("fried_parameter")),
        giqe4_(p.text("equation") == "giqe4"), pybsm_edge_(p.text("edge_integration") == "pybsm"),
        sensor_elevation_(p.text("elevation") == "sensor") {
    if (!giqe4_ && p.given("noise_gain")) p.reject("noise_gain", "is a GIQE-4 term; set equation = \"giqe4\"");
  }

  void prepare(Context& c) override {
    look_.find(c, params_, "niirs");
    f_number_ = c.require(vocabulary::optics_f_number);
    obscuration_ = c.find(vocabulary::optics_obscuration);
    detector_snr_ = params_.has("snr") ? std::nullopt : c.find(vocabulary::detector_snr);
    // Stated once: the TDI stages and the integration time are the detector's (sensor_file.cpp refuses a second,
    // different value here).
    detector_tdi_ = params_.given("tdi_stages") ? std::nullopt : c.find(vocabulary::detector_tdi_stages);
    integration_time_ = c.find(vocabulary::detector_integration_time);
    ground_speed_ = c.find(vocabulary::platform_ground_speed);
    if (!params_.has("snr") && !detector_snr_)
      params_.reject("snr", "no SNR: give snr here, or use a detector that publishes detector.snr");
    id_gsd_ = c.declare("gsd_geometric_mean", "m", "√(GSD_across · GSD_along) at the look, spherical Earth: the ground-plane GSD", "m");
    id_gsd_normal_ = c.declare("gsd_normal_plane", "m", "p R / f': the pixel on the plane normal to the line of sight", "m");
    id_elevation_ = c.declare("target_elevation", "rad",
                              sensor_elevation_ ? "90° − the off-nadir angle at the sensor (pyBSM's convention)"
                                                : "90° − the view zenith angle at the ground point", "deg");
    id_gsd_inch_ = c.declare("gsd_inches", "1",
                             giqe4_ ? "the ground-plane GSD / 0.0254 m (GIQE-4)"
                                    : "GSD_W / 0.0254 m, GSD_W = GSD_NP / sin(elevation)^¼ (NGA GIQE v5.0 eq. 5)");
    id_rer_ = c.declare(vocabulary::criterion_rer,
                        params_.has("rer") ? "input (measured)"
                        : giqe4_           ? "√(RER_across · RER_along) (GIQE-4's geometric mean)"
                                           : "(RER_cs RER_as²)^⅓, the lesser twice (NGA GIQE v5.0 eq. 7)");
    if (!params_.has("rer")) {
      id_rer_across_ = c.declare("rer_across_track", "1", "ER(½) − ER(−½) of the MTF across track (no smear, no TDI)");
      id_rer_along_ = c.declare("rer_along_track", "1", "ER(½) − ER(−½) of the MTF along track (smear and TDI included)");
    }
    // The overshoot costs ~40 edge integrals per direction: only GIQE-4 uses it.
    if (giqe4_) id_overshoot_ = c.declare("overshoot", "1", "√(H_across · H_along); H = max ER on [1, 3] samples, or ER(1.25) if monotonic");
    id_snr_ = c.declare("snr", "1", params_.has("snr") ? "input" : "= detector.snr");
    id_niirs_ = c.declare(vocabulary::criterion_niirs,
                          giqe4_ ? "GIQE-4, Leachtenauer et al. 1997 eq. (2)" : "GIQE-5, NGA GIQE v5.0 (2015)");
    id_required_ = c.declare("required_niirs", "1", "input");
    id_margin_ = c.declare(vocabulary::criterion_margin, "NIIRS / NIIRS_required − 1");
    id_nyquist_ = c.declare("nyquist_frequency", "m-1", "1/(2p)", "mm-1");
    id_mtf_system_ = c.declare("mtf_nyquist_system", "1", "product of the components at Nyquist (along track)");
    id_mtf_diffraction_ = c.declare("mtf_nyquist_diffraction", "1", "annular pupil (O'Neill 1956) at Nyquist");
    id_mtf_pixel_ = c.declare("mtf_nyquist_pixel", "1", "|sinc(π p ν)| at Nyquist = 2/π");
    id_mtf_other_ = c.declare("mtf_nyquist_other", "1", "jitter × smear × diffusion × wavefront × TDI × turbulence at Nyquist");
    id_q_ = c.declare("q_factor", "1", "Q = λN/p (sampling of the optics)");
    // The budget's inputs, so that `radchain mtf` draws the same cascade (physics/mtf_budget.hpp).
    id_budget_wavelength_ = c.declare("mtf_wavelength", "m", "input λ of the diffraction MTF", "um");
    id_budget_pitch_ = c.declare("sample_pitch", "m", "pixel pitch p (one sample)", "um");
    id_budget_jitter_ = c.declare("jitter_rms", "m", "input rms jitter on the focal plane", "um");
    id_budget_smear_ = c.declare("smear_length", "m", "smear_pixels × p", "um");
    id_budget_diffusion_ = c.declare("diffusion_rms", "m", "input rms diffusion spread", "um");
    id_budget_wfe_ = c.declare("wavefront_error", "1", "input rms wavefront error (waves)");
    id_budget_tdi_stages_ = c.declare("tdi_stages", "1", "input TDI stages");
    id_budget_tdi_mismatch_ = c.declare("tdi_mismatch", "1", "input TDI mismatch per stage (pixels)");
    id_budget_fried_ = c.declare("fried_parameter", "m", params_.has("fried_parameter") ? "input r0" : "0: no turbulence term", "cm");
  }

  void evaluate(Context& c) override {
    const Look look = look_.read(c.results);
    const double h = look.altitude_m, p = look.pixel_pitch_m, r = look.earth_radius_m;
    const double roll = look.roll_rad, pitch = look.pitch_rad;
    const double ifov = p / look.focal_length_m;
    const double gsd_ground = std::sqrt(physics::gsd_across_track_m(h, roll, pitch, ifov, r) *
                                        physics::gsd_along_track_m(h, roll, pitch, ifov, r));
    const double off_nadir = physics::off_nadir_angle_rad(roll, pitch);
    const double gsd_normal = ifov * physics::slant_range_m(h, off_nadir, r);
    const double elevation = std::numbers::pi / 2 - (sensor_elevation_ ? off_nadir : physics::view_zenith_angle_rad(h, off_nadir, r));
    const double gsd = giqe4_ ? gsd_ground : physics::giqe5_weighted_gsd_m(gsd_normal, elevation);
    const double n = c.results.value(f_number_), lambda = *wavelength_;
    const double eps = obscuration_ ? c.results.value(*obscuration_) : 0.0;
    const double tdi_stages = detector_tdi_ ? c.results.value(*detector_tdi_) : *tdi_stages_;
    // The ground moves v t during an integration of t; one line time t_line = GSD_along / v moves it one line, the
    // pushbroom's own sampling. An integration longer than the line time smears the excess, (t / t_line − 1) pixels
    // along track (Holst 2008 §10.3, linear motion MTF sinc(π d ν)), unless the file states the smear itself.
    double smear_pixels = *smear_;
    if (integration_time_ && ground_speed_) {
      const double along = physics::gsd_along_track_m(h, roll, pitch, ifov, r);
      const double line_time = physics::line_time_s(along, c.results.value(*ground_speed_));
      const double ratio = c.results.value(*integration_time_) / line_time;
      // (A shorter integration than the line time is exposure control, not an error: only a longer one smears.)
      if (ratio > 1.01) {
        if (!params_.given("smear_pixels")) smear_pixels = ratio - 1;
        c.warn(params_.problem(params_.given("smear_pixels") ? "smear_pixels" : "niirs",
                               fmt::format("the detector integrates {:.4g} line times (t = {:.4g} ms, line time {:.4g} ms "
                                           "for the {:.4g} m along-track GSD at {:.4g} m/s): {}",
                                           ratio, 1e3 * c.results.value(*integration_time_), 1e3 * line_time, along,
                                           c.results.value(*ground_speed_),
                                           params_.given("smear_pixels") ? "the smear stated here is used as given"
                                                                         : fmt::format("{:.4g} pixels of smear counted", ratio - 1))));
      }
    }
    const physics::MtfBudget budget{lambda,         n, eps, p, *jitter_, smear_pixels * p, *diffusion_, *wfe_, tdi_stages,
                                    *tdi_mismatch_, look.focal_length_m, params_.has("fried_parameter") ? *fried_ : 0.0};
    physics::MtfBudget across_budget = budget;  // smear and TDI synchronisation act along track only
    across_budget.smear_m = 0;
    across_budget.tdi_stages = 1;
    across_budget.tdi_mismatch = 0;
    // The MTF in cycles per sample u (ν = u/p).
    auto system = [&](double u) { return physics::mtf_components(budget, u / p).system(); };
    const EdgeTerms& edge = edge_terms(budget, across_budget);
    double rer = params_.has("rer") ? *rer_ : 0.0;
    const double rer_across = edge.rer_across, rer_along = edge.rer_along, overshoot = edge.overshoot;
    if (!params_.has("rer"))
      rer = giqe4_ ? std::sqrt(rer_across * rer_along) : physics::giqe5_weighted_rer(rer_across, rer_along);
    const double snr = params_.has("snr") ? *snr_ : c.results.value(*detector_snr_);
    const double niirs = giqe4_ ? physics::giqe4_niirs(gsd, rer, overshoot, *noise_gain_, snr)
                                : physics::giqe5_niirs(gsd, rer, snr);
    const double nyquist = physics::nyquist_frequency_per_m(p);
    c.results.set(id_gsd_, gsd_ground);
    c.results.set(id_gsd_normal_, gsd_normal);
    c.results.set(id_elevation_, elevation);
    c.results.set(id_gsd_inch_, gsd / physics::metres_per_inch);
    c.results.set(id_rer_, rer);
    if (id_rer_across_) {
      c.results.set(*id_rer_across_, rer_across);
      c.results.set(*id_rer_along_, rer_along);
    }
    if (id_overshoot_) c.results.set(*id_overshoot_, overshoot);
    c.results.set(id_snr_, snr);
    c.results.set(id_niirs_, niirs);
    c.results.set(id_required_, *required_);
    c.results.set(id_margin_, niirs / *required_ - 1.0);
    // The rating scale runs from 0 to 9 (IRARS, Civil NIIRS Reference Guide, 1996): a prediction outside it lies far
    // beyond the imagery the equation was fitted to (a camera at GEO gave −6.3).
    if (niirs < 0 || niirs > 9)
      c.warn(params_.problem("niirs", fmt::format("the predicted NIIRS {:.3g} lies outside the rating scale 0-9: the GIQE is "
                                                  "extrapolated far beyond its fitted range (GSD {:.3g} m, RER {:.3g}, "
                                                  "SNR {:.3g})",
                                                  niirs, gsd_ground, rer, snr)));
    c.results.set(id_nyquist_, nyquist);
    const physics::MtfComponents at_nyquist = physics::mtf_components(budget, nyquist);
    c.results.set(id_mtf_system_, system(0.5));
    c.results.set(id_mtf_diffraction_, at_nyquist.diffraction);
    c.results.set(id_mtf_pixel_, at_nyquist.pixel);
    c.results.set(id_mtf_other_, at_nyquist.others());
    c.results.set(id_q_, lambda * n / p);
    c.results.set(id_budget_wavelength_, lambda);
    c.results.set(id_budget_pitch_, p);
    c.results.set(id_budget_jitter_, budget.jitter_rms_m);
    c.results.set(id_budget_smear_, budget.smear_m);
    c.results.set(id_budget_diffusion_, budget.diffusion_rms_m);
    c.results.set(id_budget_wfe_, budget.wavefront_error_waves);
    c.results.set(id_budget_tdi_stages_, budget.tdi_stages);
    c.results.set(id_budget_tdi_mismatch_, budget.tdi_mismatch);
    c.results.set(id_budget_fried_, budget.fried_parameter_m);
  }

 private:
  // The edge response's RER (across and along track) and, for GIQE-4, its overshoot: integrals of the MTF budget
  // over 1000 panels each, ~10⁴ evaluations of every component. They depend on the budget alone, so they are
  // remembered for the last one: a sweep over reflectance, sun or look angle (smear within the line time) leaves
  // it unchanged and costs the GIQE's closed form only.
  struct EdgeTerms {
    double rer_across = 0, rer_along = 0, overshoot = 0;
  };
  static std::array<double, 12> budget_key(const physics::MtfBudget& b) {
    return {b.wavelength_m, b.f_number,   b.obscuration,  b.pitch_m,        b.jitter_rms_m,   b.smear_m,
            b.diffusion_rms_m, b.wavefront_error_waves, b.tdi_stages, b.tdi_mismatch, b.focal_length_m, b.fried_parameter_m};
  }
  const EdgeTerms& edge_terms(const physics::MtfBudget& budget, const physics::MtfBudget& across_budget) {
    const std::array<double, 12> key = budget_key(budget);
    if (edge_valid_ && key == edge_key_) return edge_;
    const double p = budget.pitch_m;
    auto system = [&](double u) { return physics::mtf_components(budget, u / p).system(); };
    auto across = [&](double u) { return physics::mtf_components(across_budget, u / p).system(); };
    const double cutoff_samples = p * physics::diffraction_cutoff_frequency_per_m(budget.wavelength_m, budget.f_number);
    const double ifov = p / budget.focal_length_m;
    constexpr int panels = 1000;
    auto rer = [&](const auto& mtf) {
      return pybsm_edge_ ? physics::relative_edge_response_pybsm(mtf, cutoff_samples, ifov)
                         : physics::relative_edge_response(mtf, cutoff_samples, panels);
    };
    auto overshoot = [&](const auto& mtf) {
      return pybsm_edge_ ? physics::edge_overshoot_pybsm(mtf, cutoff_samples, ifov)
                         : physics::edge_overshoot(mtf, cutoff_samples, panels);
    };
    edge_valid_ = false;  // (a throw below leaves no stale value under the new key)
    if (!params_.has("rer")) {
      edge_.rer_across = rer(across);
      edge_.rer_along = rer(system);
    } else {
      edge_.rer_across = edge_.rer_along = 0;
    }
    edge_.overshoot = giqe4_ ? std::sqrt(overshoot(across) * overshoot(system)) : 0.0;
    edge_key_ = key;
    edge_valid_ = true;
    return edge_;
  }
  EdgeTerms edge_;
  std::array<double, 12> edge_key_{};
  bool edge_valid_ = false;

  const Params& params_;
  std::optional<ResultId> detector_tdi_, integration_time_, ground_speed_;
  const double *required_, *wavelength_, *jitter_, *smear_, *diffusion_, *wfe_, *tdi_stages_, *tdi_mismatch_,
      *rer_, *snr_, *noise_gain_, *fried_;
  bool giqe4_, pybsm_edge_, sensor_elevation_;
  LookTerms look_;
  ResultId f_number_{};
  std::optional<ResultId> obscuration_, detector_snr_;
  std::optional<ResultId> id_overshoot_, id_rer_across_, id_rer_along_;
  ResultId id_gsd_normal_{}, id_elevation_{};
  ResultId id_gsd_{}, id_gsd_inch_{}, id_rer_{}, id_snr_{}, id_niirs_{}, id_required_{}, id_margin_{},
      id_nyquist_{}, id_mtf_system_{}, id_mtf_diffraction_{}, id_mtf_pixel_{}, id_mtf_other_{}, id_q_{},
      id_budget_wavelength_{}, id_budget_pitch_{}, id_budget_jitter_{}, id_budget_smear_{}, id_budget_diffusion_{},
      id_budget_wfe_{}, id_budget_tdi_stages_{}, id_budget_tdi_mismatch_{}, id_budget_fried_{};
};

}  // namespace

RADCHAIN_PLUGIN(Giqe, {
    .summary = "NIIRS from GSD, RER (from an MTF budget) and SNR by the GIQE-5 (or GIQE-4); margin on a required NIIRS",
    .reference = "NGA, General Image Quality Equation v5.0 (2015); Leachtenauer et al., Appl. Opt. 36 (1997) 8322",
    .schema = schema,
    .publishes = {vocabulary::criterion_niirs, vocabulary::criterion_rer, vocabulary::criterion_margin},
    .needs = {vocabulary::platform_altitude, vocabulary::platform_tilt, if_present(vocabulary::platform_roll),
              if_present(vocabulary::platform_pitch), if_present(vocabulary::platform_earth_radius),
              vocabulary::optics_focal_length, vocabulary::optics_f_number, if_present(vocabulary::optics_obscuration),
              if_present(vocabulary::detector_snr), if_present(vocabulary::detector_pixel_pitch),
              if_present(vocabulary::detector_tdi_stages), if_present(vocabulary::detector_integration_time),
              if_present(vocabulary::platform_ground_speed)},
})
