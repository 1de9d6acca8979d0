// `radchain mtf` (in the imaging module): MTF curves of a pushbroom design (Kolobrodov 1996 Fig. 2), or the MTF
// budget of an Earth-observation camera (every component and the system, Nyquist named), as CSV and optionally a PNG.
#include "imaging_common.hpp"
#include "../overrides.hpp"
#include "../plot.hpp"

#include "radchain/atomic_file.hpp"
#include "radchain/error.hpp"
#include "radchain/mtf_curves.hpp"

#include <fmt/format.h>

#include <fstream>
#include <iostream>

namespace radchain::cli {

namespace {

void write_csv(const MtfCommand& options, const std::string& csv) {
  if (options.out.empty()) {
    std::cout << csv;
  } else {
    AtomicFile file(options.out, "--out");
    file.stream() << csv;
    file.commit();
  }
}

// An Earth-observation camera's budget (a giqe criterion): every component and the system, Nyquist named.
int budget_command(const MtfCommand& options, const Report& report) {
  const MtfBudgetCurves curves = mtf_budget_curves(report);
  write_csv(options, mtf_budget_csv(curves));
  if (!options.plot.empty()) {
    std::vector<double> frequency_mm;
    std::vector<std::vector<double>> columns(9);
    for (std::size_t i = 0; i < curves.frequency_per_m.size(); ++i) {
      frequency_mm.push_back(curves.frequency_per_m[i] * 1e-3);
      const physics::MtfComponents& m = curves.components[i];
      const double values[] = {m.diffraction, m.pixel, m.jitter, m.smear, m.diffusion, m.wavefront, m.tdi, m.atmosphere, m.system()};
      for (std::size_t k = 0; k < columns.size(); ++k) columns[k].push_back(values[k]);
    }
    const physics::MtfComponents at_nyquist = physics::mtf_components(curves.budget, curves.nyquist_per_m);
    CurveOptions plot;
    plot.log_y = options.log;
    plot.mark_x = curves.nyquist_per_m * 1e-3;
    plot.mark_label = fmt::format("Nyquist {:.4g} mm-1: system {:.3f}", curves.nyquist_per_m * 1e-3, at_nyquist.system());
    plot_curves(options.plot, report.sensor_name + ": MTF budget (" + curves.criterion + ")", "spatial frequency (mm-1)",
                "MTF", frequency_mm,
                {{"diffraction", "", columns[0]}, {"pixel", "", columns[1]}, {"jitter", "", columns[2]},
                 {"smear", "", columns[3]}, {"diffusion", "", columns[4]}, {"wavefront", "", columns[5]},
                 {"TDI", "", columns[6]}, {"atmosphere", "", columns[7]}, {"system", "", columns[8]}},
                plot);
  }
  return report.all_passed() ? 0 : 1;
}

}  // namespace

int mtf_command(const MtfCommand& options) {
  Chain chain = load_sensor_of(options.sensor);
  const Report report = chain.run();
  if (mtf_view(report) == MtfView::budget) return budget_command(options, report);
  const MtfCurves curves = mtf_curves(report);
  write_csv(options, mtf_curves_csv(curves));
  if (!options.plot.empty()) {
    std::vector<double> frequency_mm;
    for (double nu : curves.frequency_per_m) frequency_mm.push_back(nu * 1e-3);
    CurveOptions plot;  // Kolobrodov's chain has no pixel Nyquist of its own (the element is 1.49 pitches): no mark
    plot.log_y = options.log;
    plot_curves(options.plot,
                fmt::format("{}: MTF at {:.3g} um, f/{:.3g}, eta = {:.3g}", report.sensor_name, curves.wavelength_m * 1e6,
                            curves.f_number, curves.eta),
                "spatial frequency (mm-1)", "MTF", frequency_mm,
                {{"diffraction-limited objective", "", curves.diffraction},
                 {"objective, eq. (7): the paper's linear model", "", curves.objective},
                 {"detector element, eq. (8)", "", curves.detector},
                 {"system, eq. (10)", "", curves.system}},
                plot);
  }
  return report.all_passed() ? 0 : 1;
}

}  // namespace radchain::cli
