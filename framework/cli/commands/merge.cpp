// `radchain merge`: shard files joined into the output of the unsharded job.
#include "../commands.hpp"
#include "../common.hpp"

namespace radchain::cli {

int merge(const MergeCommand& command) {
  std::optional<TableFormat> format;
  if (!command.output.format.empty())
    format = parse_table_format(command.output.format);
  else if (!command.output.out.empty())
    format = table_format_of_path(command.output.out);
  if (format) refuse_binary_to_stdout(*format, command.output.out);
  Sink sink(command.output.out);
  // The output is a temporary until every shard has been read and merged: a failed merge leaves an existing --out
  // untouched, and --out naming one of the shards replaces it only with the complete merge.
  const int code = merge_shards(command.shards, sink.stream(), format, !command.output.out.empty());
  sink.commit();
  return code;
}

}  // namespace radchain::cli
