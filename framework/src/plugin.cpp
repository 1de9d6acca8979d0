#include "radchain/plugin.hpp"

#include "radchain/error.hpp"

#include <fmt/format.h>

namespace radchain {

Stage::~Stage() = default;  // the key function lives in the framework, so every plugin shares one vtable type
void Stage::prepare(Context&) {}

std::string to_string(Kind kind) {
  switch (kind) {
    case Kind::platform: return "platform";
    case Kind::source: return "source";
    case Kind::target: return "target";
    case Kind::atmosphere: return "atmosphere";
    case Kind::optics: return "optics";
    case Kind::detector: return "detector";
    case Kind::criterion: return "criterion";
  }
  return "?";
}

std::string kind_directory(Kind kind) {
  switch (kind) {
    case Kind::platform: return "platforms";
    case Kind::source: return "sources";
    case Kind::target: return "targets";
    case Kind::atmosphere: return "atmospheres";
    case Kind::optics: return "optics";
    case Kind::detector: return "detectors";
    case Kind::criterion: return "criteria";
  }
  return "?";
}

std::optional<Kind> kind_from_directory(const std::string& directory) {
  for (Kind k : {Kind::platform, Kind::source, Kind::target, Kind::atmosphere, Kind::optics, Kind::detector, Kind::criterion})
    if (kind_directory(k) == directory) return k;
  return std::nullopt;
}

std::string to_string(RadiationForm form) {
  switch (form) {
    case RadiationForm::none: return "no radiation";
    case RadiationForm::pupil_irradiance: return "a point object's irradiance at the pupil";
    case RadiationForm::scene_radiance: return "an extended scene's radiance";
    case RadiationForm::focal_power: return "a point image's power";
    case RadiationForm::focal_irradiance: return "a focal-plane irradiance";
  }
  return "?";
}

ResultId Context::declare(const std::string& name, const std::string& si_unit, const std::string& equation,
                          const std::string& display_unit) {
  return results.declare(section + "." + name, si_unit, plugin, equation, display_unit);
}

ResultId Context::require(const std::string& qualified_name) const {
  if (auto id = results.find(qualified_name)) return *id;
  throw InputError({}, fmt::format("{} (plugin \"{}\")", section, plugin), "",
                   fmt::format("needs the result \"{}\", which no earlier stage provides: the chain's plugins do not fit together",
                               qualified_name));
}

void Context::refuse_form(const std::string& what, RadiationForm form) const {
  throw InputError({}, fmt::format("{} (plugin \"{}\")", section, plugin), "",
                   fmt::format("expected {} but the earlier stages deliver {}", what, to_string(form)));
}

}  // namespace radchain
