// `radchain sweep --out grid.npy`: a NumPy .npy file (numpy.lib.format version 1.0) with one float64 field per
// column, read back here by the format's own rules (magic, version, little-endian header length, the header's
// dict, 64-byte alignment, the records) and compared with the CSV of the same sweep; shards merge into the same
// bytes; a table with text columns and binary output to stdout are refused.
#include "cli_helpers.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

namespace {
using namespace radchain::test;

const std::string grid = " --set \"optics.aperture=15 cm:30 cm:7\" --set \"detector.integration_time=0.5 s:2 s:3\""
                         " --results target.magnitude,detector.snr";

struct Npy {
  std::string header;
  std::vector<double> values;
};

Npy read_npy(const std::string& bytes) {
  Npy npy;
  EXPECT_EQ(bytes.substr(0, 6), "\x93NUMPY");
  EXPECT_EQ(bytes[6], 1);  // version 1.0
  EXPECT_EQ(bytes[7], 0);
  const std::size_t length = static_cast<unsigned char>(bytes[8]) | (static_cast<std::size_t>(static_cast<unsigned char>(bytes[9])) << 8);
  EXPECT_EQ((10 + length) % 64, 0u);  // the data start 64-byte aligned
  npy.header = bytes.substr(10, length);
  EXPECT_EQ(npy.header.back(), '\n');
  const std::string data = bytes.substr(10 + length);
  EXPECT_EQ(data.size() % sizeof(double), 0u);
  npy.values.resize(data.size() / sizeof(double));
  std::memcpy(npy.values.data(), data.data(), data.size());
  return npy;
}

TEST(NpyOutput, SweepWritesARecordPerPointWithTheCsvValues) {
  Scratch scratch;
  const std::string npy_path = (scratch / "grid.npy").string();
  const CliResult written = run_cli(scratch, "sweep '" + sbv_file + "'" + grid + " --out " + npy_path);
  ASSERT_EQ(written.exit_code, 0) << written.err;
  const CliResult csv = run_cli(scratch, "sweep '" + sbv_file + "'" + grid);
  ASSERT_EQ(csv.exit_code, 0) << csv.err;
  const Npy npy = read_npy(read_text(npy_path));
  EXPECT_EQ(npy.header.substr(0, npy.header.find("]")),
            "{'descr': [('optics.aperture_cm', '<f8'), ('detector.integration_time_s', '<f8'), "
            "('target.magnitude', '<f8'), ('detector.snr', '<f8'), ");
  EXPECT_NE(npy.header.find("'fortran_order': False, 'shape': (21,), }"), std::string::npos) << npy.header;
  ASSERT_EQ(npy.values.size(), 21u * 4u);
  // The CSV's cells are the same numbers to 10 significant digits.
  std::istringstream lines(csv.out);
  std::string line;
  std::getline(lines, line);  // header
  for (std::size_t row = 0; std::getline(lines, line); ++row) {
    std::istringstream cells(line);
    std::string cell;
    for (std::size_t c = 0; std::getline(cells, cell, ','); ++c)
      EXPECT_NEAR(npy.values[row * 4 + c], std::stod(cell), 1e-9 * std::abs(std::stod(cell))) << "row " << row << " column " << c;
  }
}

TEST(NpyOutput, ShardsMergeIntoTheSameBytes) {
  Scratch scratch;
  const std::string whole = (scratch / "whole.npy").string(), merged = (scratch / "merged.npy").string();
  ASSERT_EQ(run_cli(scratch, "sweep '" + sbv_file + "'" + grid + " --out " + whole).exit_code, 0);
  for (int k = 1; k <= 3; ++k)
    ASSERT_EQ(run_cli(scratch, "sweep '" + sbv_file + "'" + grid + " --format npy --shard " + std::to_string(k) +
                                   "/3 --out " + (scratch / ("part" + std::to_string(k))).string())
                  .exit_code,
              0);
  const CliResult m = run_cli(scratch, "merge " + (scratch / "part1").string() + " " + (scratch / "part2").string() + " " +
                                           (scratch / "part3").string() + " --out " + merged);
  ASSERT_EQ(m.exit_code, 0) << m.err;
  EXPECT_EQ(read_text(merged), read_text(whole));
  // The shards say npy: merged to standard output it is refused, as a sweep's --format npy is.
  const CliResult to_stdout = run_cli(scratch, "merge " + (scratch / "part1").string() + " " + (scratch / "part2").string() +
                                                   " " + (scratch / "part3").string());
  EXPECT_EQ(to_stdout.exit_code, 2);
  EXPECT_EQ(to_stdout.out, "");
  EXPECT_EQ(to_stdout.err, "merge: the shards are of an .npy job: give --out FILE.npy (or --format csv)\n");
}

TEST(NpyOutput, RefusedForTextColumnsAndForStandardOutput) {
  Scratch scratch;
  const CliResult to_stdout = run_cli(scratch, "sweep '" + sbv_file + "'" + grid + " --format npy");
  EXPECT_EQ(to_stdout.exit_code, 2);
  EXPECT_EQ(to_stdout.out, "");
  EXPECT_EQ(to_stdout.err, "--format: npy: binary output: give --out FILE.npy\n");
  const std::string catalogue = (scratch / "catalogue.npy").string();
  const CliResult text_columns = run_cli(scratch, "catalogue '" + sbv_file + "' --out " + catalogue);
  EXPECT_EQ(text_columns.exit_code, 2);
  EXPECT_EQ(text_columns.err, "--format: npy: a catalogue table has text columns; .npy holds numbers only (use csv or json)\n");
  EXPECT_FALSE(fs::exists(catalogue));  // nothing half-written
}

}  // namespace
