#pragma once
// The tabular output of the batch commands (catalogue, sweep, merge): rows in point order, so that the output
// does not depend on the thread count, rendered as aligned text, CSV, JSON or NumPy .npy (numbers only). With an active shard
// (radchain/batch/shard.hpp) the writer writes a shard file instead.
#include "radchain/batch/shard.hpp"

#include <cstddef>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace radchain {

enum class TableFormat { text, csv, json, npy };
// "text", "csv", "json", "npy"; throws InputError otherwise.
TableFormat parse_table_format(const std::string& name);
std::string to_string(TableFormat format);
// The format a file name asks for: .csv, .json, .txt, .npy; nullopt for anything else.
std::optional<TableFormat> table_format_of_path(const std::string& path);

struct TableLayout {
  std::string kind;                  // the job that makes the table: "catalogue", "sweep"
  std::vector<std::string> columns;
  std::vector<bool> numeric;         // per column: right-aligned in text, bare numbers in JSON
  // Per column (or empty: none): significant digits a cell is shown with in text, where the cell itself holds the
  // number to the last bit for CSV, JSON and shards (0: as the cell is).
  std::vector<int> text_digits = {};
  // The text table a person reads (--wide: everything, as CSV and JSON have it): columns left out of it, and its
  // width, to which the last column is cut with "…" (0: no limit).
  std::vector<bool> text_hidden = {};
  std::size_t text_width = 0;
};
// The layout with every column in the text table and no width limit (--wide).
TableLayout wide_text(TableLayout layout);

// Footer of a table (text: a last line; JSON: "summary"), computed from the rows, so that a merged table gets
// the same footer as the unsharded one.
class TableSummary {
 public:
  virtual ~TableSummary();
  virtual void row(std::size_t point, const std::vector<std::string>& cells) = 0;
  virtual std::string text(std::size_t points) const = 0;  // "" = no footer
};
// The summary of a kind of table (catalogue: files and checks), or nullptr.
std::unique_ptr<TableSummary> summary_for(const std::string& kind);

// Writes rows as they come (text is buffered: its columns are aligned over all rows).
class TableWriter {
 public:
  // `points` is the whole job's count; `job` describes the job (command, inputs, options: not the shard), so
  // that merge refuses shards of different jobs. With an active shard the writer writes a shard file.
  TableWriter(std::ostream& out, TableFormat format, TableLayout layout, std::size_t points, ShardSpec shard = {},
              const std::string& job = {});
  ~TableWriter();
  TableWriter(const TableWriter&) = delete;
  TableWriter& operator=(const TableWriter&) = delete;

  const TableLayout& layout() const;
  void row(std::size_t point, const std::vector<std::string>& cells);
  // A row of an all-numeric table as numbers: .npy stores them as they are; the other formats format them
  // (number_cell). takes_values(): the writer would only parse formatted cells back (npy, not a shard).
  void row_values(std::size_t point, const double* values);
  bool takes_values() const;
  // A number as a cell of this table: number_cell(), or for .npy (a shard of an .npy job) the shortest text that
  // reads back to the same double, so that merged shards give the bytes of the unsharded file.
  std::string number(double value) const;
  // CSV rows of numbers need no quoting: takes_lines() says the writer would only join the cells with commas (CSV,
  // not a shard, no summary), so worker threads may format whole rows (csv_line) and row_line() writes them.
  bool takes_lines() const;
  static void csv_line(const double* values, std::size_t count, std::string& line);  // number_cell()s, ',', '\n'
  void row_line(std::size_t point, const std::string& line);
  // Writes what follows the rows; `exit_code` is what the command returns (a shard file records it).
  void finish(int exit_code);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// A cell for a number: "{:.10g}", "nan" for NaN.
std::string number_cell(double value);

// A table held in memory with its numbers as doubles, to the last bit: what a batch function returns, so that
// Python binds the numbers themselves and the command line writes them in any format through a TableWriter.
// A cell of a numeric column (layout.numeric) is a double, of the others a text.
using TableCell = std::variant<double, std::string>;
struct TableData {
  TableLayout layout;
  std::vector<std::vector<TableCell>> rows;
};
// Every row into `writer` (numbers as writer.number(), so .npy and shards keep every bit), then finish(exit_code).
void write_table(const TableData& table, TableWriter& writer, int exit_code = 0);

}  // namespace radchain
