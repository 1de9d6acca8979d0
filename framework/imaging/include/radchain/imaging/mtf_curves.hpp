#pragma once
// MTF curves of an evaluated pushbroom design (Kolobrodov 1996, Fig. 2): the diffraction-limited objective,
// the real objective in the linear model of eq. (7) with the quality η the design needs (eq. 12), the detector
// element (eq. 8) and the system (eqs. 9-10), from 0 to the element's first zero 1/V_D.
#include "radchain/chain.hpp"

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

}  // namespace radchain
