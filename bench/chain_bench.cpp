// One sensor on one core (sensors/msx-sbv.toml, Pan 2010: limiting magnitude 15.5565 at SNR 5): the spectral phase,
// the limiting-magnitude solve, one forward evaluation. Targets and results: docs/performance.md.
#include "radchain/chain.hpp"
#include "radchain/batch/sweep.hpp"

#include "bench_common.hpp"

#include <benchmark/benchmark.h>

#include <cmath>

namespace {
using namespace radchain;

using bench::keep;

const std::string& sbv = bench::sbv_sensor;

void check_magnitude(benchmark::State& state, double magnitude) {
  if (!(std::abs(magnitude - 15.5565) < 5e-5)) state.SkipWithError("the SBV limiting magnitude is not 15.5565");
}

// Target ≤ 5 µs: one limiting magnitude including all spectral integration (load excluded). invalidate_spectra()
// re-runs every stage's prepare cold: the Sun's total and V(λ) integrals over the 1,697-point E-490 table and the
// detector's photon integral are all computed again (nothing is remembered across it).
void BM_SbvLimitingMagnitudeWithSpectralPhase(benchmark::State& state) {
  Chain chain = load_sensor(sbv);
  const ParameterRef magnitude = chain.parameter("target.magnitude");
  const double start = magnitude.value();
  std::vector<SolveOutcome> outcomes;
  for (auto _ : state) {
    chain.set(magnitude, start);
    chain.invalidate_spectra();
    chain.solve_all(outcomes);
    keep(outcomes.front().value_si);
  }
  check_magnitude(state, outcomes.front().value_si);
}
BENCHMARK(BM_SbvLimitingMagnitudeWithSpectralPhase);

// What a sweep over a spectral parameter pays per point: the detector's band edge moves, so the detector (and the
// criterion after it) re-prepare; the Sun's integrals are not recomputed (the incremental spectral phase).
void BM_SbvLimitingMagnitudeAfterBandChange(benchmark::State& state) {
  Chain chain = load_sensor(sbv);
  const ParameterRef magnitude = chain.parameter("target.magnitude"), band_max = chain.parameter("detector.band_max");
  const double start = magnitude.value();
  std::vector<SolveOutcome> outcomes;
  bool wide = false;
  for (auto _ : state) {
    chain.set(magnitude, start);
    chain.set(band_max, (wide = !wide) ? 0.9e-6 : 0.89e-6);
    chain.solve_all(outcomes);
    keep(outcomes.front().value_si);
  }
}
BENCHMARK(BM_SbvLimitingMagnitudeAfterBandChange);

// The same through Chain::run(), which also copies every result into a Report and checks [expected].
void BM_SbvRunWithSpectralPhase(benchmark::State& state) {
  Chain chain = load_sensor(sbv);
  const ParameterRef magnitude = chain.parameter("target.magnitude");
  const double start = magnitude.value();
  double solved = 0;
  for (auto _ : state) {
    chain.set(magnitude, start);
    chain.invalidate_spectra();
    const Report report = chain.run();
    solved = report.solves.front().value_si;
    keep(solved);
  }
  check_magnitude(state, solved);
}
BENCHMARK(BM_SbvRunWithSpectralPhase);

// The spectral phase alone (prepare of every stage, then one scalar evaluation).
void BM_SbvSpectralPhase(benchmark::State& state) {
  Chain chain = load_sensor(sbv);
  for (auto _ : state) {
    chain.invalidate_spectra();
    chain.evaluate();
  }
}
BENCHMARK(BM_SbvSpectralPhase);

// The solve alone (the spectral phase is cached): what one point of an aperture sweep costs.
void BM_SbvLimitingMagnitudeSolve(benchmark::State& state) {
  Chain chain = load_sensor(sbv);
  const ParameterRef magnitude = chain.parameter("target.magnitude");
  const double start = magnitude.value();
  std::vector<SolveOutcome> outcomes;
  for (auto _ : state) {
    chain.set(magnitude, start);
    chain.solve_all(outcomes);
    keep(outcomes.front().value_si);
  }
  check_magnitude(state, outcomes.front().value_si);
  state.counters["evaluations"] = outcomes.front().iterations;
}
BENCHMARK(BM_SbvLimitingMagnitudeSolve);

// One forward evaluation (the scalar phase of every stage).
void BM_SbvForwardEvaluation(benchmark::State& state) {
  Chain chain = load_sensor(sbv);
  const ParameterRef aperture = chain.parameter("optics.aperture");
  const ResultId snr = *chain.results().find("detector.snr");
  double d = 0.15;
  for (auto _ : state) {
    chain.set(aperture, d);
    d = d < 0.3 ? d + 1e-7 : 0.15;
    chain.evaluate();
    keep(chain.results().value(snr));
  }
}
BENCHMARK(BM_SbvForwardEvaluation);

// Loading the sensor file (parse, validate, plugins, the first spectral phase): what a catalogue pays per file.
void BM_SbvLoad(benchmark::State& state) {
  for (auto _ : state) {
    Chain chain = load_sensor(sbv);
    keep(chain.stages.size());
  }
}
BENCHMARK(BM_SbvLoad)->Unit(benchmark::kMicrosecond);

}  // namespace
