// Shards of an .npy job (`radchain sweep --shard k/n --out part-k.npy`: the shard framing, `format=npy` and each
// value as its shortest round-trip text) through `radchain merge part-*.npy --out grid.npy`. The input is one or
// more shard files, each starting at a line "# radchain shard" (text before the first is a file of its own), named
// part-<k>.npy as the CLI sees them. They are merged as the CLI merges them to a terminal (an .npy job is refused
// there), to the job's format and to CSV; a merged .npy is then read back the way numpy.load reads it.
// A finding: anything but InputError escaping; a merged .npy that is not what its header says (magic, version,
// header padded to 64 bytes and ended by '\n', the dict radchain writes, shape × columns × 8 bytes of data), whose
// header a Python literal parser would not read (a column name with a line break or NUL: numpy.load fails on it)
// or that repeats a column name (numpy refuses the dtype); a value that differs from the one the CSV merge copied
// for the same cell (both are the shards' text); a sanitizer report; a hang.
#include "fuzz_input.hpp"

#include "radchain/batch/shard.hpp"
#include "radchain/batch/table.hpp"
#include "radchain/error.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace {

[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "npy_shard_fuzz: %s\n", what.c_str());
  std::abort();
}

// The header dict radchain writes, {'descr': [('name', '<f8'), ...], 'fortran_order': False, 'shape': (N,), },
// read strictly; returns the column names and sets `rows`.
std::vector<std::string> read_dict(const std::string& dict, std::size_t& rows) {
  std::size_t at = 0;
  auto expect = [&](const char* text) {
    if (dict.compare(at, std::strlen(text), text) != 0) finding(std::string("merged .npy: header dict, expected \"") + text + "\" at " + std::to_string(at));
    at += std::strlen(text);
  };
  std::vector<std::string> names;
  expect("{'descr': [");
  while (at < dict.size() && dict[at] == '(') {
    expect("('");
    std::string name;
    for (;; ++at) {
      if (at >= dict.size()) finding("merged .npy: a column name's string literal is not closed");
      const char c = dict[at];
      // Python's literal_eval (numpy.lib.format) ends a '...' literal at a line break and refuses a NUL.
      if (c == '\n' || c == '\r' || c == '\0') finding("merged .npy: a column name holds a line break or NUL (numpy.load cannot read the header)");
      if (c == '\'') break;
      if (c == '\\') {
        if (++at >= dict.size()) finding("merged .npy: a column name ends in a lone backslash");
      }
      name += dict[at];
    }
    ++at;
    expect(", '<f8'), ");
    names.push_back(name);
  }
  expect("], 'fortran_order': False, 'shape': (");
  const auto [end, error] = std::from_chars(dict.data() + at, dict.data() + dict.size(), rows);
  if (error != std::errc()) finding("merged .npy: shape is not a count");
  at = static_cast<std::size_t>(end - dict.data());
  expect(",), }");
  while (at + 1 < dict.size() && dict[at] == ' ') ++at;
  if (at + 1 != dict.size() || dict[at] != '\n') finding("merged .npy: the header dict is not padded with spaces and ended by '\\n'");
  return names;
}

