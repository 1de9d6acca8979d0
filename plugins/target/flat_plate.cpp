// A flat plate in space (a solar panel, a bus face — one facet of a resolved satellite model) with a diffuse
// (Lambertian) and a specular (mirror) part, lit by the Sun and seen at a range r under the solar phase angle α.
// The plate's normal lies in the phase plane at `normal_offset` δ from the bisector of the Sun and sensor
// directions, so the Sun is θ_i = |α/2 − δ| and the sensor θ_r = |α/2 + δ| from the normal (δ = 0: the mirror
// geometry). Irradiance at the pupil over the irradiance E at the plate:
//   diffuse   E_d/E = ρ_d A cos θ_i cos θ_r / (π r²)
//             (Lambert: BRDF ρ_d/π, radiance L = ρ_d E cos θ_i / π, intensity L A cos θ_r, over r²; the Lambertian
//             facet of satellite photometry: Payne, Lucas, Chaudhary, Mutschler (AFRL), "A Derivation of the
//             Analytical Relationship between the Projected Albedo-Area Product of a Space Object and its
//             Aggregate Photometric Measurements", AMOS conference)
//   specular  E_s/E = ρ_s A cos θ_r / (Ω_sun r²)   when the sensor lies inside the reflected cone, 2|δ| ≤ θ_sun
//             (a mirror keeps the radiance, times ρ_s: the sensor sees the plate filled with the Sun's disk of
//             radiance L_sun = E/Ω_sun, Ω_sun = π θ_sun², θ_sun = R_sun/d; turning the normal by δ turns the
//             reflected beam by 2δ — the law of reflection; a mirror conserves radiance apart from ρ_s — the
//             radiance theorem, e.g. McCluney, Introduction to Radiometry and Photometry); 0 outside it. Valid while
//             the plate subtends less than the Sun as seen by the sensor, A cos θ_r / r² < Ω_sun (the whole plate
//             glints), which is checked.
// Unlit (θ_i ≥ 90°) or seen from behind (θ_r ≥ 90°): no light. The reflectances are grey (the reflected light keeps
// the Sun's spectrum), so the magnitude is Pan 2010 eq. (1) inverted, as for the Lambertian sphere beside it.
// R_sun = 6.957e8 m (IAU 2015 Resolution B3, nominal solar radius); d = the source's distance (1 AU by default).
#include "radchain/constants.hpp"
#include "radchain/physics/photometry.hpp"
#include "radchain/plugin.hpp"

#include <cmath>
#include <numbers>

namespace {
using namespace radchain;

constexpr double solar_radius_m = 6.957e8;  // IAU 2015 Resolution B3 nominal solar radius

const Schema& schema() {
  static const Schema s = {
      quantity("area", "m2", "10 m2").needed().above(0).at_most(1e6).scales(Scaling::power_law)
          .described("plate area A (one face)"),
      number("diffuse_reflectance", "0.2").fallback("0").at_least(0).at_most(1)
          .described("Lambertian reflectance ρ_d of the face"),
      number("specular_reflectance", "0.5").fallback("0").at_least(0).at_most(1)
          .described("mirror reflectance ρ_s of the face (ρ_d + ρ_s ≤ 1)"),
      quantity("range", "m", "36000 km").needed().above(0).described("distance r from the plate to the sensor"),
      quantity("phase_angle", "rad", "30 deg").needed().at_least(0).at_most(std::numbers::pi)
          .described("solar phase angle α, Sun-object-sensor"),
      quantity("normal_offset", "rad", "0 deg").fallback("0 deg").at_least(-std::numbers::pi / 2).at_most(std::numbers::pi / 2)
          .described("angle δ of the plate normal from the bisector of the Sun and sensor directions, in the phase plane "
                     "(0: the mirror direction, a glint)"),
  };
  return s;
}

class FlatPlate final : public Stage {
 public:
  explicit FlatPlate(const Params& p)
      : params_(p), area_(p.handle("area")), diffuse_(p.handle("diffuse_reflectance")),
        specular_(p.handle("specular_reflectance")), range_(p.handle("range")), phase_angle_(p.handle("phase_angle")),
        offset_(p.handle("normal_offset")) {
    if (p.get("diffuse_reflectance") + p.get("specular_reflectance") > 1)
      p.reject("specular_reflectance", "diffuse and specular reflectance together exceed 1 (more light out than in)");
    if (!p.given("diffuse_reflectance") && !p.given("specular_reflectance"))
      p.reject("area", "give diffuse_reflectance, specular_reflectance or both");
  }

