// Concurrency: catalogue and sweep outputs are byte for byte the same for 1, 2 and 8 threads, in every
// format (the rows are emitted in point order whatever thread computed them).
#include "cli_helpers.hpp"

#include <gtest/gtest.h>

namespace {
using namespace radchain::test;

void expect_identical_for_thread_counts(const std::string& command) {
  Scratch scratch;
  std::string reference;
  for (const char* threads : {"1", "2", "8"}) {
    const CliResult r = run_cli(scratch, command + " --threads " + threads);
    ASSERT_EQ(r.exit_code, 0) << command << " --threads " << threads << "\n" << r.err;
    ASSERT_FALSE(r.out.empty());
    if (reference.empty())
      reference = r.out;
    else
      EXPECT_EQ(r.out, reference) << command << " --threads " << threads;
  }
}

TEST(ThreadIdentity, SweepIsTheSameForOneTwoAndEightThreads) {
  for (const char* format : {"csv", "json", "text"})
    expect_identical_for_thread_counts("sweep '" + sbv_file +
                                       "' --set 'optics.aperture=15 cm:30 cm:37' --set 'detector.integration_time=0.5 s:2 s:11' "
                                       "--format " + format);
}

TEST(ThreadIdentity, ALaneFreeSweepIsTheSameForOneTwoAndEightThreads) {
  // several solves: the scalar path, not lanes
  expect_identical_for_thread_counts("sweep '" + source_dir + "/sensors/kolobrodov-1996-ccd151.toml' --set 'platform.altitude=300 km:700 km:41'");
}

TEST(ThreadIdentity, CatalogueIsTheSameForOneTwoAndEightThreads) {
  std::string files;
  for (const char* name : {"msx-sbv", "sbv-smallest-sphere", "pan2010-auxiliary-sensor", "kolobrodov-1996-ccd151",
                           "kolobrodov-1996-ccd151-computed"})
    files += " '" + source_dir + "/sensors/" + name + ".toml'";
  for (const char* format : {"csv", "json", "text"})
    expect_identical_for_thread_counts("catalogue" + files + " --format " + format);
}

}  // namespace