// The records of a merged .npy (row-major doubles), after checking the file against its header.
std::vector<double> read_npy(const std::string& npy, std::size_t& rows, std::size_t& columns) {
  if (npy.size() < 10 || npy.compare(0, 6, "\x93NUMPY") != 0) finding("merged .npy: no \\x93NUMPY magic");
  const int version = npy[6];
  if ((version != 1 && version != 3) || npy[7] != 0) finding("merged .npy: version is neither 1.0 nor 3.0");
  const std::size_t preamble = version == 1 ? 10 : 12;
  if (npy.size() < preamble) finding("merged .npy: shorter than its preamble");
  std::size_t length = 0;
  for (std::size_t b = 0; b < preamble - 8; ++b) length |= std::size_t(static_cast<unsigned char>(npy[8 + b])) << (8 * b);
  if ((preamble + length) % 64 != 0) finding("merged .npy: header not padded to 64 bytes");
  if (npy.size() < preamble + length) finding("merged .npy: shorter than its header length");
  const std::string dict = npy.substr(preamble, length);
  // Version 1.0 holds a latin-1 header; radchain writes 3.0 (UTF-8) for anything else.
  if (version == 1)
    for (const char c : dict)
      if (static_cast<unsigned char>(c) >= 0x80) finding("merged .npy: version 1.0 with a non-ASCII header");
  const std::vector<std::string> names = read_dict(dict, rows);
  if (std::set<std::string>(names.begin(), names.end()).size() != names.size())
    finding("merged .npy: a column name twice (numpy refuses the dtype)");
  columns = names.size();
  const std::size_t data = npy.size() - preamble - length;
  if (columns == 0 ? data != 0 : data / 8 / columns != rows || data != rows * columns * 8)
    finding("merged .npy: " + std::to_string(data) + " bytes of data for shape (" + std::to_string(rows) + ",) of " +
            std::to_string(columns) + " columns");
  std::vector<double> values(rows * columns);
  if (!values.empty()) std::memcpy(values.data(), npy.data() + preamble + length, data);
  return values;
}

// The merged .npy holds the numbers the CSV merge copied: the last `rows` lines of the CSV (numeric cells: no
// quotes, no commas), cell by cell.
void compare(const std::vector<double>& values, std::size_t rows, std::size_t columns, const std::string& csv) {
  std::vector<std::string> lines;
  std::istringstream in(csv);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  if (lines.size() < rows) finding("the CSV merge has fewer rows than the .npy");
  for (std::size_t r = 0; r < rows; ++r) {
    const std::string& line = lines[lines.size() - rows + r];
    std::size_t begin = 0;
    for (std::size_t c = 0; c < columns; ++c) {
      const std::size_t comma = std::min(line.find(',', begin), line.size());
      const std::string cell = line.substr(begin, comma - begin);
      begin = comma + 1;
      // As the shard reader reads a numeric cell: a number (a catalogue's delta may carry a '+'), else NaN.
      const char* first = cell.data() + (!cell.empty() && cell.front() == '+');
      double expected = NAN;
      const auto [end, error] = std::from_chars(first, cell.data() + cell.size(), expected);
      if (cell.empty() || error != std::errc() || end != cell.data() + cell.size()) expected = NAN;
      const double got = values[r * columns + c];
      if (std::isnan(expected) ? !std::isnan(got) : std::memcmp(&expected, &got, sizeof got) != 0)
        finding("row " + std::to_string(r) + " column " + std::to_string(c) + ": CSV \"" + cell + "\", .npy " + std::to_string(got));
    }
  }
}

// The job's format as the merge takes it: the last format= of the first file's header line.
bool npy_job(std::string_view input) {
  std::istringstream tokens{std::string(input.substr(0, input.find('\n')))};
  std::string format;
  for (std::string token; tokens >> token;)
    if (token.rfind("format=", 0) == 0) format = token.substr(7);
  return format == "npy";
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input = radchain::fuzz::as_text(data, size);
  const std::vector<std::string> files =
      radchain::fuzz::write_shard_files(input, [](std::size_t k) { return "part-" + std::to_string(k + 1) + ".npy"; });
  try {
    std::ostringstream terminal;  // `radchain merge part-*.npy` without --out
    (void)radchain::merge_shards(files, terminal, {}, false);
  } catch (const radchain::InputError&) {
  }
  try {
    std::ostringstream out;
    const int code = radchain::merge_shards(files, out);
    if (code < 0 || code > 3) finding("exit code " + std::to_string(code));
    std::ostringstream csv;
    (void)radchain::merge_shards(files, csv, radchain::TableFormat::csv);
    if (!npy_job(input)) return 0;  // shards of a text, CSV or JSON job: merge_fuzz's ground
    std::size_t rows = 0, columns = 0;
    const std::vector<double> values = read_npy(out.str(), rows, columns);
    compare(values, rows, columns, csv.str());
  } catch (const radchain::InputError&) {
  }
  return 0;
}