  void prepare(Context& c) override {
    if (c.light.illumination.empty()) c.refuse_form("a source spectrum", RadiationForm::none);
    c.light.signal.form = RadiationForm::pupil_irradiance;
    c.light.signal.spectrum = c.light.illumination;
    if (!c.light.up_path_transmittance.empty())
      c.light.signal.spectrum = c.light.signal.spectrum.product(c.light.up_path_transmittance, c.light.signal.spectrum.unit());
    sun_magnitude_ = c.find(vocabulary::source_visual_magnitude);
    sun_distance_ = c.find(vocabulary::source_distance);
    id_incidence_ = c.declare("incidence_angle", "rad", "θ_i = |α/2 − δ|: Sun from the plate normal", "deg");
    id_emission_ = c.declare("emission_angle", "rad", "θ_r = |α/2 + δ|: sensor from the plate normal", "deg");
    id_diffuse_ = c.declare("diffuse_fraction", "1", "E_d/E = ρ_d A cos θ_i cos θ_r / (π r²)");
    id_specular_ = c.declare("specular_fraction", "1", "E_s/E = ρ_s A cos θ_r / (Ω_sun r²) inside the glint cone, else 0");
    id_glint_ = c.declare("glint", "1", "1 when the sensor lies in the Sun's mirror image (2|δ| ≤ θ_sun)");
    id_reflected_ = c.declare("reflected_fraction", "1", "E_pupil/E_at_target: diffuse + specular");
    if (sun_magnitude_) {
      id_ratio_ = c.declare("irradiance_ratio", "1", "E_t / E_sun(1 AU), the ratio of Pan 2010 eq. (1)");
      id_magnitude_ = c.declare("magnitude", "1", "apparent visual magnitude, Pan 2010 eq. (1) inverted");
    }
  }

  void evaluate(Context& c) override {
    const double alpha = *phase_angle_, delta = *offset_, a = *area_, r = *range_;
    const double incidence = std::abs(alpha / 2 - delta), emission = std::abs(alpha / 2 + delta);
    const bool visible = incidence < std::numbers::pi / 2 && emission < std::numbers::pi / 2;
    const double sun_distance = sun_distance_ ? c.results.value(*sun_distance_) : constants::astronomical_unit_m;
    const double sun_radius = solar_radius_m / sun_distance, sun_solid_angle = std::numbers::pi * sun_radius * sun_radius;
    const double diffuse = visible ? *diffuse_ * a * std::cos(incidence) * std::cos(emission) / (std::numbers::pi * r * r) : 0.0;
    const bool glint = visible && *specular_ > 0 && 2 * std::abs(delta) <= sun_radius;
    if (glint && a * std::cos(emission) / (r * r) >= sun_solid_angle)
      params_.reject("range", "the plate subtends more than the Sun's disk as seen from the sensor: the glint would not "
                              "fill it (the mirror model needs A cos θ_r / r² < Ω_sun)");
    const double specular = glint ? *specular_ * a * std::cos(emission) / (sun_solid_angle * r * r) : 0.0;
    const double reflected = diffuse + specular;
    c.light.signal.scale = c.light.illumination_scale * reflected * c.light.up_path_scale;
    c.results.set(id_incidence_, incidence);
    c.results.set(id_emission_, emission);
    c.results.set(id_diffuse_, diffuse);
    c.results.set(id_specular_, specular);
    c.results.set(id_glint_, glint ? 1.0 : 0.0);
    c.results.set(id_reflected_, reflected);
    if (id_ratio_) {  // per unit illumination_scale the source is the Sun at 1 AU (sun plugin): eq. (1)'s ratio
      const double ratio = c.light.illumination_scale * reflected;
      c.results.set(*id_ratio_, ratio);
      c.results.set(*id_magnitude_, physics::magnitude_from_ratio(ratio, c.results.value(*sun_magnitude_)));
    }
  }

 private:
  const Params& params_;
  const double *area_, *diffuse_, *specular_, *range_, *phase_angle_, *offset_;
  std::optional<ResultId> sun_magnitude_, sun_distance_, id_ratio_, id_magnitude_;
  ResultId id_incidence_{}, id_emission_{}, id_diffuse_{}, id_specular_{}, id_glint_{}, id_reflected_{};
};

}  // namespace

RADCHAIN_PLUGIN(FlatPlate, {
    .summary = "flat plate (one satellite facet) with diffuse and specular reflectance at a range, phase angle and "
               "normal orientation: Lambert term and the Sun's mirror glint",
    .reference = "Lambert's law (Lambertian facet, Payne et al., AMOS); mirror glint by radiance conservation "
                 "(McCluney); Pan et al. 2010 eq. (1) for its magnitude; IAU 2015 Resolution B3 solar radius",
    .schema = schema,
    .publishes = {},
    .needs = {if_present(vocabulary::source_visual_magnitude), if_present(vocabulary::source_distance)},
})
