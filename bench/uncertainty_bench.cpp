// 10^5 Monte-Carlo samples of the SBV, a limiting-magnitude solve at each, on all cores (target
// ≤ 1 s on 2 cores). Three inputs varied (transmittance, read noise, QE), as in docs/budget.md.
#include "radchain/batch/uncertainty.hpp"

#include "bench_common.hpp"

#include <benchmark/benchmark.h>

namespace {
using namespace radchain;

void BM_SbvUncertainty100kSamplesWithSolves_AllCores(benchmark::State& state) {
  UncertaintyOptions options;
  options.sensor_file = bench::sbv_sensor;
  options.vary = {"optics.transmittance=normal(0.56, 0.02)", "detector.read_noise=uniform(5 e-, 7 e-)",
                  "detector.qe=triangular(0.25, 0.27, 0.29)"};
  options.results = {"target.magnitude"};
  options.samples = 100000;
  for (auto _ : state) {
    const Uncertainty u = run_uncertainty(options);
    bench::keep(u.results.front().sd);
  }
}
BENCHMARK(BM_SbvUncertainty100kSamplesWithSolves_AllCores)->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();

}  // namespace
