#pragma once
// The tabular output of the batch commands (catalogue, sweep), how a batch job is split into shards and how
// the shards are joined again.
//
// A job is a list of points (a catalogue: one sensor file per point; a sweep: one grid point per point). Every
// point writes one or more rows, always in point order, so the output does not depend on the thread count.
// `--shard k/n` runs a deterministic subset of the points (a contiguous block, or every n-th point) and writes a
// *shard file*: the job's CSV with a leading `point` column, framed by a header line that identifies the job
// and a trailer that proves the file is complete:
//
//   # radchain shard 2/4 order=block kind=sweep points=16 format=csv job=5c0f8e1d2a3b4c5d types=nnn
//   point,optics.aperture_cm,target.magnitude,detector.snr
//   4,19,16.12,5
//   ...
//   # end rows=4 exit=0
//
// merge_shards() checks that the files belong to one job and cover every point once, and writes exactly the
// bytes the unsharded job writes (text, CSV or JSON): cells are formatted once, by the job, and only copied.
#include <cstddef>
#include <functional>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace radchain {

enum class TableFormat { text, csv, json };
// "text", "csv", "json"; throws InputError otherwise.
TableFormat parse_table_format(const std::string& name);
std::string to_string(TableFormat format);
// The format a file name asks for: .csv, .json, .txt; nullopt for anything else.
std::optional<TableFormat> table_format_of_path(const std::string& path);

struct TableLayout {
  std::string kind;                  // the job that makes the table: "catalogue", "sweep"
  std::vector<std::string> columns;
  std::vector<bool> numeric;         // per column: right-aligned in text, bare numbers in JSON
};

// Which points of a job one shard runs.
struct ShardSpec {
  enum class Order { block, round_robin };
  std::size_t index = 0;  // 1-based; 0 = the whole job (no shard file)
  std::size_t count = 1;
  Order order = Order::block;
  bool active() const { return index != 0; }
};
// "2/8" with order "block" (contiguous) or "round-robin" (every n-th point); throws InputError.
ShardSpec parse_shard(const std::string& text, const std::string& order = "block");
std::string to_string(ShardSpec::Order order);

// The points of a job of `total` points that a shard runs: first, first + stride, ... (`count` of them).
struct PointRange {
  std::size_t first = 0, count = 0, stride = 1;
  std::size_t operator[](std::size_t i) const { return first + i * stride; }
};
PointRange shard_points(const ShardSpec& shard, std::size_t total);

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
  // Writes what follows the rows; `exit_code` is what the command returns (a shard file records it).
  void finish(int exit_code);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Joins shard files into the output the unsharded job writes, in `format` (default: the job's). Returns the
// job's exit code (the largest one the shards recorded). Throws InputError: not a shard file, shards of
// different jobs, a shard missing, given twice or incomplete.
int merge_shards(const std::vector<std::string>& files, std::ostream& out, std::optional<TableFormat> format = {});

// A cell for a number: "{:.10g}", "nan" for NaN.
std::string number_cell(double value);

// A job's fingerprint (64-bit FNV-1a, hex) of its description.
std::string job_fingerprint(const std::string& description);

// --- Parallel work -----------------------------------------------------------------------------------------
// Every parallel job runs on TBB's pool. A worker slot (< worker_slots()) identifies the thread running a
// chunk, so that each thread owns its Chain (load once per thread; a Chain is not thread-safe).
std::size_t worker_slots();
// Runs body(slot, begin, end) over [0, n) in chunks of about `grain`, on all cores (or --threads).
void parallel_chunks(std::size_t n, std::size_t grain,
                     const std::function<void(std::size_t slot, std::size_t begin, std::size_t end)>& body);
// Caps the threads of every later parallel job (0 = all cores), for --threads.
void limit_threads(std::size_t threads);
// The number of threads parallel jobs use.
std::size_t thread_count();

}  // namespace radchain
