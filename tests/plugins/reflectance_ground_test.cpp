// reflectance_ground: the at-aperture radiance L = τ↑ ρ E cos θ_s τ↓ / π + L_path against a hand
// computation from the source's in-band irradiance and the atmosphere's inputs.
#include "radchain/chain.hpp"
#include "radchain/error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <unistd.h>

namespace {
using namespace radchain;

std::string write_sensor(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()) + ".toml");
  std::ofstream(path) << text;
  return path.string();
}

const char* sensor = R"toml(
[sensor]
name = "reflectance_ground test"
[platform]
plugin = "earth_orbit"
altitude = "700 km"
[source]
plugin = "sun"
band_min = "0.63 um"
band_max = "0.69 um"
[atmosphere]
plugin = "constant"
transmittance = 0.8
path_radiance = "5 W/(m2 sr)"
[target]
plugin = "reflectance_ground"
reflectance = 0.25
solar_zenith = "60 deg"
[optics]
plugin = "telescope"
aperture = "10 cm"
focal_length = "1 m"
[detector]
plugin = "pixel_array"
pixel_pitch = "10 um"
pixel_count = 1000
[criteria.gsd]
plugin = "gsd_requirement"
gsd = "10 m"
)toml";

TEST(ReflectanceGround, AtApertureRadianceByHand) {
  const std::string path = write_sensor("reflectance_ground", sensor);
  Chain chain = load_sensor(path);
  const Report r = chain.run();
  std::filesystem::remove(path);
  const double e_band = r.value("source.band_irradiance").value();  // E in 0.63-0.69 µm at 1 AU, normal incidence
  const double surface = 0.8 * 0.25 * e_band * 0.5 * 0.8 / std::numbers::pi;  // τ↑ ρ E cos 60° τ↓ / π
  EXPECT_NEAR(r.value("target.cos_solar_zenith").value(), 0.5, 1e-15);
  EXPECT_NEAR(r.value("target.surface_radiance_at_aperture").value(), surface, 1e-9 * surface);
  EXPECT_NEAR(r.value("target.path_radiance").value(), 5.0, 1e-9);
  EXPECT_NEAR(r.value("target.at_aperture_radiance").value(), surface + 5.0, 1e-9 * surface);
  // a sanity range: the Sun gives ~93 W m-2 in 60 nm of red (E-490), so L ≈ 2.37 + 5 W m-2 sr-1
  EXPECT_GT(e_band, 80.0);
  EXPECT_LT(e_band, 120.0);
}

TEST(ReflectanceGround, SunBelowTheHorizonIsAnInputError) {
  std::string text = sensor;
  text.replace(text.find("\"60 deg\""), 8, "\"95 deg\"");
  const std::string path = write_sensor("reflectance_ground_night", text);
  EXPECT_THROW(load_sensor(path), InputError);
  std::filesystem::remove(path);
}

}  // namespace
