// Regressions: crafted shard files and shard counts. merge validates every header field and row
// against the job it belongs to and refuses what does not fit with one located line and exit 2 — it never
// crashes (a shard count near 2^64 made it allocate a slot per shard; a catalogue shard with fewer columns than
// a catalogue has made its summary read past the row).
#include "cli_helpers.hpp"

#include <gtest/gtest.h>

#include <cstring>

namespace {
using namespace radchain::test;

std::size_t lines_of(const std::string& text) { return count_lines(text); }

// A valid one-shard sweep file of the SBV sensor, written by radchain itself.
std::string real_shard(const Scratch& scratch) {
  const fs::path file = scratch / "real.shard";
  const CliResult r = run_cli(scratch, "sweep '" + sbv_file + "' --set 'optics.aperture=15 cm:30 cm:4' --results target.magnitude --shard 1/1 --out '" +
                                           file.string() + "'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return read_text(file);
}

CliResult merge_text(const Scratch& scratch, const std::string& name, const std::string& text) {
  const fs::path file = scratch / name;
  write_text(file, text);
  return run_cli(scratch, "merge '" + file.string() + "'");
}

TEST(MergeHostile, AShardCountNear2To64IsRefusedNotACrash) {
  Scratch scratch;
  std::string text = real_shard(scratch);
  ASSERT_NE(text.find("shard 1/1 "), std::string::npos);
  text.replace(text.find("shard 1/1 "), 10, "shard 1/18446744073709551615 ");
  const CliResult r = merge_text(scratch, "huge.shard", text);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(lines_of(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("at most 100000 shards"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
  // and sweep refuses to write such a shard in the first place
  const CliResult sweep = run_cli(scratch, "sweep '" + sbv_file + "' --set 'optics.aperture=15 cm:30 cm:4' --shard 1/18446744073709551615");
  EXPECT_EQ(sweep.exit_code, 2);
  EXPECT_NE(sweep.err.find("at most 100000 shards"), std::string::npos) << sweep.err;
}

TEST(MergeHostile, ACatalogueShardWithTooFewColumnsIsRefused) {
  Scratch scratch;
  const std::string text =
      "# radchain shard 1/1 order=block kind=catalogue points=1 format=text job=0000000000000000 types=tt\n"
      "point,sensor,result\n0,a,b\n# end rows=1 exit=0\n";
  const CliResult r = merge_text(scratch, "short.shard", text);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("is not a catalogue's"), std::string::npos) << r.err;
}

TEST(MergeHostile, HeaderFieldsAreChecked) {
  Scratch scratch;
  const std::string text = real_shard(scratch);
  const std::pair<std::string, std::string> edits[] = {
      {"kind=sweep", "kind=sweeep"}, {"format=csv", "format=xml"}, {"order=block", "order=random"}, {"exit=0", "exit=77"}};
  for (const auto& [from, to] : edits) {
    std::string bad = text;
    ASSERT_NE(bad.find(from), std::string::npos) << from;
    bad.replace(bad.find(from), from.size(), to);
    const CliResult r = merge_text(scratch, "bad.shard", bad);
    EXPECT_EQ(r.exit_code, 2) << to << ": " << r.err;
    EXPECT_EQ(lines_of(r.err), 1u) << r.err;
    EXPECT_TRUE(r.out.empty()) << to;
  }
}

// merge_fuzz (a long run on tmpfs, session 6): a sweep shard that repeats a point wrote one record more than its
// .npy header promised, and the writer's own consistency check ended the process (std::logic_error). A sweep has
// one row per point; a repeat is refused as the shard's fault, for every output format.
TEST(MergeHostile, ASweepShardRepeatingAPointIsRefused) {
  Scratch scratch;
  const CliResult sweep = run_cli(scratch, "sweep '" + sbv_file + "' --set 'optics.aperture=15 cm:30 cm:3' --results target.magnitude"
                                           " --shard 1/1 --out '" + (scratch / "a.shard").string() + "' --format npy");
  ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
  std::string text = read_text(scratch / "a.shard");
  // Write the last data row twice and say so in the end line: only the repeat is wrong.
  const auto end = text.find("# end rows=3");
  ASSERT_NE(end, std::string::npos) << text;
  const auto last = text.rfind('\n', end - 2) + 1;
  text.insert(end, text.substr(last, end - last));
  text.replace(text.find("# end rows=3"), 12, "# end rows=4");
  write_text(scratch / "b.shard", text);
  for (const std::string out : {"c.npy", "c.csv"}) {
    const CliResult r = run_cli(scratch, "merge '" + (scratch / "b.shard").string() + "' --out '" + (scratch / out).string() + "'");
    EXPECT_EQ(r.exit_code, 2) << out << ": " << r.err;
    EXPECT_EQ(lines_of(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("is not the next point"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(scratch / out)) << out;
  }
}

}  // namespace

// A numeric cell that is not a number (a corrupted or hand-edited shard) is refused with its row and column; it
// became a silent NaN in the merged table, exit 0. "nan" (a failed point, as radchain writes it) stays valid.
namespace {
using namespace radchain::test;

TEST(MergeHostile, AnUnparsableNumericCellIsRefused) {
  Scratch scratch;
  const std::string text = real_shard(scratch);
  // The first data row: "0,<aperture>,<magnitude>"; its last cell is the limiting magnitude.
  const std::size_t row = text.find("\n0,") + 1;
  const std::size_t cell = text.rfind(',', text.find('\n', row)) + 1;
  const std::size_t end = text.find('\n', row);
  for (const std::string bad : {"abc", "1e999", "0x10", "", "inf"}) {
    std::string corrupted = text;
    corrupted.replace(cell, end - cell, bad);
    const CliResult r = merge_text(scratch, "bad.shard", corrupted);
    EXPECT_EQ(r.exit_code, 2) << bad << ": " << r.out << r.err;
    EXPECT_EQ(count_lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("row 1: target.magnitude = \"" + bad + "\" is not a number"), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
  std::string failed_point = text;
  failed_point.replace(cell, end - cell, "nan");
  EXPECT_EQ(merge_text(scratch, "nan.shard", failed_point).exit_code, 0);
}

}  // namespace

// npy_shard_fuzz: a column line with a NUL or a line break in a name, a name twice or bytes that are not UTF-8 was
// merged; into .npy it made a header numpy.load cannot read (a Python literal ended by the line break or refused
// for the NUL; a dtype with two fields of one name). radchain writes none of them: such a shard is refused.
namespace {
using namespace radchain::test;

TEST(MergeHostile, AColumnLineRadchainDoesNotWriteIsRefused) {
  Scratch scratch;
  const std::string header = "# radchain shard 1/1 order=block kind=sweep points=1 format=npy job=0000000000000000 types=nn\n";
  const std::string rows = "0,1,2\n# end rows=1 exit=0\n";
  struct Case {
    std::string columns, expected;
  };
  for (const Case& k : std::vector<Case>{{std::string("point,a\0b,c\n", 12), "control character"},
                                         {"point,\"a\nb\",c\n", "control character"},
                                         {"point,a,a\n", "names \"a\" twice"},
                                         {"point,a\xff,c\n", "not UTF-8"}}) {
    write_text(scratch / "bad.shard", header + k.columns + rows);
    const CliResult r = run_cli(scratch, "merge '" + (scratch / "bad.shard").string() + "' --out '" + (scratch / "m.npy").string() + "'");
    EXPECT_EQ(r.exit_code, 2) << k.expected << ": " << r.err;
    EXPECT_EQ(count_lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find(k.expected), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(scratch / "m.npy")) << k.expected;
  }
  write_text(scratch / "good.shard", header + "point,a,b\n" + rows);  // the same shard with names radchain writes
  EXPECT_EQ(run_cli(scratch, "merge '" + (scratch / "good.shard").string() + "' --out '" + (scratch / "m.npy").string() + "'").exit_code, 0);
}

// npy_shard_fuzz: a numeric cell with a leading '+' (accepted by the shard reader: a catalogue's signed delta) was
// NaN in a merged .npy while the CSV merge kept its number.
TEST(MergeHostile, APlusSignedCellIsItsNumberInNpy) {
  Scratch scratch;
  write_text(scratch / "plus.shard", "# radchain shard 1/1 order=block kind=sweep points=1 format=npy job=0000000000000000 types=nn\n"
                                     "point,a,b\n0,+8.5,2\n# end rows=1 exit=0\n");
  const CliResult r = run_cli(scratch, "merge '" + (scratch / "plus.shard").string() + "' --out '" + (scratch / "m.npy").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string npy = read_text(scratch / "m.npy");
  ASSERT_GE(npy.size(), 16u);
  double values[2];
  std::memcpy(values, npy.data() + npy.size() - 16, 16);
  EXPECT_EQ(values[0], 8.5);
  EXPECT_EQ(values[1], 2.0);
}

}  // namespace
