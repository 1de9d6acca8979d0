#include "overrides.hpp"

#include "radchain/error.hpp"
#include "radchain/strings.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <iostream>

namespace radchain::cli {
namespace {
using strings::trimmed;


}  // namespace

Override parse_override(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError(SourceLocation{"--set", 0, 0}, "", text, "expected <section>.<key>=<value>, e.g. optics.aperture=\"20 cm\"");
  return Override{text.substr(0, eq), text.substr(eq + 1)};
}

std::vector<Override> parse_overrides(const std::vector<std::string>& sets) {
  std::vector<Override> out;
  for (const auto& s : sets) out.push_back(parse_override(s));
  return out;
}

void warn_about_solved_overrides(const std::vector<SolveSpec>& solves, const std::vector<Override>& overrides,
                                 std::ostream& err) {
  for (const auto& o : overrides) {
    const std::string key = trimmed(o.key);
    if (std::any_of(solves.begin(), solves.end(), [&](const SolveSpec& s) { return s.unknown == key; }))
      err << fmt::format("radchain: warning: --set {}={}: a [[solve]] overwrites {} (add --no-solve to evaluate at the value set)\n",
                         key, o.value, key);
  }
}

Chain load_sensor_of(const SensorArgs& args) {
  const std::vector<Override> overrides = parse_overrides(args.sets);
  Chain chain = load_sensor(args.sensor, overrides, args.no_solve ? Solving::forward_only : Solving::as_written);
  chain.solver = args.solver == "root" ? SolverChoice::root : SolverChoice::automatic;
  warn_about_solved_overrides(chain.solves, overrides, std::cerr);  // (none left when forward only)
  return chain;
}

}  // namespace radchain::cli
