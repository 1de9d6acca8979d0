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
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace radchain {

enum class TableFormat;

// Which points of a job one shard runs.
struct ShardSpec {
  enum class Order { block, round_robin };
  std::size_t index = 0;  // 1-based; 0 = the whole job (no shard file)
  std::size_t count = 1;
  Order order = Order::block;
  bool active() const { return index != 0; }
};
inline constexpr std::size_t max_shards = 100000;
// "2/8" with order "block" (contiguous) or "round-robin" (every n-th point); throws InputError.
ShardSpec parse_shard(const std::string& text, const std::string& order = "block");
std::string to_string(ShardSpec::Order order);

// The points of a job of `total` points that a shard runs: first, first + stride, ... (`count` of them).
struct PointRange {
  std::size_t first = 0, count = 0, stride = 1;
  std::size_t operator[](std::size_t i) const { return first + i * stride; }
};
PointRange shard_points(const ShardSpec& shard, std::size_t total);

// Joins shard files into the output the unsharded job writes, in `format` (default: the job's). Returns the
// job's exit code (the largest one the shards recorded). Throws InputError: not a shard file, shards of
// different jobs, a shard missing, given twice or incomplete.
// binary_ok = false: a job whose format is .npy (format not given) is refused rather than written to `out` (a terminal).
int merge_shards(const std::vector<std::string>& files, std::ostream& out, std::optional<TableFormat> format = {},
                 bool binary_ok = true);

// A job's fingerprint (64-bit FNV-1a, hex) of its description.
std::string job_fingerprint(const std::string& description);

}  // namespace radchain
