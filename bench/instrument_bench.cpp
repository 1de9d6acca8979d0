// Real instruments' trade grids, what survey and EO analysts sweep: `radchain sweep` as the command runs it (the
// sweep's own method choice, rows formatted into an .npy stream that is thrown away), on one core.
// bench/instrument_reference.py times numpy doing the same physics on the same grids and prints the ratios:
//   /usr/bin/python3 bench/instrument_reference.py --bench out/release/radchain_bench
// Grids (10⁶ points each unless said):
//   Rubin r m5 (sensors/rubin-lsst-r-m5.toml): airmass × exposure × sky brightness, 100 each; the seeing at the
//     zenith × exposure × sky brightness, 100 each (the PSF's n_eff changes with the outer axis: the site scales the
//     seeing by X^0.6, so the first grid's PSF changes with the airmass too).
//   Sentinel-2A MSI B4 (sensors/sentinel-2a-msi-b4.toml, emva1288 + GIQE): detector.snr over reflectance × sun
//     zenith × roll (100 × 100 × 100); NIIRS over aperture × roll (100 × 100: the MTF budget changes with the
//     aperture, so a point costs the GIQE's edge-response integrals whenever it does).
// The spectral axis goes outermost: a spectral parameter re-runs the spectral phase when it changes.
#include "radchain/batch/sweep.hpp"
#include "radchain/batch/table.hpp"
#include "radchain/batch/thread_pool.hpp"

#include "bench_common.hpp"

#include <benchmark/benchmark.h>

#include <ostream>
#include <streambuf>
#include <string>
#include <utility>
#include <vector>

namespace {
using namespace radchain;

const std::string rubin = RADCHAIN_SOURCE_DIR "/sensors/rubin-lsst-r-m5.toml";
const std::string sentinel = RADCHAIN_SOURCE_DIR "/sensors/sentinel-2a-msi-b4.toml";

class NullBuffer : public std::streambuf {
 protected:
  int overflow(int c) override { return c; }
  std::streamsize xsputn(const char*, std::streamsize n) override { return n; }
};

// One `radchain sweep … --out grid.npy --threads 1`, the output discarded; the sweep's method as a label.
void sweep_one_core(benchmark::State& state, const std::string& file,
                    std::vector<std::pair<std::string, std::string>> axes, std::vector<std::string> results) {
  SweepOptions options;
  options.sensor_file = file;
  options.axes = std::move(axes);
  options.results = std::move(results);
  limit_threads(1);
  Sweep sweep(options);
  for (auto _ : state) {
    NullBuffer buffer;
    std::ostream out(&buffer);
    TableWriter writer(out, TableFormat::npy, sweep.layout(), sweep.points());
    writer.finish(sweep.run(writer));
  }
  limit_threads(0);
  state.counters["points"] = static_cast<double>(sweep.points());
  state.counters["ns/point"] = benchmark::Counter(static_cast<double>(sweep.points()),
                                                  benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.SetLabel(sweep.method());
}

void BM_RubinM5_AirmassExposureSky_OneCore(benchmark::State& state) {
  sweep_one_core(state, rubin,
                 {{"atmosphere.airmass", "1:2:100"}, {"detector.integration_time", "5 s:60 s:100"},
                  {"atmosphere.sky_brightness", "19:22:100"}},
                 {"target.magnitude"});
}
BENCHMARK(BM_RubinM5_AirmassExposureSky_OneCore)->Unit(benchmark::kMillisecond)->Iterations(1);

void BM_RubinM5_SeeingExposureSky_OneCore(benchmark::State& state) {
  sweep_one_core(state, rubin,
                 {{"atmosphere.seeing", "0.5 arcsec:1.5 arcsec:100"}, {"detector.integration_time", "5 s:60 s:100"},
                  {"atmosphere.sky_brightness", "19:22:100"}},
                 {"target.magnitude"});
}
BENCHMARK(BM_RubinM5_SeeingExposureSky_OneCore)->Unit(benchmark::kMillisecond)->Iterations(1);

void BM_Sentinel2Snr_ReflectanceSunRoll_OneCore(benchmark::State& state) {
  sweep_one_core(state, sentinel,
                 {{"platform.roll", "0 deg:20 deg:100"}, {"target.solar_zenith", "20 deg:70 deg:100"},
                  {"target.reflectance", "0.02:0.6:100"}},
                 {"detector.snr"});
}
BENCHMARK(BM_Sentinel2Snr_ReflectanceSunRoll_OneCore)->Unit(benchmark::kMillisecond)->Iterations(1);

void BM_Sentinel2Niirs_ApertureRoll_OneCore(benchmark::State& state) {
  sweep_one_core(state, sentinel, {{"optics.aperture", "10 cm:20 cm:100"}, {"platform.roll", "0 deg:20 deg:100"}},
                 {"criteria.iq.niirs"});
}
BENCHMARK(BM_Sentinel2Niirs_ApertureRoll_OneCore)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
