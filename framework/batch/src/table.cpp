// Tables of the batch commands: text / CSV / JSON rendering, written row by row in point order.
#include "radchain/batch/table.hpp"

#include "radchain/batch/catalogue.hpp"
#include "radchain/batch/shard.hpp"
#include "radchain/error.hpp"
#include "table_text.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <iterator>
#include <bit>
#include <limits>
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
using namespace table_detail;

TableFormat parse_table_format(const std::string& name) {
  if (name == "text") return TableFormat::text;
  if (name == "csv") return TableFormat::csv;
  if (name == "json") return TableFormat::json;
  if (name == "npy") return TableFormat::npy;
  throw InputError(SourceLocation{"--format", 0, 0}, "", name, "expected text, csv, json or npy");
}

std::string to_string(TableFormat format) {
  switch (format) {
    case TableFormat::text: return "text";
    case TableFormat::csv: return "csv";
    case TableFormat::json: return "json";
    case TableFormat::npy: return "npy";
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
  if (ends_with(".npy")) return TableFormat::npy;
  return std::nullopt;
}

TableSummary::~TableSummary() = default;

std::unique_ptr<TableSummary> summary_for(const std::string& kind) {
  if (kind == "catalogue") return catalogue_summary();
  return nullptr;
}

TableLayout wide_text(TableLayout layout) {
  layout.text_hidden.clear();
  layout.text_width = 0;
  return layout;
}

std::string number_cell(double value) {
  if (std::isnan(value)) return "nan";
  return fmt::format("{:.10g}", value);
}

// --- .npy --------------------------------------------------------------------------------------------------

namespace {

static_assert(std::endian::native == std::endian::little, "the .npy writer stores the machine's doubles as '<f8'");

// A Python string literal for the header's dict.
std::string python_string(const std::string& text) {
  std::string out = "'";
  for (char c : text) {
    if (c == '\\' || c == '\'') out += '\\';
    out += c;
  }
  return out + "'";
}

// NumPy's .npy format (numpy.lib.format, NEP 1): magic "\x93NUMPY", version, the header length (little-endian
// uint16 in version 1.0; uint32 in 3.0, whose header is UTF-8), then a Python dict literal padded with spaces to a
// multiple of 64 bytes and ended by '\n', then the data. One record per row with one little-endian float64 field
// per column, so that `pandas.DataFrame(numpy.load(path))` has the table's column names.
std::string npy_header(const std::vector<std::string>& columns, std::size_t rows) {
  std::string descr;
  for (const auto& c : columns) descr += "(" + python_string(c) + ", '<f8'), ";
  std::string dict = "{'descr': [" + descr + "], 'fortran_order': False, 'shape': (" + std::to_string(rows) + ",), }";
  const bool ascii = std::all_of(dict.begin(), dict.end(), [](char c) { return static_cast<unsigned char>(c) < 0x80; });
  const bool v1 = ascii && dict.size() + 11 + 63 < 65536;
  const std::size_t preamble = v1 ? 10 : 12;
  dict.append((64 - (preamble + dict.size() + 1) % 64) % 64, ' ');
  dict += '\n';
  std::string header = "\x93NUMPY";
  header += static_cast<char>(v1 ? 1 : 3);
  header += '\0';
  const std::size_t length = dict.size();
  for (std::size_t b = 0; b < (v1 ? 2u : 4u); ++b) header += static_cast<char>((length >> (8 * b)) & 0xff);
  return header + dict;
}

}  // namespace

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
  if (w.format == TableFormat::npy) {
    if (std::find(w.layout.numeric.begin(), w.layout.numeric.end(), false) != w.layout.numeric.end())
      throw InputError(SourceLocation{"--format", 0, 0}, "", "npy",
                       fmt::format("a {} table has text columns; .npy holds numbers only (use csv or json)", w.layout.kind));
    w.out << npy_header(w.layout.columns, w.points);
  }
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
    case TableFormat::npy: {  // from cells written by number_cell() (a merge of shards): parsed back exactly
      std::vector<double> values(cells.size());
      for (std::size_t i = 0; i < cells.size(); ++i) {
        const std::string& cell = cells[i];
        // A leading '+' as the shard reader accepts it (a catalogue's signed delta): from_chars alone made it NaN.
        const char* first = cell.data() + (!cell.empty() && cell.front() == '+');
        const auto [end, error] = std::from_chars(first, cell.data() + cell.size(), values[i]);
        if (cell.empty() || error != std::errc() || end != cell.data() + cell.size())
          values[i] = std::numeric_limits<double>::quiet_NaN();
      }
      w.out.write(reinterpret_cast<const char*>(values.data()), static_cast<std::streamsize>(values.size() * sizeof(double)));
      break;
    }
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

std::string TableWriter::number(double value) const {
  if (impl_->format != TableFormat::npy) return number_cell(value);
  return std::isnan(value) ? "nan" : fmt::format("{}", value);
}

bool TableWriter::takes_lines() const {
  return impl_->format == TableFormat::csv && !impl_->shard.active() && !impl_->summary;
}

void TableWriter::csv_line(const double* values, std::size_t count, std::string& line) {
  line.clear();
  for (std::size_t i = 0; i < count; ++i) {
    if (i) line += ',';
    if (std::isnan(values[i])) line += "nan";  // as number_cell()
    else fmt::format_to(std::back_inserter(line), "{:.10g}", values[i]);
  }
  line += '\n';
}

void TableWriter::row_line(std::size_t, const std::string& line) {
  ++impl_->rows;
  impl_->out.write(line.data(), static_cast<std::streamsize>(line.size()));
}

bool TableWriter::takes_values() const { return impl_->format == TableFormat::npy && !impl_->shard.active(); }

void TableWriter::row_values(std::size_t point, const double* values) {
  Impl& w = *impl_;
  const std::size_t n = w.layout.columns.size();
  if (takes_values() && !w.summary) {
    ++w.rows;
    w.out.write(reinterpret_cast<const char*>(values), static_cast<std::streamsize>(n * sizeof(double)));
    return;
  }
  std::vector<std::string> cells(n);
  for (std::size_t i = 0; i < n; ++i) cells[i] = number(values[i]);
  row(point, cells);
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
  if (w.format == TableFormat::npy) {
    // The header promised w.points records: a shorter file would load as garbage, so it is an error, not a file.
    if (w.rows != w.points) throw std::logic_error(fmt::format(".npy: {} rows written of {}", w.rows, w.points));
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
    auto shown = [&](std::size_t i) { return !(i < w.layout.text_hidden.size() && w.layout.text_hidden[i]); };
    std::vector<std::size_t> width(n);
    for (std::size_t i = 0; i < n; ++i) width[i] = display_width(w.layout.columns[i]);
    for (auto& row : w.buffered)
      for (std::size_t i = 0; i < n; ++i) {
        if (i < w.layout.text_digits.size() && w.layout.text_digits[i] > 0 && !row[i].empty()) {
          double value = 0;
          const auto [end, error] = std::from_chars(row[i].data(), row[i].data() + row[i].size(), value);
          if (error == std::errc() && end == row[i].data() + row[i].size())
            row[i] = fmt::format("{:.{}g}", value, w.layout.text_digits[i]);
        }
        if (row[i].empty()) row[i] = "-";
        width[i] = std::max(width[i], display_width(row[i]));
      }
    // A width limit cuts the last column (a note, a source) to what the others leave, at least 10 columns of it.
    std::size_t last = n;
    for (std::size_t i = 0; i < n; ++i)
      if (shown(i)) last = i;
    if (w.layout.text_width > 0 && last < n) {
      std::size_t others = 0;
      for (std::size_t i = 0; i < last; ++i)
        if (shown(i)) others += width[i] + 2;
      const std::size_t room = std::max<std::size_t>(10, w.layout.text_width > others ? w.layout.text_width - others : 0);
      if (width[last] > room) {
        for (auto& row : w.buffered) row[last] = truncated(row[last], room);
        width[last] = room;
      }
    }
    auto line = [&](const std::vector<std::string>& cells) {
      std::string text;
      bool first = true;
      for (std::size_t i = 0; i < n; ++i) {
        if (!shown(i)) continue;
        if (!first) text += "  ";
        first = false;
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

void write_table(const TableData& table, TableWriter& writer, int exit_code) {
  std::vector<std::string> cells;
  for (std::size_t i = 0; i < table.rows.size(); ++i) {
    cells.clear();
    for (const TableCell& cell : table.rows[i])
      cells.push_back(std::holds_alternative<double>(cell) ? writer.number(std::get<double>(cell)) : std::get<std::string>(cell));
    writer.row(i, cells);
  }
  writer.finish(exit_code);
}

}  // namespace radchain
