// A tungsten reference lamp modelled as a Planckian radiator at a stated temperature on a stated temperature
// scale. Only c2/T enters the spectral shape, so "2848 K", "2854 K" and "2856 K" describe (almost) one lamp
// when each is paired with the c2 of its own scale (docs/sources.md):
//   cie_a_1931  T = 2848 K, c2 = 1.435e-2 m K   the defining formula of illuminant A (CIE S 014-2:2006 =
//                                               ISO 11664-2; CIE 015:2018 §4): reproduces the CIE A table
//   ipts48      T = 2854 K, c2 = 1.438e-2 m K   IPTS-48; the "2854 K lamp" of Russian/Soviet detector data
//                                               (Kolobrodov 1996, after Ishanin et al. 1991)
//   its90       T = 2856 K, c2 = 1.4388e-2 m K  the c2 written into IPTS-68 and ITS-90 (Preston-Thomas 1990,
//                                               Metrologia 27, 3, §3.4); "2856 K" is today's statement of A
//   exact       T = 2856 K, c2 = h c / k_B      SI-2019 exact constants
// The absolute level is the total irradiance at the detector (`irradiance`), or the illuminance there
// (`illuminance`), or neither: then the lamp is relative (the spectrum integrates to 1 W m^-2, scale 1).
#include "radchain/constants.hpp"
#include "radchain/physics/band.hpp"
#include "radchain/physics/photometry.hpp"
#include "radchain/plugin.hpp"

namespace {
using namespace radchain;

struct Convention {
  const char* name;
  double c2_m_K;
  double nominal_temperature_K;
};

// The four statements of the same lamp (see the file header for the sources).
constexpr Convention conventions[] = {
    {"ipts48", constants::second_radiation_ipts48_m_K, 2854.0},
    {"cie_a_1931", constants::second_radiation_1931_m_K, 2848.0},
    {"its90", constants::second_radiation_ipts68_m_K, 2856.0},  // ITS-90 keeps the IPTS-68 value 0.014388 m K
    {"exact", constants::second_radiation_m_K, 2856.0},
};

const Convention& convention_named(const std::string& name) {
  for (const auto& c : conventions)
    if (name == c.name) return c;
  return conventions[0];  // unreachable: validation accepts only the choices
}

const Schema& schema() {
  static const Schema s = {
      choice("convention", {"ipts48", "cie_a_1931", "its90", "exact"}).fallback("ipts48").affects_spectrum()
          .described("temperature scale and its c2: ipts48 1.438e-2 (2854 K lamps), cie_a_1931 1.435e-2 (2848 K = CIE A), "
                     "its90 1.4388e-2, exact h c/k (2856 K)"),
      quantity("temperature", "K", "2854 K").above(0).affects_spectrum()
          .described("colour temperature on the convention's scale (default: 2854 K ipts48, 2848 K cie_a_1931, "
                     "2856 K its90 and exact)"),
      quantity("irradiance", "W m-2", "0.5 W/m2").above(0)
          .described("absolute level: total irradiance at the detector, whole spectrum (else relative)"),
      quantity("illuminance", "lx", "1000 lx").above(0)
          .described("absolute level: illuminance at the detector (instead of irradiance)"),
      spectrum_file("v_lambda", "1", "cie_1924_photopic_V_1nm.csv").fallback("cie_1924_photopic_V_1nm.csv")
          .described("photopic luminous efficiency V(λ) for the illuminance"),
  };
  return s;
}

class BlackbodyLamp final : public Stage {
 public:
  explicit BlackbodyLamp(const Params& p)
      : params_(p), irradiance_(p.handle("irradiance")), illuminance_(p.handle("illuminance")) {
    if (p.has("irradiance") && p.has("illuminance"))
      p.reject("illuminance", "give the lamp's level as irradiance or as illuminance, not both");
  }

  void prepare(Context& c) override {
    const Convention& convention = convention_named(params_.text("convention"));
    temperature_K_ = params_.has("temperature") ? params_.get("temperature") : convention.nominal_temperature_K;
    c2_m_K_ = convention.c2_m_K;
    // Planck M_λ with the convention's c2 (c1 exact SI: only the shape matters once normalised), scaled to
    // ∫ E_λ dλ = 1 W m^-2 on the grid, so that `scale` is the total irradiance in W m^-2.
    const Spectrum planck = physics::blackbody_exitance_spectrum(temperature_K_, c2_m_K_);
    c.light.illumination = planck.scaled(1.0 / planck.integral());
    note_table(c.light, planck, "Planck curve of " + params_.context() + " (its sampled grid)");
    illuminance_per_W_m2_ = physics::luminous(c.light.illumination, params_.spectrum("v_lambda"));

    id_temperature_ = c.declare("temperature", "K", "input T (or the convention's nominal temperature)", "K");
    id_c2_ = c.declare("second_radiation_constant", "m K", std::string("c2 of the ") + convention.name + " convention", "m K");
    id_total_ = c.declare("total_irradiance", "W m-2",
                          "∫ E_λ dλ of Planck M_λ(T, c2) at the given level (relative lamp: 1 W m-2)", "W m-2");
    id_illuminance_ = c.declare(vocabulary::source_illuminance, "CIE: E_v = 683 lm/W ∫ V(λ) E_λ dλ", "lx");
    id_efficacy_ = c.declare("luminous_efficacy", "lm W-1", "E_v / E_e of the Planck spectrum", "lm W-1");
    id_relative_ = c.declare("relative", "1", "1: no irradiance or illuminance given, the level is relative (scale 1)");
  }

  void evaluate(Context& c) override {
    // The level is looked up here, not cached: a solve or sweep may set irradiance on a lamp given as relative.
    const bool by_irradiance = params_.has("irradiance"), by_illuminance = params_.has("illuminance");
    double total = 1.0;  // relative
    if (by_irradiance) total = *irradiance_;
    else if (by_illuminance) total = *illuminance_ / illuminance_per_W_m2_;
    c.light.illumination_scale = total;
    c.results.set(id_temperature_, temperature_K_);
    c.results.set(id_c2_, c2_m_K_);
    c.results.set(id_total_, total);
    c.results.set(id_illuminance_, total * illuminance_per_W_m2_);
    c.results.set(id_efficacy_, illuminance_per_W_m2_);
    c.results.set(id_relative_, by_irradiance || by_illuminance ? 0.0 : 1.0);
  }

 private:
  const Params& params_;
  const double* irradiance_;
  const double* illuminance_;
  double temperature_K_ = 0, c2_m_K_ = 0, illuminance_per_W_m2_ = 0;
  ResultId id_temperature_{}, id_c2_{}, id_total_{}, id_illuminance_{}, id_efficacy_{}, id_relative_{};
};

}  // namespace

RADCHAIN_PLUGIN(BlackbodyLamp, {
    .summary = "Planckian reference lamp (CIE A, 2854 K) at a stated temperature and c2 convention",
    .reference = "Planck; CIE S 014-2 illuminant A; IPTS-48; ITS-90; Kolobrodov 1996",
    .schema = schema,
    .publishes = {vocabulary::source_illuminance},
})
