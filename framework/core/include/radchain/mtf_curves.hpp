#pragma once
// MTF curves of an evaluated pushbroom design (Kolobrodov 1996, Fig. 2): the diffraction-limited objective,
// the real objective in the linear model of eq. (7) with the quality η the design needs (eq. 12), the detector
// element (eq. 8) and the system (eqs. 9-10), from 0 to the element's first zero 1/V_D. Or the MTF budget of an
// Earth-observation camera (the giqe criterion's), component by component.
#include "radchain/chain.hpp"
#include "radchain/physics/mtf_budget.hpp"

#include <string>
#include <vector>

namespace radchain {

struct MtfCurves {
  double wavelength_m = 0, f_number = 0, eta = 0, element_m = 0;
  std::vector<double> frequency_per_m, diffraction, objective, detector, system;
};

// Reads optics.f_number, detector.element_size_for_mtf and, from the first criterion that publishes them,
// <criterion>.wavelength and <criterion>.required_quality (plugin mtf_match). Throws InputError naming what is
// missing when the sensor is not such a design.
MtfCurves mtf_curves(const Report& report, int points = 201);
// CSV with a unit header: frequency_mm-1,diffraction,objective_eq7,detector_eq8,system_eq10
std::string mtf_curves_csv(const MtfCurves& curves);

// The MTF budget of an Earth-observation camera (the giqe criterion's cascade, physics/mtf_budget.hpp): every
// component and the system from 0 to 1/p (twice Nyquist), with Nyquist 1/(2p) a grid point.
struct MtfBudgetCurves {
  std::string criterion;  // "criteria.<name>" whose budget this is
  physics::MtfBudget budget;
  double nyquist_per_m = 0;
  std::vector<double> frequency_per_m;
  std::vector<physics::MtfComponents> components;
};
// Whether the report has a budget (a giqe criterion), and the curves; mtf_budget_curves throws InputError if not.
bool has_mtf_budget(const Report& report);

// Which MTF curves a sensor is shown with (`radchain mtf`, the HTML report): Kolobrodov's design curves for a chain
// that designs to a required MTF (an mtf_match criterion), else the camera's budget (a giqe criterion), else none.
enum class MtfView { design_curves, budget, none };
MtfView mtf_view(const Report& report);
// The budget's parameters as the report states them (criterion name in `criterion`); throws InputError if none.
physics::MtfBudget mtf_budget(const Report& report, std::string* criterion = nullptr);
MtfBudgetCurves mtf_budget_curves(const Report& report, int points = 201);
// CSV: frequency_mm-1, diffraction, pixel, jitter, smear, diffusion, wavefront, tdi, system; a comment line names
// the Nyquist frequency and the system MTF there.
std::string mtf_budget_csv(const MtfBudgetCurves& curves);

}  // namespace radchain
