#include "radchain/plugin.hpp"

#include "radchain/error.hpp"

#include <fmt/format.h>

namespace radchain {

Stage::~Stage() = default;  // the key function lives in the framework, so every plugin shares one vtable type
void Stage::prepare(Context&) {}
bool Stage::evaluate_lanes(LaneContext&) { return false; }

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

ResultId Context::declare(std::string_view name, std::string_view si_unit, std::string_view equation,
                          std::string_view display_unit) {
  if (declarations_ && next_declaration_ < declarations_->size()) {
    // The same declaration as at the last spectral phase: "<section>.<name>" with the same unit and equation.
    const ResultId id = (*declarations_)[next_declaration_];
    const ResultInfo& info = results.info(id);
    const std::string_view known = info.name;  // "<section>.<name>": the section is this stage's by construction
    if (known.size() == section.size() + 1 + name.size() && known.ends_with(name) && info.si_unit == si_unit &&
        info.equation == equation) {
      ++next_declaration_;
      return id;
    }
  }
  const ResultId id = results.declare(section + "." + std::string(name), std::string(si_unit), plugin, std::string(equation),
                                      std::string(display_unit));
  if (declarations_) {
    declarations_->resize(next_declaration_);  // a stage that declares differently from now on: forget the rest
    declarations_->push_back(id);
    ++next_declaration_;
  }
  return id;
}

std::optional<ResultId> Context::find(std::string_view qualified_name) {
  if (lookups_ && next_lookup_ < lookups_->size()) {
    const ResultId id = (*lookups_)[next_lookup_];
    if (id < results.size() && results.info(id).name == qualified_name) {
      ++next_lookup_;
      return id;
    }
  }
  const std::optional<ResultId> id = results.find(qualified_name);
  if (lookups_ && id) {  // (a miss is not remembered: a later spectral phase may find the result)
    lookups_->resize(next_lookup_);
    lookups_->push_back(*id);
    ++next_lookup_;
  }
  return id;
}

ResultId Context::require(std::string_view qualified_name) {
  if (auto id = find(qualified_name)) return *id;
  throw InputError({}, fmt::format("{} (plugin \"{}\")", section, plugin), "",
                   fmt::format("needs the result \"{}\", which no earlier stage provides: the chain's plugins do not fit together",
                               qualified_name));
}

void Context::refuse_form(const std::string& what, RadiationForm form) const {
  throw InputError({}, fmt::format("{} (plugin \"{}\")", section, plugin), "",
                   fmt::format("expected {} but the earlier stages deliver {}", what, to_string(form)));
}

}  // namespace radchain
