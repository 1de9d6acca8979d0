// Shards of a batch job: which points a shard runs, and merging shard files into the unsharded output.
#include "radchain/batch/shard.hpp"

#include "radchain/batch/catalogue.hpp"
#include "radchain/error.hpp"
#include "radchain/input_file.hpp"
#include "table_text.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string_view>

namespace radchain {
using namespace table_detail;

ShardSpec parse_shard(const std::string& text, const std::string& order) {
  ShardSpec shard;
  const auto slash = text.find('/');
  try {
    if (slash == std::string::npos) throw std::invalid_argument(text);
    shard.index = parse_count(text.substr(0, slash));
    shard.count = parse_count(text.substr(slash + 1));
  } catch (const std::invalid_argument&) {
    shard.index = 0;
  }
  if (shard.index < 1 || shard.index > shard.count)
    throw InputError(SourceLocation{"--shard", 0, 0}, "", text, "expected k/n with 1 <= k <= n, e.g. --shard 2/8");
  // Each shard is a file to merge: a count beyond this is a typo, and merge allocates a slot per shard.
  if (shard.count > max_shards)
    throw InputError(SourceLocation{"--shard", 0, 0}, "", text, fmt::format("at most {} shards", max_shards));
  if (order == "block") {
    shard.order = ShardSpec::Order::block;
  } else if (order == "round-robin") {
    shard.order = ShardSpec::Order::round_robin;
  } else {
    throw InputError(SourceLocation{"--shard-order", 0, 0}, "", order, "expected block or round-robin");
  }
  return shard;
}

std::string to_string(ShardSpec::Order order) { return order == ShardSpec::Order::block ? "block" : "round-robin"; }

PointRange shard_points(const ShardSpec& shard, std::size_t total) {
  if (!shard.active()) return PointRange{0, total, 1};
  const std::size_t k = shard.index - 1, n = shard.count;
  if (shard.order == ShardSpec::Order::block) {
    const std::size_t first = k * total / n, end = (k + 1) * total / n;
    return PointRange{first, end - first, 1};
  }
  return PointRange{k, total > k ? (total - k + n - 1) / n : 0, n};
}

std::string job_fingerprint(const std::string& description) {
  std::uint64_t hash = 14695981039346656037ull;  // FNV-1a, 64 bit
  for (unsigned char c : description) hash = (hash ^ c) * 1099511628211ull;
  return fmt::format("{:016x}", hash);
}

// --- merge -------------------------------------------------------------------------------------------------

namespace {

// Whether `text` is well-formed UTF-8 (no overlong forms, surrogates or code points beyond U+10FFFF).
bool valid_utf8(const std::string& text) {
  for (std::size_t i = 0; i < text.size();) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    const std::size_t n = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xe ? 3 : (c >> 3) == 0x1e ? 4 : 0;
    if (n == 0 || i + n > text.size()) return false;
    std::uint32_t code = n == 1 ? c : c & (0x7f >> n);
    for (std::size_t k = 1; k < n; ++k) {
      const unsigned char t = static_cast<unsigned char>(text[i + k]);
      if ((t >> 6) != 0x2) return false;
      code = (code << 6) | (t & 0x3f);
    }
    static constexpr std::uint32_t least[] = {0, 0, 0x80, 0x800, 0x10000};
    if (code < least[n] || code > 0x10ffff || (code >= 0xd800 && code <= 0xdfff)) return false;
    i += n;
  }
  return true;
}

// The column line as radchain writes it: printable UTF-8 names, each once. What is not could not be merged into
// every format: an .npy header is read as a Python literal (a line break or NUL ends it, invalid UTF-8 does not
// decode) and numpy refuses two fields of one name (npy_shard_fuzz).
std::string column_problem(const std::vector<std::string>& columns) {
  std::set<std::string_view> seen;
  for (std::size_t c = 0; c < columns.size(); ++c) {
    const std::string& name = columns[c];
    if (std::any_of(name.begin(), name.end(), [](char ch) { return static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f; }))
      return fmt::format("column {} of the column line has a control character", c + 2);
    if (!valid_utf8(name)) return fmt::format("column {} of the column line is not UTF-8", c + 2);
    if (!seen.insert(name).second) return fmt::format("the column line names \"{}\" twice", name);
  }
  return "";
}

struct ShardReader {
  std::string path;
  std::ifstream in;
  ShardSpec shard;
  std::map<std::string, std::string> fields;  // order, kind, points, format, job, types
  std::vector<std::string> columns;           // without "point"
  PointRange points;
  std::size_t next_index = 0;  // position in `points` of the next point expected
  std::size_t rows = 0;
  bool has_row = false;
  std::size_t row_point = 0;
  std::vector<std::string> row;
  int exit_code = 0;
  bool ended = false;

