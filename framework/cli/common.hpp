#pragma once
// What several commands share: --set parsing, the output stream (--out or stdout), --format and --shard.
#include "commands.hpp"

#include "radchain/batch/shard.hpp"
#include "radchain/batch/table.hpp"

#include <fstream>
#include <ostream>
#include <string>

namespace radchain::cli {

// --set key=value; the value may be quoted for the shell's sake: optics.aperture="20 cm".
Override parse_override(const std::string& text);
std::string unquoted(std::string text);

// The stream a command writes to: --out file, or stdout.
class Sink {
 public:
  explicit Sink(const std::string& path);
  std::ostream& stream();

 private:
  std::ofstream file_;
};

TableFormat format_of(const Output& output, TableFormat fallback);
ShardSpec shard_of(const Batch& batch);

}  // namespace radchain::cli
