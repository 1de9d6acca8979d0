#pragma once
// The numeric parameter "<section>.<key>" of a chain, for the batch jobs that vary one (sweep axes, Python point
// sweeps): found, or why not, in the words both jobs print. Private to the batch library.
#include "radchain/chain.hpp"
#include "radchain/error.hpp"

#include <fmt/format.h>

#include <string>
#include <vector>

namespace radchain::batch_detail {

inline bool is_numeric(ParamType type) {
  return type == ParamType::quantity || type == ParamType::number || type == ParamType::integer;
}

struct ParameterLookup {
  const Params::Entry* entry = nullptr;  // the parameter, numeric or not
  std::string problem;                   // set when there is no such parameter: the section's or the key's "did you mean"
};

// `section` and `name` are the parts of the key around its last dot.
inline ParameterLookup look_up_parameter(const Chain& chain, const std::string& section, const std::string& name) {
  ParameterLookup found;
  const StageSlot* slot = nullptr;
  std::vector<std::string> sections;
  for (const auto& s : chain.stages) {
    sections.push_back(s.section);
    if (s.section == section) slot = &s;
  }
  if (!slot) {
    found.problem = fmt::format("the sensor file has no section \"{}\"{}; sections: {}", section,
                                did_you_mean(section, sections), join(sections));
    return found;
  }
  std::vector<std::string> numeric_keys;
  std::string renamed;
  for (const auto& e : slot->params->entries()) {
    if (is_numeric(e.spec->type)) numeric_keys.push_back(e.spec->key);
    if (e.spec->key == name) found.entry = &e;
    for (const auto& former : e.spec->former_keys)
      if (former == name) renamed = e.spec->key;
  }
  if (!found.entry && !renamed.empty()) {
    found.problem = fmt::format("{}: \"{}\" is renamed \"{}\" (one name in every plugin)", slot->params->context(), name, renamed);
  } else if (!found.entry) {
    found.problem = fmt::format("{} has no numeric parameter \"{}\"{}; its numeric parameters: {}", slot->params->context(),
                                name, did_you_mean(name, numeric_keys),
                                numeric_keys.empty() ? "none" : join(numeric_keys));
  }
  return found;
}

}  // namespace radchain::batch_detail