  InputError fail(const std::string& problem) const { return InputError(SourceLocation{path, 0, 0}, "merge", "", problem); }

  void open() {
    // Shards are as large as the job (no size cap), but a FIFO or a device is refused before it blocks.
    in = open_input_file(path, "shard file", UINTMAX_MAX);
    std::string header;
    if (!std::getline(in, header) || header.rfind(shard_magic, 0) != 0)
      throw fail("not a shard file (it does not start with \"# radchain shard\"; write shards with --shard k/n)");
    std::istringstream tokens(header.substr(std::string(shard_magic).size()));
    std::string token;
    tokens >> token;
    shard = parse_shard(token, "block");
    while (tokens >> token) {
      const auto eq = token.find('=');
      if (eq != std::string::npos) fields[token.substr(0, eq)] = token.substr(eq + 1);
    }
    for (const char* key : {"order", "kind", "points", "format", "job", "types"})
      if (!fields.count(key)) throw fail(fmt::format("shard header has no {}=", key));
    if (fields["order"] != "block" && fields["order"] != "round-robin")
      throw fail("shard header: order=" + fields["order"] + " is neither block nor round-robin");
    shard.order = fields["order"] == "round-robin" ? ShardSpec::Order::round_robin : ShardSpec::Order::block;
    if (fields["kind"] != "catalogue" && fields["kind"] != "sweep")
      throw fail("shard header: kind=" + fields["kind"] + " is neither catalogue nor sweep");
    if (fields["format"] != "text" && fields["format"] != "csv" && fields["format"] != "json" && fields["format"] != "npy")
      throw fail("shard header: format=" + fields["format"] + " is not text, csv, json or npy");
    if (fields["types"].find_first_not_of("nt") != std::string::npos)
      throw fail("shard header: types=" + fields["types"] + " has letters other than n and t");
    std::size_t total = 0;
    try {
      total = parse_count(fields["points"]);
    } catch (const std::invalid_argument&) {
      throw fail("shard header: points=" + fields["points"] + " is not a count");
    }
    points = shard_points(shard, total);
    std::string line;
    if (!std::getline(in, line) || !parse_csv_record(in, line, columns) || columns.empty() || columns.front() != "point")
      throw fail("no column line after the shard header");
    columns.erase(columns.begin());
    if (columns.size() != fields["types"].size()) throw fail("the column line does not match types=");
    if (const std::string problem = column_problem(columns); !problem.empty()) throw fail(problem);
    // A catalogue table has fixed columns (its summary reads them by position).
    if (fields["kind"] == "catalogue" && columns != catalogue_layout().columns)
      throw fail("the column line is not a catalogue's (" + join(catalogue_layout().columns, ",") + ")");
    advance();
  }

  void advance() {
    has_row = false;
    std::string line;
    if (!std::getline(in, line)) throw fail("incomplete: no \"# end\" line (was the job interrupted?)");
    if (line.rfind(trailer_magic, 0) == 0) {
      std::istringstream tokens(line.substr(std::string(trailer_magic).size()));
      std::string token;
      std::size_t recorded_rows = 0;
      while (tokens >> token) {
        try {
          if (token.rfind("rows=", 0) == 0) recorded_rows = parse_count(token.substr(5));
          if (token.rfind("exit=", 0) == 0) {
            const std::size_t code = parse_count(token.substr(5));
            if (code > 3) throw std::invalid_argument(token);  // radchain's exit codes are 0 to 3
            exit_code = static_cast<int>(code);
          }
        } catch (const std::invalid_argument&) {
          throw fail("bad \"# end\" line: " + line);
        }
      }
      if (recorded_rows != rows) throw fail(fmt::format("holds {} rows but its end line says {}", rows, recorded_rows));
      if (next_index != points.count)
        throw fail(fmt::format("incomplete: point {} of this shard has no row", points[next_index]));
      ended = true;
      return;
    }
    if (!parse_csv_record(in, line, row) || row.size() != columns.size() + 1)
      throw fail(fmt::format("row {}: expected {} cells", rows + 1, columns.size() + 1));
    try {
      row_point = parse_count(row.front());
    } catch (const std::invalid_argument&) {
      throw fail(fmt::format("row {}: point \"{}\" is not a count", rows + 1, row.front()));
    }
    row.erase(row.begin());
    // A numeric cell is a number as the job wrote it or "nan" (a failed point); a catalogue leaves a value it did
    // not compute empty. Anything else (a corrupted or hand-edited shard) would become a silent NaN in the merge.
    const std::string& types = fields.at("types");
    for (std::size_t c = 0; c < row.size(); ++c) {
      const std::string& cell = row[c];
      if (types[c] != 'n' || cell == "nan" || (cell.empty() && fields.at("kind") == "catalogue")) continue;
      double value = 0;
      const char* begin = cell.data() + (!cell.empty() && cell.front() == '+');  // a catalogue's signed delta
      const auto [end, error] = std::from_chars(begin, cell.data() + cell.size(), value);
      if (cell.empty() || error != std::errc() || end != cell.data() + cell.size() || !std::isfinite(value))
        throw fail(fmt::format("row {}: {} = \"{}\" is not a number (a finite decimal, or nan for a failed point)",
                               rows + 1, columns[c], cell));
    }
    // Rows come in point order: the next point of this shard, or (a catalogue: a file's rows) the current point
    // again. A sweep has one row per point: a repeated one would write more records than its header promises.
    const bool same = fields.at("kind") == "catalogue" && next_index > 0 && row_point == points[next_index - 1];
    if (!same) {
      if (next_index >= points.count || row_point != points[next_index])
        throw fail(fmt::format("row {}: point {} is not the next point of shard {}/{} ({})", rows + 1, row_point,
                               shard.index, shard.count,
                               next_index < points.count ? std::to_string(points[next_index]) : "none left"));
      ++next_index;
    }
    ++rows;
    has_row = true;
  }
};

}  // namespace

