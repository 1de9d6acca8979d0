#pragma once
// `radchain sweep`: one sensor file evaluated over a grid of parameter values, its solves re-run at every
// point. Each axis is `--set key=from:to:steps` ("optics.aperture=15 cm:30 cm:16": 16 values from 0.15 m to
// 0.30 m); several axes make a grid, the first axis outermost. Values are spaced evenly in the unit the range is
// written in (so "15 cm:30 cm:16" gives exactly the values `--set optics.aperture="20 cm"` gives) and converted
// to SI once.
//
// Every worker thread owns a Chain loaded once from the file; a point changes parameters through Chain::set()
// and re-runs what they affect: the scalar phase from the changed stage on, the spectral phase only for a
// spectral parameter.
// Before each point the solved unknowns go back to their values in the file, so a point's result does not
// depend on which points the thread ran before it: the output is the same for any thread count or shard.
#include "radchain/chain.hpp"
#include "radchain/batch/point_engine.hpp"
#include "radchain/batch/table.hpp"

#include <array>
#include <atomic>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace radchain {

struct SweepAxis {
  std::string key;            // "optics.aperture"
  std::string range;          // as written: "15 cm:30 cm:16"
  double from = 0, to = 0;    // in `unit`
  std::size_t steps = 1;
  std::string unit;           // the unit the range is written in ("" for plain numbers)
  std::string si_unit;        // the parameter's SI unit ("1" for plain numbers)
  double to_si = 1;           // value_si = value × to_si (units::to_si)
  double from_si = 0, to_si_value = 0;  // the ends in SI, read from their text as a file's value is
  double value(std::size_t i) const;  // in `unit`; the last value is `to` exactly
  double value_si(std::size_t i) const;  // units::to_si: the same bits as the value written in a file
};

// `--set` values: "from:to:steps" is a range (any ':' makes it one), anything else a fixed value.
bool is_sweep_range(const std::string& value);

// Parses "from:to:steps" for a numeric parameter of `chain`. Throws InputError (one line) for a malformed range,
// a missing or wrong unit, steps that are not a whole number ≥ 1, values outside the parameter's accepted range,
// a non-integer value for an integer parameter, a parameter that is not numeric or that a [[solve]] determines.
SweepAxis parse_sweep_axis(Chain& chain, const std::string& key, const std::string& range);

struct SweepOptions {
  std::string sensor_file;
  std::vector<Override> overrides;                        // fixed values: --set key=value
  std::vector<std::pair<std::string, std::string>> axes;  // --set key=from:to:steps, outermost first
  std::vector<std::string> results;                       // result columns; empty: every result
  SolverChoice solver = SolverChoice::automatic;          // --solver
  bool no_solve = false;                                  // --no-solve: forward only at every point (a solved unknown may be an axis)
  ShardSpec shard;
  std::atomic<std::size_t>* progress = nullptr;           // counts finished points
  // A grid of more than large_points is refused unless allow_large (--allow-large): hours of work and gigabytes of
  // output should be asked for, not started by a typo. Above max_points it is refused outright.
  bool allow_large = false;
  // Columns in SI, named by the bare key or result (Python's radchain.grid and radchain.dask.sweep, whose units are
  // the DataFrame's attrs, as Session.sweep's are); false: in the units written and displayed, with the unit in the
  // column's name (`radchain sweep`: "optics.aperture_cm").
  bool si_columns = false;
  static constexpr double large_points = 1e8;
  static constexpr double max_points = 1e10;
};

class Sweep {
 public:
  // Loads the sensor once to check the axes and the result names. Throws InputError.
  explicit Sweep(SweepOptions options);

  const SweepOptions& options() const { return options_; }
  const std::vector<SweepAxis>& axes() const { return axes_; }
  const std::vector<std::string>& results() const { return results_; }  // names of the result columns
  const std::vector<std::string>& result_units() const { return units_; }  // their display units
  // Every column's unit as written to it: the axes' and results' units, SI ones with si_columns.
  std::vector<std::string> column_units() const;
  std::size_t points() const { return points_; }                          // the whole grid
  std::size_t columns() const { return axes_.size() + results_.size(); }
  // Columns: each axis as "<key>_<unit>", then each result as "<name>_<display unit>" (no suffix for "1"),
  // the convention of the spectra/ CSV headers; with si_columns the bare names.
  TableLayout layout() const;
  std::string job() const;  // what identifies the job for merge (file, overrides, axes, results)
  // Index along each axis of a grid point (the last axis varies fastest).
  std::vector<std::size_t> indices(std::size_t point) const;

  // Runs the shard's points on all cores and writes one row per point in point order. `observer` sees each
  // point's values (axes in their units, then results in display units) in point order. Returns 1 if a solve
  // failed at some point (its unknown's cell is nan; `failure` says where and why), else 0.
  int run(TableWriter& writer, std::string* failure = nullptr,
          const std::function<void(std::size_t point, const double* values)>& observer = {});
  // How the last run() solved its points: "closed form factored over the grid: …" (radchain/batch/factored_grid.hpp),
  // or "per point: <why the grid does not factor>".
  const std::string& method() const { return method_; }

 private:
  SweepOptions options_;
  std::vector<SweepAxis> axes_;
  std::vector<std::string> results_, units_, si_units_;
  std::size_t points_ = 1;
  std::string method_;
};

// One worker's point engine (load_sensor once, radchain/batch/point_engine.hpp), fed the grid's points.
class SweepWorker {
 public:
  explicit SweepWorker(const Sweep& sweep);
  // Evaluates a grid point into out[0 .. columns): axes in their units, results in display units. false when
  // a solve failed (failure() says why; the unknown's value is nan).
  bool evaluate(std::size_t point, double* out);
  const std::string& failure() const { return engine_.failure(0); }
  // Points points[0 .. count) (count ≤ lane_count) into consecutive rows of out; ok[k] false where a solve failed
  // (failure_of(k) says why). Each point's row is the same whichever points share its group.
  void evaluate_group(const std::size_t* points, std::size_t count, double* out, char* ok);
  const std::string& failure_of(std::size_t k) const { return engine_.failure(k); }
  Chain& chain() { return engine_.chain(); }

 private:
  // The indices of `point` along each axis into index_, and each axis's value into the row (in its unit) and
  // values_[a](lane) (SI).
  void locate(std::size_t point);
  void place(double* row, int lane);
  const Sweep& sweep_;
  PointEngine engine_;
  const double* rows_ = nullptr;  // the current call's first row (its axis values name a point in messages)
  std::vector<std::size_t> index_;
  // Each axis's value at the step it had last (as written and in SI): an outer axis keeps its step for many points,
  // and the SI value is read from text (units::to_si), the file's rule.
  struct AxisValue {
    std::size_t step = SIZE_MAX;
    double value = 0, value_si = 0;
  };
  std::vector<AxisValue> axis_values_;
  const AxisValue& axis_value(std::size_t axis);  // at index_[axis]
  std::vector<Lanes> values_;  // each axis's value per lane (kept: no allocation per group)
  std::vector<double> scalar_;  // each axis's value at one point
};

}  // namespace radchain
