#pragma once
// Every parallel batch job runs on TBB's pool (TBB stays private to radchain::batch).
#include <cstddef>
#include <functional>

namespace radchain {

// A worker slot (< worker_slots()) identifies the thread running a
// chunk, so that each thread owns its Chain (load once per thread; a Chain is not thread-safe).
std::size_t worker_slots();
// Runs body(slot, begin, end) over [0, n) in chunks of about `grain`, on all cores (or --threads).
void parallel_chunks(std::size_t n, std::size_t grain,
                     const std::function<void(std::size_t slot, std::size_t begin, std::size_t end)>& body);
// Caps the threads of every later parallel job (0 = all cores), for --threads.
void limit_threads(std::size_t threads);
// The number of threads parallel jobs use.
std::size_t thread_count();

}  // namespace radchain
