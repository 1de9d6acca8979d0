// Sharding and merge: every point in exactly one shard, and the merged output byte-identical to the unsharded
// run, for catalogues and sweeps, both shard orders and every format.
#include "cli_helpers.hpp"
#include "radchain/batch/shard.hpp"
#include "radchain/batch/table.hpp"
#include "radchain/batch/thread_pool.hpp"
#include "radchain/batch/catalogue.hpp"
#include "radchain/error.hpp"
#include "radchain/batch/sweep.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <set>
#include <sstream>

namespace {
using namespace radchain;
using namespace radchain::test;

TEST(Shard, EveryPointInExactlyOneShard) {
  for (const char* order : {"block", "round-robin"})
    for (std::size_t total : {0u, 1u, 7u, 16u, 1000u})
      for (std::size_t n : {1u, 2u, 3u, 8u}) {
        std::multiset<std::size_t> seen;
        for (std::size_t k = 1; k <= n; ++k) {
          const PointRange range = shard_points(parse_shard(std::to_string(k) + "/" + std::to_string(n), order), total);
          for (std::size_t i = 0; i < range.count; ++i) {
            seen.insert(range[i]);
            if (i > 0) {
              EXPECT_LT(range[i - 1], range[i]);
            }
          }
        }
        ASSERT_EQ(seen.size(), total) << order << " " << total << " " << n;
        for (std::size_t p = 0; p < total; ++p) EXPECT_EQ(seen.count(p), 1u) << order << " point " << p;
      }
  // Blocks are contiguous and balanced: 16 points in 3 shards are 5, 5, 6.
  EXPECT_EQ(shard_points(parse_shard("1/3"), 16).count, 5u);
  EXPECT_EQ(shard_points(parse_shard("3/3"), 16).first, 10u);
  EXPECT_EQ(shard_points(parse_shard("2/3", "round-robin"), 16).stride, 3u);
}

TEST(Shard, BadShardSpecs) {
  for (const char* spec : {"0/3", "4/3", "3", "a/b", "1/0", "-1/3", "1/3/4"}) EXPECT_THROW(parse_shard(spec), InputError) << spec;
  EXPECT_THROW(parse_shard("1/3", "random"), InputError);
}

// In-process: the whole job and its n shards (merged in reverse order) through the same library calls the CLI
// makes; the merged bytes and exit code must equal the unsharded ones.
struct Job {
  std::function<TableLayout()> layout;
  std::function<std::size_t()> points;
  std::function<std::string()> job;
  std::function<int(const ShardSpec&, TableWriter&)> run;
};

void expect_merge_identical(const Job& job, TableFormat format, int n, const std::string& order) {
  Scratch scratch;
  std::ostringstream whole;
  int whole_code = 0;
  {
    TableWriter writer(whole, format, job.layout(), job.points());
    whole_code = job.run(ShardSpec{}, writer);
    writer.finish(whole_code);
  }
  std::vector<std::string> files;
  for (int k = n; k >= 1; --k) {
    const ShardSpec shard = parse_shard(std::to_string(k) + "/" + std::to_string(n), order);
    const fs::path part = scratch / ("part" + std::to_string(k));
    std::ofstream out(part, std::ios::binary);
    TableWriter writer(out, format, job.layout(), job.points(), shard, job.job());
    writer.finish(job.run(shard, writer));
    files.push_back(part.string());
  }
  std::ostringstream merged;
  EXPECT_EQ(merge_shards(files, merged), whole_code);
  EXPECT_EQ(merged.str(), whole.str()) << to_string(format) << ", " << n << " shards, " << order;
}

Job catalogue_job_of(const std::vector<std::string>& files) {
  return Job{catalogue_layout, [files] { return files.size(); },
             [files] { return catalogue_job(files, {}); },
             [files](const ShardSpec& shard, TableWriter& writer) {
               CatalogueOptions options;
               options.shard = shard;
               return run_catalogue(files, options, writer);
             }};
}

Job sweep_job_of(SweepOptions options) {
  auto sweep = std::make_shared<Sweep>(options);
  return Job{[sweep] { return sweep->layout(); }, [sweep] { return sweep->points(); }, [sweep] { return sweep->job(); },
             [options](const ShardSpec& shard, TableWriter& writer) {
               SweepOptions o = options;
               o.shard = shard;
               Sweep sweep(o);
               return sweep.run(writer);
             }};
}

TEST(ShardMerge, CatalogueEveryFormat) {
  const auto files = catalogue_files({source_dir + "/sensors", sbv_file});  // a file twice: two points
  for (TableFormat format : {TableFormat::csv, TableFormat::text, TableFormat::json})
    expect_merge_identical(catalogue_job_of(files), format, 2, "block");
  // More shards than files: some shards hold no file at all.
  expect_merge_identical(catalogue_job_of(files), TableFormat::text, static_cast<int>(files.size()) + 2, "round-robin");
}

TEST(ShardMerge, CatalogueWithAFailedCheck) {
  Scratch scratch;
  write_text(scratch / "a.toml", read_text(sbv_file));
  write_text(scratch / "b.toml", sbv_with("value = 15.55, tolerance = 0.05", "value = 14.0, tolerance = 0.05"));
  write_text(scratch / "c.toml", read_text(sbv_file));
  expect_merge_identical(catalogue_job_of(catalogue_files({scratch.path().string()})), TableFormat::text, 3, "block");
}

TEST(ShardMerge, SweepGridEveryFormat) {
  SweepOptions options;
  options.sensor_file = sbv_file;
  options.axes = {{"optics.aperture", "15 cm:30 cm:16"}, {"detector.qe", "0.2:0.8:3"}};
  for (TableFormat format : {TableFormat::csv, TableFormat::json, TableFormat::text})
    for (const char* order : {"block", "round-robin"}) expect_merge_identical(sweep_job_of(options), format, 3, order);
}

TEST(ShardMerge, RefusesIncompleteOrMixedShards) {
  Scratch scratch;
  SweepOptions options;
  options.sensor_file = sbv_file;
  options.axes = {{"optics.aperture", "15 cm:30 cm:4"}};
  options.results = {"target.magnitude"};
  auto write_shard = [&](const SweepOptions& o, const std::string& spec, const std::string& name) {
    SweepOptions with = o;
    with.shard = parse_shard(spec);
    Sweep sweep(with);
    std::ofstream out(scratch / name, std::ios::binary);
    TableWriter writer(out, TableFormat::csv, sweep.layout(), sweep.points(), with.shard, sweep.job());
    writer.finish(sweep.run(writer));
    return (scratch / name).string();
  };
  const std::string p1 = write_shard(options, "1/2", "p1"), p2 = write_shard(options, "2/2", "p2");
  SweepOptions other_options = options;
  other_options.overrides = {{"detector.qe", "0.5"}};
  const std::string other = write_shard(other_options, "2/2", "other");
  auto merge_error = [](const std::vector<std::string>& files) -> std::string {
    std::ostringstream out;
    try {
      merge_shards(files, out);
    } catch (const InputError& error) {
      EXPECT_EQ(out.str(), "");  // nothing is written before every shard has been checked
      return error.what();
    }
    return "(merged)";
  };
  EXPECT_NE(merge_error({p1}).find("shard 2/2 is missing"), std::string::npos);
  EXPECT_NE(merge_error({p1, p1}).find("given twice"), std::string::npos);
  EXPECT_NE(merge_error({p1, other}).find("another job"), std::string::npos);
  const std::string text = read_text(p2);
  write_text(scratch / "cut", text.substr(0, text.rfind("# end")));
  EXPECT_NE(merge_error({p1, (scratch / "cut").string()}).find("incomplete"), std::string::npos);
  // A row of shard 2/2 (point 2) deleted, its end line adjusted: point 3 is not the next point of the shard.
  const std::size_t header_end = text.find('\n', text.find('\n') + 1) + 1;
  const std::size_t row3 = text.find("\n3,") + 1;
  const std::string row3_line = text.substr(row3, text.find('\n', row3) + 1 - row3);
  write_text(scratch / "edited", text.substr(0, header_end) + row3_line + "# end rows=1 exit=0\n");
  EXPECT_NE(merge_error({p1, (scratch / "edited").string()}).find("point 3 is not the next point"), std::string::npos);
  EXPECT_NE(merge_error({sbv_file}).find("not a shard file"), std::string::npos);
  EXPECT_EQ(merge_error({p2, p1}), "(merged)");
}

// End to end through the CLI: shards written with --shard/--out, joined by `radchain merge`.
TEST(ShardMergeCli, SweepCsvRoundRobin) {
  Scratch scratch;
  const std::string sweep = "sweep '" + sbv_file + "' --set 'optics.aperture=15 cm:30 cm:16' --set 'detector.qe=0.2:0.8:3'";
  const CliResult whole = run_cli(scratch, sweep);
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  std::string shards;
  for (int k = 1; k <= 3; ++k) {
    const std::string part = (scratch / ("part-" + std::to_string(k) + ".csv")).string();
    const CliResult r = run_cli(scratch, sweep + " --shard " + std::to_string(k) + "/3 --shard-order round-robin --out '" + part + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    shards = " '" + part + "'" + shards;  // given to merge in reverse order
  }
  const fs::path merged = scratch / "all.csv";
  const CliResult m = run_cli(scratch, "merge" + shards + " --out '" + merged.string() + "'");
  EXPECT_EQ(m.exit_code, 0) << m.err;
  EXPECT_EQ(read_text(merged), whole.out);
  EXPECT_EQ(count_lines(whole.out), 1u + 48u);
  const CliResult missing = run_cli(scratch, "merge '" + (scratch / "part-1.csv").string() + "'");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_EQ(count_lines(missing.err), 1u) << missing.err;
  EXPECT_EQ(missing.out, "");
}

}  // namespace
