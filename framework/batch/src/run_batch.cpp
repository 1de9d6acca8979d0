#include "radchain/batch/run_batch.hpp"

#include "radchain/batch/catalogue.hpp"
#include "radchain/batch/thread_pool.hpp"

#include <algorithm>

namespace radchain {

void run_batch(std::size_t count, std::size_t block, std::size_t grain,
               const std::function<void(std::size_t slot, std::size_t begin, std::size_t end)>& compute,
               const std::function<void(std::size_t position)>& emit) {
  preload_plugins();  // workers then only read the host's tables
  block = std::max<std::size_t>(1, block);
  for (std::size_t base = 0; base < count; base += block) {
    const std::size_t n = std::min(block, count - base);
    parallel_chunks(n, grain, [&](std::size_t slot, std::size_t begin, std::size_t end) { compute(slot, base + begin, base + end); });
    for (std::size_t i = 0; i < n; ++i) emit(base + i);
  }
}

}  // namespace radchain
