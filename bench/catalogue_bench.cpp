// A catalogue of 1,000 sensor files (the bundled sensors/, copied round-robin into a temporary folder) evaluated
// with their solves and [expected] checks. Target: ≤ 2 s wall on 2 cores.
#include "radchain/batch/shard.hpp"
#include "radchain/batch/table.hpp"
#include "radchain/batch/thread_pool.hpp"
#include "radchain/batch/catalogue.hpp"

#include "bench_common.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace {
using namespace radchain;

using bench::keep;
namespace fs = std::filesystem;

class ThousandFiles {
 public:
  ThousandFiles() : dir_(fs::temp_directory_path() / ("radchain_bench_catalogue_" + std::to_string(::getpid()))) {
    fs::create_directories(dir_);
    std::vector<std::string> texts;
    for (const auto& file : catalogue_files({RADCHAIN_SOURCE_DIR "/sensors"})) {
      std::ifstream in(file);
      std::ostringstream text;
      text << in.rdbuf();
      texts.push_back(text.str());
    }
    for (std::size_t i = 0; i < 1000; ++i) {
      char name[32];
      std::snprintf(name, sizeof name, "sensor-%04zu.toml", i);
      std::ofstream(dir_ / name) << "# copy " << i << "\n" << texts[i % texts.size()];
    }
    files_ = catalogue_files({dir_.string()});
  }
  ~ThousandFiles() {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  const std::vector<std::string>& files() const { return files_; }

 private:
  fs::path dir_;
  std::vector<std::string> files_;
};

const ThousandFiles& thousand_files() {
  static ThousandFiles files;
  return files;
}

void run(benchmark::State& state, std::size_t threads) {
  const auto& files = thousand_files().files();
  limit_threads(threads);
  for (auto _ : state) {
    std::ostringstream out;
    TableWriter writer(out, TableFormat::text, catalogue_layout(), files.size());
    writer.finish(run_catalogue(files, {}, writer));
    keep(out.str().size());
  }
  state.counters["files"] = static_cast<double>(files.size());
  state.counters["threads"] = static_cast<double>(thread_count());
  limit_threads(0);
}

void BM_Catalogue1000Files_AllCores(benchmark::State& state) { run(state, 0); }
BENCHMARK(BM_Catalogue1000Files_AllCores)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();

void BM_Catalogue1000Files_OneCore(benchmark::State& state) { run(state, 1); }
BENCHMARK(BM_Catalogue1000Files_OneCore)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();

}  // namespace
