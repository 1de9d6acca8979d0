// Tables of the batch commands: text / CSV / JSON rendering, shard files, merge, and the TBB pool they run on.
#include "radchain/shard.hpp"

#include "radchain/catalogue.hpp"
#include "radchain/error.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <map>
#include <mutex>
#include <ostream>
#include <sstream>
#include <stdexcept>

namespace radchain {
namespace {

constexpr const char* shard_magic = "# radchain shard ";
constexpr const char* trailer_magic = "# end ";

std::string csv_cell(const std::string& cell) {
  if (cell.find_first_of(",\"\n\r") == std::string::npos) return cell;
  std::string quoted = "\"";
  for (char c : cell) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

void write_csv_record(std::ostream& out, const std::vector<std::string>& cells, const std::string* first = nullptr) {
  std::string line;
  if (first) line = *first;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (first || i > 0) line += ',';
    line += csv_cell(cells[i]);
  }
  line += '\n';
  out << line;
}

// One CSV record starting with `line` (further lines are read while a quoted cell is open).
bool parse_csv_record(std::istream& in, std::string line, std::vector<std::string>& cells) {
  cells.clear();
  std::string cell;
  bool quoted = false;
  for (std::size_t i = 0;; ++i) {
    if (i == line.size()) {
      if (!quoted) break;
      std::string more;
      if (!std::getline(in, more)) return false;  // an open quote at the end of the file
      cell += '\n';
      line = std::move(more);
      i = static_cast<std::size_t>(-1);
      continue;
    }
    const char c = line[i];
    if (quoted) {
      if (c == '"') {
        if (i + 1 < line.size() && line[i + 1] == '"') {
          cell += '"';
          ++i;
        } else {
          quoted = false;
        }
      } else {
        cell += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      cells.push_back(std::move(cell));
      cell.clear();
    } else {
      cell += c;
    }
  }
  cells.push_back(std::move(cell));
  return true;
}

std::string json_string(const std::string& text) {
  return nlohmann::json(text).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

// A numeric cell as a JSON value: the number as written (without a leading '+'), null when empty or not finite.
std::string json_number(const std::string& cell) {
  std::string text = cell;
  if (!text.empty() && text.front() == '+') text.erase(0, 1);
  if (text.empty()) return "null";
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size()) return json_string(cell);
  if (!std::isfinite(v)) return "null";
  // JSON wants a digit before '.', and no leading zeros.
  if (text.front() == '.') text.insert(0, "0");
  if (text.size() > 1 && text[0] == '-' && text[1] == '.') text.insert(1, "0");
  return text;
}

// Display width of UTF-8 text (code points; every character the tables print is one column wide).
std::size_t display_width(const std::string& text) {
  std::size_t width = 0;
  for (unsigned char c : text)
    if ((c & 0xC0) != 0x80) ++width;
  return width;
}

std::string padded(const std::string& text, std::size_t width, bool right) {
  const std::size_t w = display_width(text);
  if (w >= width) return text;
  const std::string pad(width - w, ' ');
  return right ? pad + text : text + pad;
}

std::string types_text(const std::vector<bool>& numeric) {
  std::string types;
  for (bool n : numeric) types += n ? 'n' : 't';
  return types;
}

std::size_t parse_count(const std::string& text) {
  std::size_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || text.empty()) throw std::invalid_argument(text);
  return value;
}

}  // namespace

TableFormat parse_table_format(const std::string& name) {
  if (name == "text") return TableFormat::text;
  if (name == "csv") return TableFormat::csv;
  if (name == "json") return TableFormat::json;
  throw InputError(SourceLocation{"--format", 0, 0}, "", name, "expected text, csv or json");
}

std::string to_string(TableFormat format) {
  switch (format) {
    case TableFormat::text: return "text";
    case TableFormat::csv: return "csv";
    case TableFormat::json: return "json";
  }
  return "?";
}

std::optional<TableFormat> table_format_of_path(const std::string& path) {
  auto ends_with = [&](const std::string& suffix) {
    return path.size() >= suffix.size() && path.compare(path.size() - suffix.size(), suffix.size(), suffix) == 0;
  };
  if (ends_with(".csv")) return TableFormat::csv;
  if (ends_with(".json")) return TableFormat::json;
  if (ends_with(".txt")) return TableFormat::text;
  return std::nullopt;
}

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

TableSummary::~TableSummary() = default;

std::unique_ptr<TableSummary> summary_for(const std::string& kind) {
  if (kind == "catalogue") return catalogue_summary();
  return nullptr;
}

std::string number_cell(double value) {
  if (std::isnan(value)) return "nan";
  return fmt::format("{:.10g}", value);
}

std::string job_fingerprint(const std::string& description) {
  std::uint64_t hash = 14695981039346656037ull;  // FNV-1a, 64 bit
  for (unsigned char c : description) hash = (hash ^ c) * 1099511628211ull;
  return fmt::format("{:016x}", hash);
}

// --- TableWriter -------------------------------------------------------------------------------------------

struct TableWriter::Impl {
  std::ostream& out;
  TableFormat format;
  TableLayout layout;
  std::size_t points;
  ShardSpec shard;
  std::string job;
  std::unique_ptr<TableSummary> summary;
  std::vector<std::vector<std::string>> buffered;  // text
  std::size_t rows = 0;
  bool finished = false;
};

TableWriter::TableWriter(std::ostream& out, TableFormat format, TableLayout layout, std::size_t points, ShardSpec shard,
                         const std::string& job)
    : impl_(new Impl{out, format, std::move(layout), points, shard, job, nullptr, {}, 0, false}) {
  Impl& w = *impl_;
  if (w.layout.numeric.size() != w.layout.columns.size()) throw std::logic_error("TableLayout: numeric flags != columns");
  if (w.shard.active()) {
    w.out << fmt::format("{}{}/{} order={} kind={} points={} format={} job={} types={}\n", shard_magic, w.shard.index,
                         w.shard.count, to_string(w.shard.order), w.layout.kind, w.points, to_string(w.format),
                         job_fingerprint(job), types_text(w.layout.numeric));
    const std::string point = "point";
    write_csv_record(w.out, w.layout.columns, &point);
    return;
  }
  w.summary = summary_for(w.layout.kind);
  if (w.format == TableFormat::csv) write_csv_record(w.out, w.layout.columns);
  if (w.format == TableFormat::json) {
    std::string columns;
    for (const auto& c : w.layout.columns) columns += (columns.empty() ? "" : ", ") + json_string(c);
    w.out << "{\n  \"kind\": " << json_string(w.layout.kind) << ",\n  \"columns\": [" << columns << "],\n  \"rows\": [";
  }
}

TableWriter::~TableWriter() = default;

const TableLayout& TableWriter::layout() const { return impl_->layout; }

void TableWriter::row(std::size_t point, const std::vector<std::string>& cells) {
  Impl& w = *impl_;
  if (cells.size() != w.layout.columns.size())
    throw std::logic_error(fmt::format("table row of {} cells for {} columns", cells.size(), w.layout.columns.size()));
  if (w.summary) w.summary->row(point, cells);
  ++w.rows;
  if (w.shard.active()) {
    const std::string p = std::to_string(point);
    write_csv_record(w.out, cells, &p);
    return;
  }
  switch (w.format) {
    case TableFormat::csv: write_csv_record(w.out, cells); break;
    case TableFormat::text: w.buffered.push_back(cells); break;
    case TableFormat::json: {
      std::string line = w.rows == 1 ? "\n    {" : ",\n    {";
      for (std::size_t i = 0; i < cells.size(); ++i) {
        if (i) line += ", ";
        line += json_string(w.layout.columns[i]) + ": " + (w.layout.numeric[i] ? json_number(cells[i]) : json_string(cells[i]));
      }
      w.out << line << '}';
      break;
    }
  }
}

void TableWriter::finish(int exit_code) {
  Impl& w = *impl_;
  if (w.finished) return;
  w.finished = true;
  if (w.shard.active()) {
    w.out << fmt::format("{}rows={} exit={}\n", trailer_magic, w.rows, exit_code);
    w.out.flush();
    return;
  }
  const std::string footer = w.summary ? w.summary->text(w.points) : std::string();
  if (w.format == TableFormat::json) {
    w.out << (w.rows ? "\n  ],\n" : "],\n");
    if (!footer.empty()) w.out << "  \"summary\": " << json_string(footer) << ",\n";
    w.out << "  \"exit_code\": " << exit_code << "\n}\n";
  } else if (w.format == TableFormat::text) {
    const std::size_t n = w.layout.columns.size();
    std::vector<std::size_t> width(n);
    for (std::size_t i = 0; i < n; ++i) width[i] = display_width(w.layout.columns[i]);
    for (auto& row : w.buffered)
      for (std::size_t i = 0; i < n; ++i) {
        if (row[i].empty()) row[i] = "-";
        width[i] = std::max(width[i], display_width(row[i]));
      }
    auto line = [&](const std::vector<std::string>& cells) {
      std::string text;
      for (std::size_t i = 0; i < n; ++i) {
        if (i) text += "  ";
        text += padded(cells[i], width[i], w.layout.numeric[i]);
      }
      while (!text.empty() && text.back() == ' ') text.pop_back();
      w.out << text << '\n';
    };
    line(w.layout.columns);
    for (const auto& row : w.buffered) line(row);
    if (!footer.empty()) w.out << footer << '\n';
    w.buffered.clear();
  }
  w.out.flush();
}

// --- merge -------------------------------------------------------------------------------------------------

namespace {

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
    in.open(path);
    if (!in) throw fail("cannot be read (missing file or no permission)");
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
    shard.order = fields["order"] == "round-robin" ? ShardSpec::Order::round_robin : ShardSpec::Order::block;
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
          if (token.rfind("exit=", 0) == 0) exit_code = static_cast<int>(parse_count(token.substr(5)));
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
    // Rows come in point order: the current point again, or the next point of this shard.
    const bool same = next_index > 0 && row_point == points[next_index - 1];
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

int merge_shards(const std::vector<std::string>& files, std::ostream& out, std::optional<TableFormat> format) {
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
  const TableFormat job_format = parse_table_format(first.fields.at("format"));
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

// --- parallel ----------------------------------------------------------------------------------------------

namespace {
std::mutex& control_mutex() {
  static std::mutex m;
  return m;
}
std::unique_ptr<tbb::global_control>& control() {
  static std::unique_ptr<tbb::global_control> c;
  return c;
}
}  // namespace

std::size_t worker_slots() { return static_cast<std::size_t>(std::max(1, tbb::this_task_arena::max_concurrency())); }

void parallel_chunks(std::size_t n, std::size_t grain,
                     const std::function<void(std::size_t slot, std::size_t begin, std::size_t end)>& body) {
  if (n == 0) return;
  const std::size_t slots = worker_slots();
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, n, std::max<std::size_t>(1, grain)),
      [&](const tbb::blocked_range<std::size_t>& range) {
        const int index = tbb::this_task_arena::current_thread_index();
        if (index < 0 || static_cast<std::size_t>(index) >= slots)
          throw std::logic_error("parallel_chunks: a worker outside the arena's slots");
        body(static_cast<std::size_t>(index), range.begin(), range.end());
      },
      tbb::simple_partitioner());
}

void limit_threads(std::size_t threads) {
  std::lock_guard lock(control_mutex());
  control().reset();
  if (threads > 0)
    control() = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
}

std::size_t thread_count() {
  return tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
}

}  // namespace radchain
