// Shard files through `radchain merge`: the input is one or more shard files, each starting at a line
// "# radchain shard" (text before the first such line is a file of its own), merged in the job's format
// and, when that succeeds, into JSON as well.
#include "fuzz_input.hpp"

#include "radchain/error.hpp"
#include "radchain/batch/shard.hpp"
#include "radchain/batch/table.hpp"

#include <sstream>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input = radchain::fuzz::as_text(data, size);
  const std::vector<std::string> files =
      radchain::fuzz::write_shard_files(input, [](std::size_t k) { return "shard" + std::to_string(k); });
  try {
    std::ostringstream out;
    (void)radchain::merge_shards(files, out);
    std::ostringstream json;
    (void)radchain::merge_shards(files, json, radchain::TableFormat::json);
  } catch (const radchain::InputError&) {
  }
  return 0;
}
