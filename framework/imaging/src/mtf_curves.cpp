#include "radchain/imaging/mtf_curves.hpp"

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

}  // namespace radchain
