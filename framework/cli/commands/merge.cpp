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
  Sink sink(command.output.out);
  return merge_shards(command.shards, sink.stream(), format);
}

}  // namespace radchain::cli