int merge_shards(const std::vector<std::string>& files, std::ostream& out, std::optional<TableFormat> format, bool binary_ok) {
  if (files.empty()) throw InputError(SourceLocation{"merge", 0, 0}, "", "", "no shard files given");
  auto open_all = [&] {
    std::vector<std::unique_ptr<ShardReader>> readers;
    for (const auto& file : files) {
      auto reader = std::make_unique<ShardReader>();
      reader->path = file;
      reader->open();
      readers.push_back(std::move(reader));
    }
    return readers;
  };
  // First pass: every file complete and in order, before a byte is written (a failed merge writes nothing).
  for (auto& r : open_all())
    while (!r->ended) r->advance();
  std::vector<std::unique_ptr<ShardReader>> readers = open_all();
  const ShardReader& first = *readers.front();
  const std::size_t count = first.shard.count;
  std::vector<const ShardReader*> by_index(count + 1, nullptr);
  for (const auto& r : readers) {
    for (const char* key : {"order", "kind", "points", "format", "job", "types"})
      if (r->fields.at(key) != first.fields.at(key))
        throw r->fail(fmt::format("belongs to another job than {} ({}={} there, {} here)", first.path, key,
                                  first.fields.at(key), r->fields.at(key)));
    if (r->shard.count != count || r->columns != first.columns)
      throw r->fail(fmt::format("belongs to another job than {} (shards of {} there, {} here)", first.path, count,
                                r->shard.count));
    if (by_index[r->shard.index])
      throw r->fail(fmt::format("shard {}/{} is given twice (also {})", r->shard.index, count, by_index[r->shard.index]->path));
    by_index[r->shard.index] = r.get();
  }
  for (std::size_t k = 1; k <= count; ++k)
    if (!by_index[k])
      throw InputError(SourceLocation{"merge", 0, 0}, "", "",
                       fmt::format("shard {}/{} is missing (given: {})", k, count, join(files)));

  TableLayout layout;
  layout.kind = first.fields.at("kind");
  layout.columns = first.columns;
  for (char t : first.fields.at("types")) layout.numeric.push_back(t == 'n');
  if (const TableLayout catalogue = catalogue_layout(); layout.columns == catalogue.columns) {  // as the unsharded table shows
    layout.text_digits = catalogue.text_digits;
    layout.text_hidden = catalogue.text_hidden;
    layout.text_width = catalogue.text_width;
  }
  const TableFormat job_format = parse_table_format(first.fields.at("format"));
  if (!binary_ok && format.value_or(job_format) == TableFormat::npy)
    throw InputError(SourceLocation{"merge", 0, 0}, "", "", "the shards are of an .npy job: give --out FILE.npy (or --format csv)");
  TableWriter writer(out, format.value_or(job_format), layout, parse_count(first.fields.at("points")));

  // A k-way merge on the point index: every point lives in exactly one shard, and each shard is in point order.
  int exit_code = 0;
  while (true) {
    ShardReader* next = nullptr;
    for (auto& r : readers)
      if (r->has_row && (!next || r->row_point < next->row_point)) next = r.get();
    if (!next) break;
    const std::size_t point = next->row_point;
    while (next->has_row && next->row_point == point) {
      writer.row(point, next->row);
      next->advance();
    }
  }
  for (auto& r : readers) {
    if (!r->ended) throw r->fail("rows after the end of the merge");
    exit_code = std::max(exit_code, r->exit_code);
  }
  writer.finish(exit_code);
  return exit_code;
}

}  // namespace radchain
