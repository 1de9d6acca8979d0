// Tables of the batch commands: text / CSV / JSON rendering, written row by row in point order.
#include "radchain/batch/table.hpp"

#include "radchain/batch/catalogue.hpp"
#include "radchain/batch/shard.hpp"
#include "radchain/error.hpp"
#include "table_text.hpp"

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
using namespace table_detail;

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

TableSummary::~TableSummary() = default;

std::unique_ptr<TableSummary> summary_for(const std::string& kind) {
  if (kind == "catalogue") return catalogue_summary();
  return nullptr;
}

std::string number_cell(double value) {
  if (std::isnan(value)) return "nan";
  return fmt::format("{:.10g}", value);
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

}  // namespace radchain
