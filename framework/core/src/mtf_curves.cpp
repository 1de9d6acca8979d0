#include "radchain/mtf_curves.hpp"

#include "radchain/error.hpp"
#include "radchain/physics/mtf.hpp"
#include "radchain/vocabulary.hpp"

#include <fmt/format.h>

namespace radchain {

MtfCurves mtf_curves(const Report& report, int points) {
  auto need = [&](const std::string& name) {  // a qualified name of a vocabulary term
    const auto v = report.value(name);
    if (!v) throw InputError(SourceLocation{report.sensor_file, 0, 0}, "mtf", name,
                             "this sensor publishes no such result: MTF curves need a telescope with a focal length, "
                             "a ccd_line detector and an mtf_match criterion");
    return *v;
  };
  MtfCurves c;
  c.f_number = need(std::string(vocabulary::optics_f_number.name));
  c.element_m = need(std::string(vocabulary::detector_element_size_for_mtf.name));
  std::string criterion;  // the last criterion publishing a required quality
  for (const auto& r : report.results)
    if (vocabulary::criterion_required_quality.matches(r.name))
      criterion = r.name.substr(9, r.name.size() - 9 - vocabulary::criterion_required_quality.key().size() - 1);
  if (criterion.empty()) need(vocabulary::criterion_required_quality.in_criterion("<name>"));
  c.wavelength_m = need(vocabulary::criterion_wavelength.in_criterion(criterion));
  c.eta = need(vocabulary::criterion_required_quality.in_criterion(criterion));
  const double top = 1.0 / c.element_m;
  for (int i = 0; i < points; ++i) {
    const double nu = top * i / (points - 1);
    c.frequency_per_m.push_back(nu);
    c.diffraction.push_back(physics::diffraction_mtf(nu, c.wavelength_m, c.f_number));
    c.objective.push_back(physics::kolobrodov_linear_mtf(nu, c.wavelength_m, c.f_number, c.eta));
    c.detector.push_back(physics::detector_pixel_mtf(nu, c.element_m));
    c.system.push_back(c.objective.back() * c.detector.back());  // eq. (9)
  }
  return c;
}

std::string mtf_curves_csv(const MtfCurves& c) {
  std::string out = fmt::format(
      "# MTF curves (Kolobrodov 1996 Fig. 2): lambda = {:.4g} um, N = f'/D = {:.4g}, eta = {:.4g}, V_D = {:.4g} um\n"
      "# diffraction: circular pupil (Goodman); objective: eq. (7); detector: eq. (8); system: eq. (10)\n"
      "frequency_mm-1,diffraction,objective_eq7,detector_eq8,system_eq10\n",
      c.wavelength_m * 1e6, c.f_number, c.eta, c.element_m * 1e6);
  for (std::size_t i = 0; i < c.frequency_per_m.size(); ++i)
    out += fmt::format("{:.6g},{:.6f},{:.6f},{:.6f},{:.6f}\n", c.frequency_per_m[i] * 1e-3, c.diffraction[i],
                       c.objective[i], c.detector[i], c.system[i]);
  return out;
}

namespace {
// "criteria.<name>" of the criterion publishing the budget (a giqe criterion's mtf_nyquist_system), or "".
std::string budget_criterion(const Report& report) {
  const std::string key = ".mtf_nyquist_system";
  for (const auto& r : report.results)
    if (r.name.starts_with("criteria.") && r.name.ends_with(key)) return r.name.substr(0, r.name.size() - key.size());
  return {};
}
}  // namespace

bool has_mtf_budget(const Report& report) { return !budget_criterion(report).empty(); }

MtfView mtf_view(const Report& report) {
  for (const auto& r : report.results)
    if (vocabulary::criterion_required_quality.matches(r.name)) return MtfView::design_curves;
  return has_mtf_budget(report) ? MtfView::budget : MtfView::none;
}

physics::MtfBudget mtf_budget(const Report& report, std::string* criterion_name) {
  const std::string criterion = budget_criterion(report);
  auto need = [&](const std::string& name) {
    const auto v = report.value(name);
    if (!v) throw InputError(SourceLocation{report.sensor_file, 0, 0}, "mtf", name,
                             "this sensor publishes no such result: an MTF budget needs a telescope with a focal length "
                             "and a giqe criterion");
    return *v;
  };
  if (criterion.empty()) need("criteria.<name>.mtf_nyquist_system");
  physics::MtfBudget b;
  b.f_number = need(std::string(vocabulary::optics_f_number.name));
  b.obscuration = report.value(std::string(vocabulary::optics_obscuration.name)).value_or(0.0);
  b.wavelength_m = need(criterion + ".mtf_wavelength");
  b.pitch_m = need(criterion + ".sample_pitch");
  b.jitter_rms_m = need(criterion + ".jitter_rms");
  b.smear_m = need(criterion + ".smear_length");
  b.diffusion_rms_m = need(criterion + ".diffusion_rms");
  b.wavefront_error_waves = need(criterion + ".wavefront_error");
  b.tdi_stages = need(criterion + ".tdi_stages");
  b.tdi_mismatch = need(criterion + ".tdi_mismatch");
  b.focal_length_m = need(std::string(vocabulary::optics_focal_length.name));
  b.fried_parameter_m = report.value(criterion + ".fried_parameter").value_or(0.0);
  if (criterion_name) *criterion_name = criterion;
  return b;
}

MtfBudgetCurves mtf_budget_curves(const Report& report, int points) {
  MtfBudgetCurves c;
  c.budget = mtf_budget(report, &c.criterion);
  const physics::MtfBudget& b = c.budget;
  c.nyquist_per_m = physics::nyquist_frequency_per_m(b.pitch_m);
  const int n = points % 2 ? points : points + 1;  // odd: the middle point is Nyquist exactly
  for (int i = 0; i < n; ++i) {
    const double nu = 2.0 * c.nyquist_per_m * i / (n - 1);
    c.frequency_per_m.push_back(nu);
    c.components.push_back(physics::mtf_components(b, nu));
  }
  return c;
}

std::string mtf_budget_csv(const MtfBudgetCurves& c) {
  const physics::MtfBudget& b = c.budget;
  const physics::MtfComponents at_nyquist = physics::mtf_components(b, c.nyquist_per_m);
  std::string out = fmt::format(
      "# MTF budget of {}: lambda = {:.4g} um, N = {:.4g}, obscuration = {:.4g}, p = {:.4g} um, jitter = {:.4g} um, "
      "smear = {:.4g} um, diffusion = {:.4g} um, WFE = {:.4g} waves, TDI {:.4g} stages (mismatch {:.4g} px), "
      "turbulence r0 = {:.4g} cm (0: none)\n"
      "# Nyquist 1/(2p) = {:.6g} mm-1: system MTF {:.6f} (diffraction {:.6f}, pixel {:.6f})\n"
      "frequency_mm-1,diffraction,pixel,jitter,smear,diffusion,wavefront,tdi,atmosphere,system\n",
      c.criterion, b.wavelength_m * 1e6, b.f_number, b.obscuration, b.pitch_m * 1e6, b.jitter_rms_m * 1e6,
      b.smear_m * 1e6, b.diffusion_rms_m * 1e6, b.wavefront_error_waves, b.tdi_stages, b.tdi_mismatch,
      b.fried_parameter_m * 100, c.nyquist_per_m * 1e-3, at_nyquist.system(), at_nyquist.diffraction, at_nyquist.pixel);
  for (std::size_t i = 0; i < c.frequency_per_m.size(); ++i) {
    const physics::MtfComponents& m = c.components[i];
    out += fmt::format("{:.6g},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f}\n", c.frequency_per_m[i] * 1e-3,
                       m.diffraction, m.pixel, m.jitter, m.smear, m.diffusion, m.wavefront, m.tdi, m.atmosphere, m.system());
  }
  return out;
}

}  // namespace radchain
