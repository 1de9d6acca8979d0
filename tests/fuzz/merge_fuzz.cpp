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
  const std::string_view header = "# radchain shard";
  constexpr std::size_t max_files = 32;
  std::vector<std::string> files;
  std::size_t begin = 0;
  while (begin < input.size() && files.size() < max_files) {
    std::size_t next = input.find(header, begin + 1);
    while (next != std::string_view::npos && input[next - 1] != '\n') next = input.find(header, next + 1);
    if (next == std::string_view::npos || files.size() + 1 == max_files) next = input.size();
    files.push_back(radchain::fuzz::write_scratch("shard" + std::to_string(files.size()), input.substr(begin, next - begin)));
    begin = next;
  }
  try {
    std::ostringstream out;
    (void)radchain::merge_shards(files, out);
    std::ostringstream json;
    (void)radchain::merge_shards(files, json, radchain::TableFormat::json);
  } catch (const radchain::InputError&) {
  }
  return 0;
}
