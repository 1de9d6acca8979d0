#include "common.hpp"

#include "radchain/error.hpp"

#include <iostream>

namespace radchain::cli {

Sink::Sink(const std::string& path) {
  if (!path.empty()) file_.emplace(path, "--out");
}

std::ostream& Sink::stream() { return file_ ? file_->stream() : std::cout; }

void Sink::commit() {
  if (file_) file_->commit();
  else check_standard_output();
}

TableFormat format_of(const Output& output, TableFormat fallback) {
  TableFormat format = fallback;
  if (!output.format.empty()) format = parse_table_format(output.format);
  else if (!output.out.empty())
    if (auto f = table_format_of_path(output.out)) format = *f;
  refuse_binary_to_stdout(format, output.out);
  return format;
}

void refuse_binary_to_stdout(TableFormat format, const std::string& out) {
  if (format == TableFormat::npy && out.empty())
    throw InputError(SourceLocation{"--format", 0, 0}, "", "npy", "binary output: give --out FILE.npy");
}

ShardSpec shard_of(const Batch& batch) {
  if (batch.shard.empty()) {
    if (batch.shard_order != "block" && batch.shard_order != "round-robin")
      throw InputError(SourceLocation{"--shard-order", 0, 0}, "", batch.shard_order, "expected block or round-robin");
    return {};
  }
  return parse_shard(batch.shard, batch.shard_order);
}

}  // namespace radchain::cli
