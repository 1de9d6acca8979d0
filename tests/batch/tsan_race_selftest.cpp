// The ThreadSanitizer build's self-test (scripts/tsan-batch): a deliberate data race through radchain's batch pool
// must be reported (exit 66 under TSAN_OPTIONS=exitcode=66). If it is not, a clean TSan run of the batch tests
// would prove nothing — the pool's hand-overs would be invisible, as TBB's are to an uninstrumented libtbb.
// Two chunks on two threads, each waiting at a latch for the other before its unsynchronised write, so the writes
// come from two threads however the machine schedules them (one thread cannot take both chunks alone).
#include "radchain/batch/thread_pool.hpp"

#include <cstdio>
#include <latch>

int main() {
  long unsynchronised = 0;
  std::latch both_started(2);
  radchain::limit_threads(2);
  radchain::parallel_chunks(2, 1, [&](std::size_t, std::size_t, std::size_t) {
    both_started.arrive_and_wait();
    unsynchronised += 1;
  });
  std::printf("%ld\n", unsynchronised);
  return 0;
}
