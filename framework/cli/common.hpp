#pragma once
// What the batch commands share: the output stream (--out or stdout), --format and --shard.
#include "options.hpp"
#include "overrides.hpp"

#include "radchain/atomic_file.hpp"
#include "radchain/batch/shard.hpp"
#include "radchain/batch/table.hpp"

#include <optional>
#include <ostream>
#include <string>

namespace radchain::cli {

// The stream a command writes to: --out file (atomic: a temporary renamed by commit(); without commit() nothing is
// written and an existing file is untouched), or stdout (checked in main).
class Sink {
 public:
  explicit Sink(const std::string& path);
  std::ostream& stream();
  void commit();

 private:
  std::optional<AtomicFile> file_;
};

TableFormat format_of(const Output& output, TableFormat fallback);
// .npy is binary: written to a file only (a terminal or a text pipe gets a located refusal).
void refuse_binary_to_stdout(TableFormat format, const std::string& out);
ShardSpec shard_of(const Batch& batch);

}  // namespace radchain::cli
