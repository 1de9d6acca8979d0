// The C++ side of bench/python_sweep.py: the sweep Session.sweep() runs, called from C++ (PointsEvaluator,
// radchain/batch/points.hpp), timed the same way: a warm-up run (worker chains built), then the median of
// `repeat` runs of check + output allocation (uninitialised) + run, wall clock, all cores.
//   radchain_points_bench SENSOR POINTS REPEAT solve|forward
// prints one JSON line: {"mode": ..., "points": ..., "median_s": ..., "runs_s": [...], "threads": ...}.
#include "radchain/batch/points.hpp"
#include "radchain/batch/thread_pool.hpp"
#include "radchain/error.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  using namespace radchain;
  if (argc != 5) {
    std::fprintf(stderr, "usage: %s SENSOR POINTS REPEAT solve|forward\n", argv[0]);
    return 2;
  }
  const std::string sensor = argv[1], mode = argv[4];
  const auto points = static_cast<std::size_t>(std::atof(argv[2]));
  const int repeat = std::atoi(argv[3]);
  try {
    PointsJob job;
    job.make_chain = [sensor](Solving solving) { return load_sensor(sensor, {}, solving); };
    job.parameters = {"optics.aperture"};
    job.results = {mode == "solve" ? "target.magnitude" : "detector.snr"};
    job.no_solve = mode != "solve";
    PointsEvaluator evaluator(std::move(job));
    // The Python benchmark's values: numpy.linspace(0.15, 0.30, points).
    std::vector<double> apertures(points);
    for (std::size_t i = 0; i < points; ++i)
      apertures[i] = points == 1 ? 0.15 : 0.15 + (0.30 - 0.15) * static_cast<double>(i) / static_cast<double>(points - 1);
    const double* values[] = {apertures.data()};
    std::vector<double> runs;
    double checksum = 0;
    for (int r = -1; r < repeat; ++r) {
      const auto start = std::chrono::steady_clock::now();
      evaluator.check(values, points);
      // Uninitialised, as the binding's numpy arrays are (no single-threaded zero fill before the parallel run).
      std::unique_ptr<double[]> out(new double[points * evaluator.results().size()]);
      std::unique_ptr<char[]> ok(new char[points]);
      evaluator.run(values, points, out.get(), ok.get());
      const auto stop = std::chrono::steady_clock::now();
      checksum += out[points / 2];
      if (r >= 0) runs.push_back(std::chrono::duration<double>(stop - start).count());
    }
    std::vector<double> sorted = runs;
    std::sort(sorted.begin(), sorted.end());
    std::printf("{\"mode\": \"%s\", \"points\": %zu, \"median_s\": %.6f, \"runs_s\": [", mode.c_str(), points,
                sorted[sorted.size() / 2]);
    for (std::size_t i = 0; i < runs.size(); ++i) std::printf("%s%.6f", i ? ", " : "", runs[i]);
    std::printf("], \"threads\": %zu, \"checksum\": %.17g}\n", thread_count(), checksum);
  } catch (const InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  return 0;
}
