#pragma once
// Reading what the renderer needs from a chain and its Report (private to framework/imaging). Other stages'
// results are read only through the vocabulary's terms (radchain/vocabulary.hpp), so any plugin that
// publishes them renders.
#include "radchain/chain.hpp"
#include "radchain/error.hpp"
#include "radchain/vocabulary.hpp"

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

// A finite result of the report, or nothing. A criterion's term names the criterion.
inline std::optional<double> result(const Report& report, const Term& term, std::string_view criterion = {}) {
  const auto v = term.per_criterion() ? report.value(term.in_criterion(criterion)) : report.value(std::string(term.name));
  if (v && std::isfinite(*v)) return v;
  return std::nullopt;
}

// The first criterion publishing this term with a finite value: its name and the value.
inline std::optional<std::pair<std::string, double>> criterion_result(const Report& report, const Term& term) {
  for (std::size_t i = 0; i < report.results.size(); ++i) {
    const std::string& n = report.results[i].name;
    if (term.matches(n) && std::isfinite(report.values[i]))
      return std::make_pair(n.substr(9, n.size() - 9 - term.key().size() - 1), report.values[i]);
  }
  return std::nullopt;
}

// Whether the chain has declared the term (a result is declared when the chain is built, set when evaluated).
inline bool publishes(const Chain& chain, const Term& term) { return chain.results().find(term.name).has_value(); }

}  // namespace radchain::render::detail
