// `radchain describe NAME`: prints the describe model (radchain/batch/describe.hpp) — a plugin's keys, units,
// defaults, ranges, the results it publishes and needs and a TOML example; a kind's plugins, one line each; a sensor
// file's own table (sensor, solve, expected, table); an imaging command's options (render, validate).
#include "../commands.hpp"

#include "radchain/batch/describe.hpp"
#include "radchain/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <vector>

namespace radchain::cli {

namespace {

void print_terms(const char* heading, const std::vector<TermDescription>& terms) {
  fmt::print("\n{}\n", heading);
  if (terms.empty()) fmt::print("  (none)\n");
  std::size_t width = 0, unit_width = 0;
  for (const auto& t : terms) width = std::max(width, t.name.size()), unit_width = std::max(unit_width, t.unit.size() + 2);
  for (const auto& t : terms)
    fmt::print("  {:<{}}  {:<{}}  {}{}\n", t.name, width, fmt::format("[{}]", t.unit), unit_width, t.meaning,
               t.optional ? " (read if an earlier stage publishes it)" : "");
}

// Name, type (with unit), required / default, doc, accepted range, former names.
void print_keys(const std::vector<KeyDescription>& keys) {
  std::size_t width = 6;
  for (const auto& k : keys) width = std::max(width, k.key.size());
  for (const auto& k : keys) {
    std::string kind = k.type == "quantity"   ? "quantity [" + k.si_unit + "]"
                       : k.type == "spectrum" ? "spectrum CSV [" + k.si_unit + "]"
                                              : k.type;
    if (k.shape == "list") kind += ", or a list";
    if (k.shape == "pair") kind = "[low, high] " + kind;
    const std::string status = k.required ? "required" : k.default_value ? "default " + *k.default_value : "optional";
    fmt::print("  {:<{}}  {:<24} {:<22} {}\n", k.key, width, kind, status, k.doc);
    if (!k.accepted.empty()) fmt::print("  {:<{}}  {:<24} accepted: {}\n", "", width, "", k.accepted);
    if (!k.formerly.empty()) fmt::print("  {:<{}}  {:<24} formerly: {}\n", "", width, "", join(k.formerly));
  }
}

}  // namespace

int describe(const std::string& name) {
  const Description d = radchain::describe(name);
  switch (d.what) {
    case Description::What::plugin:
      fmt::print("{}\n  {}\n  physics: {}\n  file: {}\n\nkeys:\n", d.title, d.summary, d.reference, d.file);
      print_keys(d.keys);
      print_terms("publishes:", d.publishes);
      print_terms("needs:", d.needs);
      fmt::print("\nexample:\n{}", d.example);
      break;
    case Description::What::kind: {
      fmt::print("{}:\n", d.title);
      std::size_t width = 0;
      for (const auto& p : d.plugins) width = std::max(width, p.name.size());
      for (const auto& p : d.plugins) fmt::print("  {:<{}}  {}\n", p.name, width, p.summary);
      if (d.plugins.empty()) fmt::print("  (none on the search path)\n");
      break;
    }
    case Description::What::table:
    case Description::What::command:
      fmt::print("{}\n\n{}:\n", d.title, d.what == Description::What::command ? "options" : "keys");
      print_keys(d.keys);
      if (!d.example.empty()) fmt::print("\nexample:\n{}", d.example);
      break;
  }
  return 0;
}

}  // namespace radchain::cli
