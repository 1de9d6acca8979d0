#include "common.hpp"

#include "radchain/error.hpp"

#include <iostream>

namespace radchain::cli {


Override parse_override(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError(SourceLocation{"--set", 0, 0}, "", text, "expected <section>.<key>=<value>, e.g. optics.aperture=\"20 cm\"");
  return Override{text.substr(0, eq), text.substr(eq + 1)};
}


std::string unquoted(std::string text) {
  if (text.size() >= 2 && text.front() == '"' && text.back() == '"') text = text.substr(1, text.size() - 2);
  return text;
}

// The stream a command writes to: --out file, or stdout.
Sink::Sink(const std::string& path) {
    if (path.empty()) return;
    file_.open(path, std::ios::binary);
  if (!file_) throw InputError(SourceLocation{"--out", 0, 0}, "", path, "cannot be written (missing folder or no permission)");
}

std::ostream& Sink::stream() { return file_.is_open() ? static_cast<std::ostream&>(file_) : std::cout; }

TableFormat format_of(const Output& output, TableFormat fallback) {
  if (!output.format.empty()) return parse_table_format(output.format);
  if (!output.out.empty())
    if (auto f = table_format_of_path(output.out)) return *f;
  return fallback;
}

ShardSpec shard_of(const Batch& batch) {
  if (batch.shard.empty()) {
    if (batch.shard_order != "block" && batch.shard_order != "round-robin")
      throw InputError(SourceLocation{"--shard-order", 0, 0}, "", batch.shard_order, "expected block or round-robin");
    return {};
  }
  return parse_shard(batch.shard, batch.shard_order);
}

std::vector<Override> parse_overrides(const std::vector<std::string>& sets) {
  std::vector<Override> out;
  for (const auto& s : sets) out.push_back(parse_override(s));
  return out;
}

}  // namespace radchain::cli
