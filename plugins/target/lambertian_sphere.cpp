// A diffusely reflecting (Lambertian) sphere in space — a satellite or a piece of debris — lit by the source
// and seen at a range r under the solar phase angle α (the angle Sun-object-observer; 0 = full phase).
// Irradiance at the entrance pupil, for a sphere of diameter D and Lambert (= Bond) albedo ρ:
//   E(λ) = E_src(λ) · ρ · (D²/4)/r² · (2/(3π)) · [sin α + (π − α) cos α]
//        = E_src(λ) · p · (D²/4)/r² · Φ(α),     p = 2ρ/3,   Φ(α) = [sin α + (π − α) cos α]/π
// with p the geometric albedo and Φ the Lambert-sphere phase function (Φ(0) = 1, Φ(90°) = 1/π, Φ(180°) = 0).
// The phase integral q = 2 ∫0^π Φ(α) sin α dα = 3/2, so the Bond albedo A = p q = ρ: for a Lambertian sphere
// the Bond albedo is the surface's own reflectance. Sources: H. N. Russell, "On the albedo of the planets and
// their satellites", ApJ 43 (1916) 173; T. P. Lester, M. L. McCall, J. B. Tatum, "Theory of planetary
// photometry", J. R. Astron. Soc. Can. 73 (1979) 233, eqs. for the Lambert sphere; the same phase law is the
// "diffuse sphere" of satellite photometry (e.g. McCue, Williams, Morford, Planet. Space Sci. 19 (1971) 851).
// The albedo is grey (the reflected light keeps the source's spectrum), so the sphere's apparent visual
// magnitude follows from Pan 2010 eq. (1) inverted: m = m_sun − 2.5 lg(E_t/E_sun,1AU), and a [[solve]] for
// target.diameter gives the smallest sphere whose magnitude is the sensor's limiting magnitude.
#include "radchain/constants.hpp"
#include "radchain/physics/photometry.hpp"
#include "radchain/plugin.hpp"

#include <cmath>
#include <numbers>

namespace {
using namespace radchain;

const Schema& schema() {
  static const Schema s = {
      quantity("diameter", "m", "30 cm").needed().above(0).at_most(1e4).scales(Scaling::power_law)
          .described("sphere diameter D (a [[solve]] unknown for the smallest detectable object)"),
      number("albedo", "0.2").needed().above(0).at_most(1).described("albedo, of the kind albedo_kind says"),
      choice("albedo_kind", {"bond", "geometric"}).fallback("bond")
          .described("bond: Lambert (= Bond) albedo ρ of the surface; geometric: p = 2ρ/3 (so p ≤ 2/3)"),
      quantity("range", "m", "1000 km").needed().above(0).described("distance r from the sphere to the sensor"),
      quantity("phase_angle", "rad", "90 deg").needed().at_least(0).at_most(std::numbers::pi)
          .described("solar phase angle α, Sun-object-sensor (0 = fully lit, 180 deg = unlit side)"),
  };
  return s;
}

// Lambert-sphere phase function, normalised to 1 at α = 0.
double lambert_phase_function(double alpha) {
  return (std::sin(alpha) + (std::numbers::pi - alpha) * std::cos(alpha)) / std::numbers::pi;
}

class LambertianSphere final : public Stage {
 public:
  explicit LambertianSphere(const Params& p)
      : diameter_(p.handle("diameter")), albedo_(p.handle("albedo")), range_(p.handle("range")),
        phase_angle_(p.handle("phase_angle")), geometric_given_(p.text("albedo_kind") == "geometric") {
    if (geometric_given_ && p.get("albedo") > 2.0 / 3.0)
      p.reject("albedo", "a Lambertian sphere's geometric albedo is 2/3 of its Bond albedo, so at most 0.6667");
  }

