// A million aperture values (15 cm .. 30 cm) for the SBV: forward evaluations and limiting-magnitude solves, one
// point at a time and in lanes (eight at once, what `radchain sweep` does), on one core and on all cores.
// Targets: ≤ 10 ms per million forward evaluations, ≤ 200 ms per million solves.
#include "radchain/batch/factored_grid.hpp"
#include "radchain/batch/shard.hpp"
#include "radchain/batch/table.hpp"
#include "radchain/batch/thread_pool.hpp"
#include "radchain/chain.hpp"
#include "radchain/batch/sweep.hpp"

#include "bench_common.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <ostream>
#include <streambuf>
#include <vector>

namespace {
using namespace radchain;

using bench::keep;

const std::string& sbv = bench::sbv_sensor;
constexpr std::size_t million = 1'000'000;

double aperture_at(std::size_t i) { return 0.15 + 0.15 * static_cast<double>(i) / static_cast<double>(million - 1); }

// Forward evaluations on one core: set the aperture, evaluate (every result), read the SNR.
void BM_MillionForwardEvaluations_OneCore(benchmark::State& state) {
  Chain chain = load_sensor(sbv);
  const ParameterRef aperture = chain.parameter("optics.aperture");
  const ResultId snr = *chain.results().find("detector.snr");
  chain.evaluate();
  for (auto _ : state) {
    double sum = 0;
    for (std::size_t i = 0; i < million; ++i) {
      chain.set(aperture, aperture_at(i));
      chain.evaluate();
      sum += chain.results().value(snr);
    }
    keep(sum);
  }
}
BENCHMARK(BM_MillionForwardEvaluations_OneCore)->Unit(benchmark::kMillisecond)->Iterations(2);

// The same in lanes (radchain/lanes.hpp): eight apertures per pass. Detail::full computes every result (each
// noise term's square root); Detail::essential what the SNR and the criteria need.
void million_lane_evaluations(benchmark::State& state, Detail detail) {
  Chain chain = load_sensor(sbv);
  const ParameterRef aperture = chain.parameter("optics.aperture");
  const ResultId snr = *chain.results().find("detector.snr");
  std::vector<double> apertures(million);
  for (std::size_t i = 0; i < million; ++i) apertures[i] = aperture_at(i);
  for (auto _ : state) {
    double sum = 0;
    for (std::size_t i = 0; i < million; i += lane_count) {
      chain.set_lanes(aperture, Eigen::Map<const Lanes>(apertures.data() + i));
      chain.evaluate_lanes(detail);
      sum += chain.lane_result(snr).sum();
    }
    keep(sum);
  }
}
void BM_MillionForwardEvaluations_Lanes_OneCore(benchmark::State& state) { million_lane_evaluations(state, Detail::full); }
BENCHMARK(BM_MillionForwardEvaluations_Lanes_OneCore)->Unit(benchmark::kMillisecond)->Iterations(5);
void BM_MillionForwardEvaluations_LanesEssential_OneCore(benchmark::State& state) {
  million_lane_evaluations(state, Detail::essential);
}
BENCHMARK(BM_MillionForwardEvaluations_LanesEssential_OneCore)->Unit(benchmark::kMillisecond)->Iterations(5);

// Essential lanes on all cores.
void BM_MillionForwardEvaluations_LanesEssential_AllCores(benchmark::State& state) {
  std::vector<std::unique_ptr<Chain>> chains(worker_slots());
  std::vector<double> apertures(million);
  for (std::size_t i = 0; i < million; ++i) apertures[i] = aperture_at(i);
  for (auto _ : state) {
    parallel_chunks(million, 4096, [&](std::size_t slot, std::size_t begin, std::size_t end) {
      if (!chains[slot]) chains[slot] = std::make_unique<Chain>(load_sensor(sbv));
      Chain& chain = *chains[slot];
      const ParameterRef aperture = chain.parameter("optics.aperture");
      const ResultId snr = *chain.results().find("detector.snr");
      double sum = 0;
      Lanes d;
      for (std::size_t i = begin; i < end; i += lane_count) {  // (TBB's chunks need not be multiples of 8)
        for (int k = 0; k < lane_count; ++k) d(k) = apertures[std::min(i + static_cast<std::size_t>(k), end - 1)];
        chain.set_lanes(aperture, d);
        chain.evaluate_lanes(Detail::essential);
        sum += chain.lane_result(snr).sum();
      }
      keep(sum);
    });
  }
  state.counters["threads"] = static_cast<double>(thread_count());
}
BENCHMARK(BM_MillionForwardEvaluations_LanesEssential_AllCores)->Unit(benchmark::kMillisecond)->Iterations(5)->UseRealTime();

// Forward evaluations on all cores: one Chain per worker thread.
void BM_MillionForwardEvaluations_AllCores(benchmark::State& state) {
  std::vector<std::unique_ptr<Chain>> chains(worker_slots());
  for (auto _ : state) {
    parallel_chunks(million, 4096, [&](std::size_t slot, std::size_t begin, std::size_t end) {
      if (!chains[slot]) chains[slot] = std::make_unique<Chain>(load_sensor(sbv));
      Chain& chain = *chains[slot];
      const ParameterRef aperture = chain.parameter("optics.aperture");
      const ResultId snr = *chain.results().find("detector.snr");
      double sum = 0;
      for (std::size_t i = begin; i < end; ++i) {
        chain.set(aperture, aperture_at(i));
        chain.evaluate();
        sum += chain.results().value(snr);
      }
      keep(sum);
    });
  }
  state.counters["threads"] = static_cast<double>(thread_count());
}
BENCHMARK(BM_MillionForwardEvaluations_AllCores)->Unit(benchmark::kMillisecond)->Iterations(2)->UseRealTime();

SweepOptions million_apertures() {
  SweepOptions options;
  options.sensor_file = sbv;
  options.axes = {{"optics.aperture", "15 cm:30 cm:1000000"}};
  options.results = {"target.magnitude"};
  return options;
}

// The physical reference: what a C++ programmer would write by hand for this one chain — Pan 2010
// eq. (11) in closed form over the apertures, with the chain's own photon integral and noise floor taken from one
// run (so only the per-point arithmetic is timed, as numpy_reference.py's vectorised() does). One core.
void BM_MillionLimitingMagnitudes_HandWrittenLoop(benchmark::State& state) {
  Chain chain = load_sensor(sbv);
  (void)chain.run();
  const double signal = chain.result("detector.signal_electrons"), noise = chain.result("detector.noise_electrons");
  const double m0 = chain.result("target.magnitude"), d0 = chain.result("optics.aperture");
  // At the solved limit S = T n: the electrons per unit flux ratio scale with D², the floor does not.
  const double threshold = signal / noise, floor = noise * noise - signal;
  const double t2 = threshold * threshold;
  const double required = 0.5 * (t2 + std::sqrt(t2 * t2 + 4 * t2 * floor));  // = signal (the root)
  const double electrons_per_ratio_d0 = signal / std::pow(10.0, -0.4 * m0);
  std::vector<double> out(million);
  for (auto _ : state) {
    for (std::size_t i = 0; i < million; ++i) {
      const double d = aperture_at(i) / d0;
      out[i] = -2.5 * std::log10(required / (electrons_per_ratio_d0 * d * d));
    }
    keep(out[million / 2]);
  }
  state.counters["m(15 cm)"] = -2.5 * std::log10(required / electrons_per_ratio_d0);
}
BENCHMARK(BM_MillionLimitingMagnitudes_HandWrittenLoop)->Unit(benchmark::kMillisecond);

// Solves on one core: a sweep point (unknown reset, the solve, the result read) a million times.
void BM_MillionSolves_OneCore(benchmark::State& state) {
  const Sweep sweep(million_apertures());
  SweepWorker worker(sweep);
  double out[2];
  for (auto _ : state) {
    for (std::size_t point = 0; point < million; ++point) worker.evaluate(point, out);
    keep(out[1]);
  }
}
BENCHMARK(BM_MillionSolves_OneCore)->Unit(benchmark::kMillisecond)->Iterations(1);

// A million points of `sweep` in groups of eight through `worker`, solved in lockstep on this thread (what
// `radchain sweep` does on each worker thread); the last column at `probe`.
double solve_in_groups(const Sweep& sweep, SweepWorker& worker, std::size_t probe) {
  const std::size_t columns = sweep.columns();
  std::vector<double> out(columns * lane_count);
  std::vector<char> ok(lane_count);
  std::size_t group[lane_count];
  double probed = 0;
  for (std::size_t point = 0; point < million; point += lane_count) {
    for (std::size_t k = 0; k < lane_count; ++k) group[k] = point + k;
    worker.evaluate_group(group, lane_count, out.data(), ok.data());
    if (point == probe - probe % lane_count) probed = out[(probe % lane_count) * columns + columns - 1];
  }
  keep(out[columns - 1]);
  return probed;
}

// The same in lanes: eight points per group, solved in lockstep (what `radchain sweep` does).
void BM_MillionSolves_Lanes_OneCore(benchmark::State& state) {
  const Sweep sweep(million_apertures());
  SweepWorker worker(sweep);
  for (auto _ : state) solve_in_groups(sweep, worker, 0);
}
BENCHMARK(BM_MillionSolves_Lanes_OneCore)->Unit(benchmark::kMillisecond)->Iterations(1);

// Solves on all cores: one SweepWorker (one Chain) per worker thread.
void BM_MillionSolves_AllCores(benchmark::State& state) {
  const Sweep sweep(million_apertures());
  std::vector<std::unique_ptr<SweepWorker>> workers(worker_slots());
  for (auto _ : state) {
    parallel_chunks(million, 1024, [&](std::size_t slot, std::size_t begin, std::size_t end) {
      if (!workers[slot]) workers[slot] = std::make_unique<SweepWorker>(sweep);
      double out[2];
      for (std::size_t point = begin; point < end; ++point) workers[slot]->evaluate(point, out);
      keep(out[1]);
    });
  }
  state.counters["threads"] = static_cast<double>(thread_count());
}
BENCHMARK(BM_MillionSolves_AllCores)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();

// The same in lanes on all cores.
void BM_MillionSolves_Lanes_AllCores(benchmark::State& state) {
  const Sweep sweep(million_apertures());
  std::vector<std::unique_ptr<SweepWorker>> workers(worker_slots());
  for (auto _ : state) {
    parallel_chunks(million, 1024, [&](std::size_t slot, std::size_t begin, std::size_t end) {
      if (!workers[slot]) workers[slot] = std::make_unique<SweepWorker>(sweep);
      std::vector<double> out(2 * lane_count);
      std::vector<char> ok(lane_count);
      std::size_t group[lane_count];
      for (std::size_t point = begin; point < end; point += lane_count) {
        const std::size_t count = std::min<std::size_t>(lane_count, end - point);
        for (std::size_t k = 0; k < count; ++k) group[k] = point + k;
        workers[slot]->evaluate_group(group, count, out.data(), ok.data());
      }
      keep(out[1]);
    });
  }
  state.counters["threads"] = static_cast<double>(thread_count());
}
BENCHMARK(BM_MillionSolves_Lanes_AllCores)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();

// The headline benchmark: 10⁶ limiting magnitudes over a 3-axis grid, aperture × QE × exposure (100 each), what
// `radchain sweep --set optics.aperture=15cm:30cm:100 --set detector.qe=0.2:0.8:100 --set
// detector.integration_time=0.1s:2s:100` computes; bench/numpy_reference.py times numpy's closed form of the same grid.
SweepOptions million_grid() {
  SweepOptions options;
  options.sensor_file = sbv;
  options.axes = {{"optics.aperture", "15 cm:30 cm:100"}, {"detector.qe", "0.2:0.8:100"}, {"detector.integration_time", "0.1 s:2 s:100"}};
  options.results = {"target.magnitude"};
  return options;
}
double grid_value(double from, double to, std::size_t i) { return from + (to - from) * static_cast<double>(i) / 99.0; }

void BM_MillionGridSolves_Lanes_OneCore(benchmark::State& state) {
  const Sweep sweep(million_grid());
  SweepWorker worker(sweep);
  double probed = 0;
  for (auto _ : state) probed = solve_in_groups(sweep, worker, 123456);
  state.counters["m(point 123456)"] = probed;
}
BENCHMARK(BM_MillionGridSolves_Lanes_OneCore)->Unit(benchmark::kMillisecond)->Iterations(1);

// A sweep's limiting magnitudes factored by axis (radchain/batch/factored_grid.hpp), what `radchain sweep` does for
// it: the plan (the chain along each axis — or, for a long axis that declares a power law, at its ends and quarters —
// and over the noise floor's sub-grid, the separability tests and the check against the per-point solve at ~70
// points) is made inside the timed loop, then every point is written as a sweep row (the axis values and the
// magnitude) into the block buffer `radchain sweep` formats from.
void factored_sweep(benchmark::State& state, const SweepOptions& options, std::size_t probe) {
  const Sweep sweep(options);
  SweepWorker worker(sweep);
  constexpr std::size_t block = 16384;
  const std::size_t columns = sweep.columns(), points = sweep.points();
  std::vector<double> out(block * columns);
  std::vector<char> ok(block);
  double probed = 0;
  std::size_t solved_alone = 0;
  for (auto _ : state) {
    std::string why_not;
    const std::optional<FactoredGrid> grid = FactoredGrid::plan(sweep, worker, why_not);
    if (!grid) {
      state.SkipWithError(("the grid does not factor: " + why_not).c_str());
      return;
    }
    solved_alone = 0;
    for (std::size_t first = 0; first < points; first += block) {
      const std::size_t count = std::min(block, points - first);
      grid->evaluate(first, count, 1, out.data(), ok.data());
      for (std::size_t k = 0; k < count; ++k)
        if (!ok[k]) ++solved_alone, worker.evaluate(first + k, &out[k * columns]);
      if (first <= probe && probe < first + count) probed = out[(probe - first) * columns + columns - 1];
    }
    keep(out[columns - 1]);
  }
  state.counters["m(probe)"] = probed;
  state.counters["solved alone"] = static_cast<double>(solved_alone);
}

// The 100 × 100 × 100 grid: the noise floor varies with the exposure alone (dark electrons), so the chain runs
// ~430 times for 10⁶ points.
void BM_MillionGridSolves_Factored_OneCore(benchmark::State& state) { factored_sweep(state, million_grid(), 123456); }
BENCHMARK(BM_MillionGridSolves_Factored_OneCore)->Unit(benchmark::kMillisecond);

// 10⁶ apertures, one axis: S ∝ D² from the law (a logarithm per aperture), the floor independent of D.
void BM_MillionSolves_Factored_OneCore(benchmark::State& state) { factored_sweep(state, million_apertures(), 0); }
BENCHMARK(BM_MillionSolves_Factored_OneCore)->Unit(benchmark::kMillisecond);

// The physical reference for the grid: Pan 2010 eq. (11) by hand. Per point the noise floor n² − S = dark rate × t
// + read² + quantisation (the SBV window is one pixel, no sky) and the electrons per unit flux ratio ∝ D² QE t,
// both from one run of the chain.
void BM_MillionGridLimitingMagnitudes_HandWrittenLoop(benchmark::State& state) {
  Chain chain = load_sensor(sbv);
  (void)chain.run();
  auto result = [&](const char* name) { return chain.result(name); };
  const double signal = result("detector.signal_electrons"), m0 = result("target.magnitude");
  const double d0 = result("optics.aperture"), t0 = result("detector.integration_time");
  const double qe0 = chain.parameter("detector.qe").value();
  const double dark_rate = result("detector.dark_electrons") / t0;
  const double constant_floor = std::pow(result("detector.read_noise"), 2) + std::pow(result("detector.quantisation_noise"), 2);
  const double threshold = result("criteria.detection.threshold"), t2 = threshold * threshold;
  const double electrons_per_ratio_0 = signal / std::pow(10.0, -0.4 * m0) / (d0 * d0 * qe0 * t0);
  std::vector<double> out(million);
  for (auto _ : state) {
    std::size_t i = 0;
    for (std::size_t a = 0; a < 100; ++a) {
      const double d = grid_value(0.15, 0.30, a);
      for (std::size_t q = 0; q < 100; ++q) {
        const double qe = grid_value(0.2, 0.8, q);
        for (std::size_t e = 0; e < 100; ++e, ++i) {
          const double t = grid_value(0.1, 2.0, e);
          const double floor = dark_rate * t + constant_floor;
          const double required = 0.5 * (t2 + std::sqrt(t2 * t2 + 4 * t2 * floor));
          out[i] = -2.5 * std::log10(required / (electrons_per_ratio_0 * d * d * qe * t));
        }
      }
    }
    keep(out[million / 2]);
  }
  state.counters["m(point 123456)"] = out[123456];
}
BENCHMARK(BM_MillionGridLimitingMagnitudes_HandWrittenLoop)->Unit(benchmark::kMillisecond);

// What `radchain sweep` does for a million points: the solves on all cores and the CSV (to a null stream).
class NullBuffer : public std::streambuf {
 protected:
  int overflow(int c) override { return c; }
  std::streamsize xsputn(const char*, std::streamsize n) override { return n; }
};

void BM_MillionSolves_SweepCsv_AllCores(benchmark::State& state) {
  Sweep sweep(million_apertures());
  for (auto _ : state) {
    NullBuffer buffer;
    std::ostream out(&buffer);
    TableWriter writer(out, TableFormat::csv, sweep.layout(), sweep.points());
    writer.finish(sweep.run(writer));
  }
}
BENCHMARK(BM_MillionSolves_SweepCsv_AllCores)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();

}  // namespace
