// Image simulation speed, one thread (docs/rendering.md). Run from the build tree (plugins next to it):
//   ./radchain_render_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// SpaceFrame: a 2048×2048 MSX SBV frame with 200 field stars and a target, Airy PSF (f/3, 27 um pixels, 0.6 um),
//   shot + dark + read noise, full well and the 12-bit ADC; the frame is rendered into an existing image (the
//   PSF stamps and the background law are prepared once, outside the loop). Goal: ≥ 20 frames/s.
// SpaceFrameSetup: what is prepared once (chain evaluations for 201 magnitudes, PSF stamps by FFT).
// EarthScene: the Kolobrodov camera over the built-in test scene (N×N map at 1.25 m → 5 m), diffraction and
//   element MTF by FFTW, NEE noise, 12-bit ADC; throughput in input megapixels per second.
#include "radchain/chain.hpp"
#include "radchain/imaging/render.hpp"

#include <benchmark/benchmark.h>

#include <string>

namespace {
using namespace radchain;
using namespace radchain::render;

struct Sensor {
  Chain chain;
  Report report;
  explicit Sensor(const std::string& name) : chain(load_sensor(std::string(RADCHAIN_SOURCE_DIR) + "/sensors/" + name)) {
    report = chain.run();
  }
};

SpaceFrameOptions sbv_frame() {
  SpaceFrameOptions o;
  o.width = o.height = 2048;
  o.stars.count = 200;
  o.stars.seed = 7;
  o.focal_length_m = 0.45;
  o.pixel_pitch_m = 27e-6;
  o.psf = PsfModel::airy;
  o.psf_wavelength_m = 0.6e-6;
  o.sky_electrons_per_pixel = 20.0;
  return o;
}

void SpaceFrame(benchmark::State& state) {
  Sensor sbv("msx-sbv.toml");
  const SpaceFrameRenderer renderer(space_frame_setup(sbv.chain, sbv.report, sbv_frame()));
  Image frame(2048, 2048);
  std::uint64_t seed = 1;
  for (auto _ : state) {
    renderer.render(seed++, frame);
    benchmark::DoNotOptimize(frame.pixels.data());
  }
  state.counters["frames/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["Mpixel/s"] = benchmark::Counter(static_cast<double>(state.iterations()) * 2048.0 * 2048.0 / 1e6, benchmark::Counter::kIsRate);
}
BENCHMARK(SpaceFrame)->Unit(benchmark::kMillisecond)->UseRealTime();

void SpaceFrameSetupAndRender(benchmark::State& state) {
  Sensor sbv("msx-sbv.toml");
  std::uint64_t seed = 1;
  for (auto _ : state) {
    const SpaceFrameRenderer renderer(space_frame_setup(sbv.chain, sbv.report, sbv_frame()));
    Image frame = renderer.render(seed++);
    benchmark::DoNotOptimize(frame.pixels.data());
  }
}
BENCHMARK(SpaceFrameSetupAndRender)->Unit(benchmark::kMillisecond)->UseRealTime();

void EarthScene(benchmark::State& state) {
  Sensor kolobrodov("kolobrodov-1996-ccd151-computed.toml");
  const auto n = static_cast<int>(state.range(0));
  TestSceneOptions scene;
  scene.size_px = n;
  const Image map = make_test_scene(scene);
  EarthSceneOptions o;
  o.input_sampling_m = scene.sampling_m;
  const EarthSceneSetup setup = earth_scene_setup(kolobrodov.chain, kolobrodov.report, o);
  std::uint64_t seed = 1;
  for (auto _ : state) {
    Image image = render_earth_scene(setup, map, seed++);
    benchmark::DoNotOptimize(image.pixels.data());
  }
  state.counters["input Mpixel/s"] = benchmark::Counter(static_cast<double>(state.iterations()) * n * n / 1e6, benchmark::Counter::kIsRate);
}
BENCHMARK(EarthScene)->Arg(1024)->Arg(4096)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
