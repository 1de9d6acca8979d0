#pragma once
// Reading what the renderer needs from a chain and its Report (private to framework/src/render).
#include "radchain/chain.hpp"
#include "radchain/error.hpp"

#include <cmath>
#include <optional>
#include <string>

namespace radchain::render::detail {

// An InputError about a sensor that cannot be rendered: `sensors/x.toml: render: <subject>: <problem>`.
[[noreturn]] inline void refuse(const std::string& sensor_file, const std::string& subject, const std::string& problem) {
  throw InputError(SourceLocation{sensor_file, 0, 0}, "render", subject, problem);
}

inline StageSlot* find_slot(Chain& chain, const std::string& section) {
  for (auto& s : chain.stages)
    if (s.section == section) return &s;
  return nullptr;
}

// A finite result of the report, or nothing.
inline std::optional<double> result(const Report& report, const std::string& name) {
  const auto v = report.value(name);
  if (v && std::isfinite(*v)) return v;
  return std::nullopt;
}

// The first result named criteria.<name>.<suffix>, and the <name>.
inline std::optional<std::pair<std::string, double>> criterion_result(const Report& report, const std::string& suffix) {
  for (std::size_t i = 0; i < report.results.size(); ++i) {
    const std::string& n = report.results[i].name;
    if (n.rfind("criteria.", 0) == 0 && n.size() > suffix.size() + 10 && n.ends_with("." + suffix) &&
        std::isfinite(report.values[i]))
      return std::make_pair(n.substr(9, n.size() - 9 - suffix.size() - 1), report.values[i]);
  }
  return std::nullopt;
}

inline std::optional<double> parameter(Chain& chain, const std::string& section, const std::string& key) {
  StageSlot* slot = find_slot(chain, section);
  if (!slot || !slot->params) return std::nullopt;
  try {
    return slot->params->maybe(key);
  } catch (const std::exception&) {
    return std::nullopt;  // not a key of this plugin
  }
}

}  // namespace radchain::render::detail
