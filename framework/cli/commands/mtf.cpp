// `radchain mtf` (in the imaging module): MTF curves of a pushbroom design (Kolobrodov 1996 Fig. 2) as CSV and
// optionally a PNG.
#include "imaging_common.hpp"
#include "../overrides.hpp"
#include "../plot.hpp"

#include "radchain/atomic_file.hpp"
#include "radchain/error.hpp"
#include "radchain/imaging/mtf_curves.hpp"

#include <fmt/format.h>

#include <fstream>
#include <iostream>

namespace radchain::cli {

int mtf_command(const MtfCommand& options) {
  Chain chain = load_sensor_of(options.sensor);
  const Report report = chain.run();
  const MtfCurves curves = mtf_curves(report);
  const std::string csv = mtf_curves_csv(curves);
  if (options.out.empty()) {
    std::cout << csv;
  } else {
    AtomicFile file(options.out, "--out");
    file.stream() << csv;
    file.commit();
  }
  if (!options.plot.empty()) {
    std::vector<double> frequency_mm;
    for (double nu : curves.frequency_per_m) frequency_mm.push_back(nu * 1e-3);
    plot_sweep(options.plot,
               fmt::format("{}: MTF at {:.3g} um, f/{:.3g}, eta = {:.3g}", report.sensor_name, curves.wavelength_m * 1e6,
                           curves.f_number, curves.eta),
               "spatial frequency (mm-1)", frequency_mm,
               {{"diffraction-limited objective", "", curves.diffraction},
                {"objective, eq. (7)", "", curves.objective},
                {"detector element, eq. (8)", "", curves.detector},
                {"system, eq. (10)", "", curves.system}});
  }
  return report.all_passed() ? 0 : 1;
}

}  // namespace radchain::cli
