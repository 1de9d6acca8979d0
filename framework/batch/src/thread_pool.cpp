// The pool every parallel batch job runs on: TBB's; or, in the ThreadSanitizer build (RADCHAIN_STD_THREADS, set by
// -DRADCHAIN_TSAN=ON), plain std::threads. libtbb.so is not instrumented, so TSan cannot see the synchronisation
// inside TBB's scheduler and reports its hand-overs as races (blocked_range splits, a job's state read by a worker
// and released by the caller); with std::thread every hand-over is a pthread call TSan understands, and what it
// checks is radchain's own shared state — the part that can be wrong.
#include "radchain/batch/thread_pool.hpp"

#ifndef RADCHAIN_STD_THREADS
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>
#else
#include <atomic>
#include <exception>
#include <thread>
#include <vector>
#endif

#include <algorithm>
#include <memory>
#include <mutex>
#include <stdexcept>

namespace radchain {

#ifndef RADCHAIN_STD_THREADS
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

#else  // RADCHAIN_STD_THREADS

namespace {
std::atomic<std::size_t> thread_limit{0};  // 0: all cores
}

std::size_t thread_count() {
  const std::size_t limit = thread_limit.load();
  return limit > 0 ? limit : std::max<std::size_t>(1, std::thread::hardware_concurrency());
}

std::size_t worker_slots() { return thread_count(); }

void limit_threads(std::size_t threads) { thread_limit.store(threads); }

// Chunks of `grain` handed out by an atomic counter to thread_count() threads; slot = the thread's index. The first
// exception stops the hand-out and is rethrown after every thread has joined (as tbb::parallel_for does).
void parallel_chunks(std::size_t n, std::size_t grain,
                     const std::function<void(std::size_t slot, std::size_t begin, std::size_t end)>& body) {
  if (n == 0) return;
  grain = std::max<std::size_t>(1, grain);
  const std::size_t chunks = (n + grain - 1) / grain, slots = std::min(thread_count(), chunks);
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr first_error;
  std::mutex error_mutex;
  auto work = [&](std::size_t slot) {
    for (std::size_t k; !failed.load() && (k = next.fetch_add(1)) < chunks;) {
      try {
        body(slot, k * grain, std::min(n, (k + 1) * grain));
      } catch (...) {
        std::lock_guard lock(error_mutex);
        if (!first_error) first_error = std::current_exception();
        failed.store(true);
      }
    }
  };
  std::vector<std::thread> threads;
  for (std::size_t slot = 1; slot < slots; ++slot) threads.emplace_back(work, slot);
  work(0);
  for (auto& t : threads) t.join();
  if (first_error) std::rethrow_exception(first_error);
}

#endif

}  // namespace radchain
