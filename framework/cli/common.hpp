#pragma once
// What the batch commands share: the output stream (--out or stdout), --format and --shard.
#include "options.hpp"
#include "overrides.hpp"

#include "radchain/batch/shard.hpp"
#include "radchain/batch/table.hpp"

#include <fstream>
#include <ostream>
#include <string>

namespace radchain::cli {

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