  void prepare(Context& c) override {
    if (c.light.illumination.empty()) c.refuse_form("a source spectrum", RadiationForm::none);
    c.light.signal.form = RadiationForm::pupil_irradiance;
    c.light.signal.spectrum = c.light.illumination;
    if (!c.light.up_path_transmittance.empty())
      c.light.signal.spectrum = c.light.signal.spectrum.product(c.light.up_path_transmittance, c.light.signal.spectrum.unit());
    sun_magnitude_ = c.find(vocabulary::source_visual_magnitude);
    sun_illuminance_ = c.find(vocabulary::source_illuminance);
    sun_distance_ = c.find(vocabulary::source_distance);
    id_diameter_ = c.declare("diameter", "m", "input D", "cm");
    id_bond_ = c.declare("bond_albedo", "1", "ρ (Lambert sphere: Bond albedo = surface albedo, phase integral q = 3/2)");
    id_geometric_ = c.declare("geometric_albedo", "1", "p = 2ρ/3 (Lambert sphere, Russell 1916)");
    id_phase_ = c.declare("phase_function", "1", "Φ(α) = [sin α + (π − α) cos α]/π (Lambert sphere)");
    id_range_ = c.declare("range", "m", "input r", "km");
    id_phase_angle_ = c.declare("phase_angle", "rad", "input α", "deg");
    id_reflectance_ = c.declare("reflected_fraction", "1",
                                "E_pupil/E_at_target = ρ (D²/4)/r² (2/3π)[sin α + (π − α) cos α]");
    if (sun_magnitude_ && sun_distance_) {
      id_ratio_ = c.declare("irradiance_ratio", "1", "E_t / E_sun(1 AU), the ratio of Pan 2010 eq. (1)");
      id_magnitude_ = c.declare("magnitude", "1", "apparent visual magnitude, Pan 2010 eq. (1) inverted: "
                                "m = m_sun − 2.5 lg(E_t/E_sun)");
      if (sun_illuminance_) id_illuminance_ = c.declare(vocabulary::target_illuminance, "E_t = ratio × E_s(1 AU)", "lx");
    }
  }

  void evaluate(Context& c) override {
    const double bond = geometric_given_ ? 1.5 * *albedo_ : *albedo_;
    const double phase = lambert_phase_function(*phase_angle_);
    const double d = *diameter_, r = *range_;
    // ρ (D²/4)/r² (2/(3π)) [sin α + (π − α) cos α] = p (D/2)²/r² Φ(α)
    const double reflected = (2.0 / 3.0) * bond * (d * d / 4.0) / (r * r) * phase;
    c.light.signal.scale = c.light.illumination_scale * reflected * c.light.up_path_scale;
    c.results.set(id_diameter_, d);
    c.results.set(id_bond_, bond);
    c.results.set(id_geometric_, 2.0 * bond / 3.0);
    c.results.set(id_phase_, phase);
    c.results.set(id_range_, r);
    c.results.set(id_phase_angle_, *phase_angle_);
    c.results.set(id_reflectance_, reflected);
    if (id_ratio_) {
      // The source's spectrum per unit illumination_scale is the Sun at 1 AU (sun plugin): the ratio to it is
      // the ratio of eq. (1), whatever the Sun-object distance.
      const double ratio = c.light.illumination_scale * reflected;
      c.results.set(*id_ratio_, ratio);
      c.results.set(*id_magnitude_, physics::magnitude_from_ratio(ratio, c.results.value(*sun_magnitude_)));
      if (id_illuminance_) {
        const double au = constants::astronomical_unit_m / c.results.value(*sun_distance_);
        c.results.set(*id_illuminance_, ratio * c.results.value(*sun_illuminance_) / (au * au));
      }
    }
  }

 private:
  const double *diameter_, *albedo_, *range_, *phase_angle_;
  bool geometric_given_;
  std::optional<ResultId> sun_magnitude_, sun_illuminance_, sun_distance_, id_ratio_, id_magnitude_, id_illuminance_;
  ResultId id_diameter_{}, id_bond_{}, id_geometric_{}, id_phase_{}, id_range_{}, id_phase_angle_{}, id_reflectance_{};
};

}  // namespace

RADCHAIN_PLUGIN(LambertianSphere, {
    .summary = "diffuse (Lambertian) sphere of given diameter and albedo at a range and solar phase angle",
    .reference = "Russell 1916 (Lambert sphere: p = 2ρ/3, Φ(α)); Pan et al. 2010 eq. (1) for its magnitude",
    .schema = schema,
    .publishes = {vocabulary::target_illuminance},
    .needs = {if_present(vocabulary::source_visual_magnitude), if_present(vocabulary::source_illuminance),
              if_present(vocabulary::source_distance)},
})
