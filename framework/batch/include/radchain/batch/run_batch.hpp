#pragma once
// The one way a batch job (catalogue, sweep) runs its points: on all cores, written in point order.
#include <cstddef>
#include <functional>

namespace radchain {

// Runs positions [0, count) of a job in blocks of at most `block` positions. For each block, `compute(slot, begin,
// end)` runs for sub-ranges of about `grain` positions on the thread pool (positions are job-wide; `slot`
// identifies the worker thread, so each thread can own its Chain), then `emit(position)` runs for every position of
// the block, in order, on the calling thread. Blocks bound the memory of long jobs; emitting in order makes the
// output independent of the thread count. Plugins are loaded once before the first block.
void run_batch(std::size_t count, std::size_t block, std::size_t grain,
               const std::function<void(std::size_t slot, std::size_t begin, std::size_t end)>& compute,
               const std::function<void(std::size_t position)>& emit);

}  // namespace radchain
