// The TBB pool every parallel batch job runs on.
#include "radchain/batch/thread_pool.hpp"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <memory>
#include <mutex>
#include <stdexcept>

namespace radchain {

// --- parallel ----------------------------------------------------------------------------------------------

namespace {
std::mutex& control_mutex() {
  static std::mutex m;
  return m;
}
std::unique_ptr<tbb::global_control>& control() {
  static std::unique_ptr<tbb::global_control> c;
  return c;
}
}  // namespace

std::size_t worker_slots() { return static_cast<std::size_t>(std::max(1, tbb::this_task_arena::max_concurrency())); }

void parallel_chunks(std::size_t n, std::size_t grain,
                     const std::function<void(std::size_t slot, std::size_t begin, std::size_t end)>& body) {
  if (n == 0) return;
  const std::size_t slots = worker_slots();
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, n, std::max<std::size_t>(1, grain)),
      [&](const tbb::blocked_range<std::size_t>& range) {
        const int index = tbb::this_task_arena::current_thread_index();
        if (index < 0 || static_cast<std::size_t>(index) >= slots)
          throw std::logic_error("parallel_chunks: a worker outside the arena's slots");
        body(static_cast<std::size_t>(index), range.begin(), range.end());
      },
      tbb::simple_partitioner());
}

void limit_threads(std::size_t threads) {
  std::lock_guard lock(control_mutex());
  control().reset();
  if (threads > 0)
    control() = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
}

std::size_t thread_count() {
  return tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
}

}  // namespace radchain
