// The ThreadSanitizer build's self-test (scripts/tsan-batch): a deliberate data race through radchain's batch pool
// must be reported (exit 66 under TSAN_OPTIONS=exitcode=66). If it is not, a clean TSan run of the batch tests
// would prove nothing — the pool's hand-overs would be invisible, as TBB's are to an uninstrumented libtbb.
#include "radchain/batch/thread_pool.hpp"

#include <cstdio>

int main() {
  long unsynchronised = 0;
  radchain::limit_threads(2);
  radchain::parallel_chunks(1000, 1, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) unsynchronised += 1;
  });
  std::printf("%ld\n", unsynchronised);
  return 0;
}
