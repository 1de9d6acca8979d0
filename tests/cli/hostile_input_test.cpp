// Regressions: results that lie, plugins that misbehave, absurd but well-formed requests and
// documents shaped to exhaust the stack. Each gives a clear error and an exit code, never a crash or a hang.
#include "cli_helpers.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sys/stat.h>

#include <array>
#include <cstdint>

namespace {
using namespace radchain::test;

const std::string test_plugins = RADCHAIN_BINARY_DIR "/test_plugins";

// --- results that lie ----------------------------------------------------------------------------------------

TEST(HostileInput, AFailedSolveReportsNaNNotTheBracketEnd) {
  Scratch scratch;
  const fs::path file = scratch / "unsolvable.toml";
  write_text(file, sbv_with("bracket = [5, 25]", "bracket = [5, 6]"));  // the root is near 15
  const CliResult text = run_cli(scratch, "run '" + file.string() + "'");
  EXPECT_EQ(text.exit_code, 1) << text.err;
  EXPECT_NE(text.out.find("FAILED"), std::string::npos) << text.out;
  std::string magnitude_line;
  std::istringstream lines(text.out);
  for (std::string line; std::getline(lines, line);)
    if (magnitude_line.empty() && line.find("  target.magnitude ") == 0) magnitude_line = line;  // the results table
  std::istringstream cells(magnitude_line);
  std::string name, value;
  cells >> name >> value;
  EXPECT_EQ(value, "-") << text.out;  // how the report shows a value that is not a number

  const CliResult json = run_cli(scratch, "run '" + file.string() + "' --format json");
  EXPECT_EQ(json.exit_code, 1) << json.err;
  const auto j = nlohmann::json::parse(json.out);
  bool seen = false;
  for (const auto& r : j["results"])
    if (r["name"] == "target.magnitude") {
      seen = true;
      EXPECT_TRUE(r["value"].is_null()) << r.dump();
    }
  EXPECT_TRUE(seen) << json.out;
  EXPECT_FALSE(j["solves"][0]["converged"].get<bool>());
}

// --- plugins ------------------------------------------------------------------------------------------------

TEST(HostileInput, APluginThrowingANonStdExceptionIsAnInternalErrorNotAnAbort) {
  Scratch scratch;
  const fs::path file = scratch / "throws.toml";
  write_text(file, sbv_with("plugin = \"none\"", "plugin = \"throws_int\""));
  const CliResult r = run_cli(scratch, "--plugin-path '" RADCHAIN_BINARY_DIR "/test_plugins_throw' run '" + file.string() + "'");
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("not a std::exception"), std::string::npos) << r.err;
}

// In a catalogue, that plugin fails its own file: the other files' rows are all written.
TEST(HostileInput, APluginThrowingAnythingFailsItsFileNotTheCatalogue) {
  Scratch scratch;
  const fs::path folder = scratch / "catalogue";
  fs::create_directories(folder);
  write_text(folder / "a_throws.toml", sbv_with("plugin = \"none\"", "plugin = \"throws_int\""));
  write_text(folder / "b_sbv.toml", read_text(sbv_file));
  const CliResult r = run_cli(scratch, "--plugin-path '" RADCHAIN_BINARY_DIR "/test_plugins_throw' catalogue '" +
                                           folder.string() + "' --format csv");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.out.find("a_throws"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("not a std::exception"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("b_sbv,\"MSX SBV (Pan 2010, Table 1)\",target.magnitude"), std::string::npos) << r.out;
}

TEST(HostileInput, PluginsListsEveryLibraryAndMarksTheBadOnes) {
  Scratch scratch;
  const CliResult r = run_cli(scratch, "--plugin-path '" + test_plugins + "' plugins");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  for (const char* bad : {"bad_abi", "no_entry"}) {
    const auto at = r.out.find(std::string(bad) + " ");
    ASSERT_NE(at, std::string::npos) << r.out;
    EXPECT_NE(r.out.find("UNUSABLE", at), std::string::npos) << r.out;
  }
  EXPECT_NE(r.out.find("telescope "), std::string::npos) << r.out;  // the good ones are listed too
  EXPECT_NE(r.out.find("snr_threshold "), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("2 of "), std::string::npos) << r.err;
  EXPECT_EQ(count_lines(r.err), 1u) << r.err;
}

TEST(HostileInput, ALibraryOfAnotherAbiIsRefusedBeforeItsConstructorsRun) {
  Scratch scratch;
  const fs::path marker = scratch / "constructor-ran";
  const std::string env = "RADCHAIN_TEST_MARKER='" + marker.string() + "' ";
  const std::string library = RADCHAIN_BINARY_DIR "/test_plugins_ctor/optics/ctor_marker.so";
  const CliResult listed = run_cli(scratch, "--plugin-path '" RADCHAIN_BINARY_DIR "/test_plugins_ctor' plugins");
  EXPECT_EQ(listed.exit_code, 2) << listed.err;
  EXPECT_NE(listed.out.find("UNUSABLE: built for plugin ABI 999"), std::string::npos) << listed.out;
  const CliResult described = run_cli(scratch, "describe '" + library + "'");
  EXPECT_EQ(described.exit_code, 2) << described.err;
  EXPECT_NE(described.err.find("built for plugin ABI 999"), std::string::npos) << described.err;
  // the environment reaches the CLI through the shell of run_cli
  const int status = std::system((env + "'" RADCHAIN_CLI "' describe '" + library + "' >/dev/null 2>&1").c_str());
  EXPECT_EQ(WEXITSTATUS(status), 2);
  EXPECT_FALSE(fs::exists(marker)) << "the library's static constructor ran before the ABI check";
}

// --- limits ------------------------------------------------------------------------------------------------

TEST(HostileInput, SweepStepCountsThatOverflowOrAreHugeAreRefusedQuickly) {
  Scratch scratch;
  for (const char* steps : {"99999999999999999999999", "20000000000", "9223372036854775807"}) {
    const CliResult r = run_cli(scratch, "sweep '" + sbv_file + "' --set 'optics.aperture=15 cm:30 cm:" + steps + "'");
    EXPECT_EQ(r.exit_code, 2) << steps << " " << r.err;
    EXPECT_NE(r.err.find("is more than 1e+10"), std::string::npos) << r.err;
    EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  }
  // 10^9 steps pass validation at once (the range is checked at its ends), then ask for --allow-large
  const CliResult big = run_cli(scratch, "sweep '" + sbv_file + "' --set 'optics.aperture=15 cm:30 cm:1000000000'");
  EXPECT_EQ(big.exit_code, 2) << big.err;
  EXPECT_NE(big.err.find("give --allow-large"), std::string::npos) << big.err;
}

TEST(HostileInput, ALargeSweepNeedsAllowLarge) {
  Scratch scratch;
  const std::string grid = "sweep '" + sbv_file + "' --set 'optics.aperture=15 cm:30 cm:20000' --set 'detector.integration_time=0.1 s:10 s:20000'";
  const CliResult r = run_cli(scratch, grid);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("the grid has 4e+08 points: more than 1e+08"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
  // with the flag it starts: one shard of 100000 runs 4000 points
  const CliResult allowed = run_cli(scratch, grid + " --allow-large --shard 100000/100000 --results detector.snr");
  EXPECT_EQ(allowed.exit_code, 0) << allowed.err;
  EXPECT_EQ(count_lines(allowed.out), 4000u + 3u);  // header, column names, rows, trailer
}

TEST(HostileInput, ADottedKeyOfThousandsOfPartsIsRefusedNotAStackOverflow) {
  Scratch scratch;
  for (std::size_t parts : {65u, 5000u, 100000u}) {
    std::string key = "optics";
    for (std::size_t i = 1; i < parts; ++i) key += ".a";
    const fs::path file = scratch / "deep.toml";
    write_text(file, read_text(sbv_file) + "\n" + key + " = 1\n");
    const CliResult r = run_cli(scratch, "run '" + file.string() + "'");
    EXPECT_EQ(r.exit_code, 2) << parts << " " << r.err.substr(0, 300);
    EXPECT_NE(r.err.find("a dotted key of more than 64 parts"), std::string::npos) << r.err.substr(0, 300);
    EXPECT_EQ(count_lines(r.err), 1u);
  }
  // a table header the same way
  std::string header = "[optics";
  for (int i = 0; i < 3000; ++i) header += ".b";
  const fs::path file = scratch / "deep_header.toml";
  write_text(file, read_text(sbv_file) + "\n" + header + "]\nx = 1\n");
  const CliResult r = run_cli(scratch, "run '" + file.string() + "'");
  EXPECT_EQ(r.exit_code, 2) << r.err.substr(0, 300);
  EXPECT_NE(r.err.find("deep_header.toml:"), std::string::npos) << r.err.substr(0, 300);
  // a quoted key may hold dots: they are not parts
  const fs::path quoted = scratch / "quoted.toml";
  std::string dots(100, '.');
  write_text(quoted, "# \"" + dots + "\"\n" + read_text(sbv_file));
  EXPECT_EQ(run_cli(scratch, "run '" + quoted.string() + "'").exit_code, 0);
}

TEST(HostileInput, AnOverLongKeyIsRefused) {
  Scratch scratch;
  const fs::path file = scratch / "long.toml";
  write_text(file, sbv_with("[optics]\n", "[optics]\n" + std::string(5000, 'k') + " = 1\n"));
  const CliResult r = run_cli(scratch, "run '" + file.string() + "'");
  EXPECT_EQ(r.exit_code, 2) << r.err.substr(0, 300);
  EXPECT_NE(r.err.find("a key of 5000 characters: at most 256"), std::string::npos) << r.err.substr(0, 300);
  EXPECT_EQ(count_lines(r.err), 1u);
}

}  // namespace

namespace {
using namespace radchain::test;

// A sensor file may name any readable file as a table: a device or a file of gigabytes is refused before reading.
TEST(HostileInput, DataFilesThatAreNotTablesOrTooLargeAreRefused) {
  Scratch scratch;
  const std::string computed = source_dir + "/sensors/kolobrodov-1996-ccd151-computed.toml";
  const CliResult device = run_cli(scratch, "run '" + computed + "' --set 'source.table=\"/dev/zero\"'");
  EXPECT_EQ(device.exit_code, 2) << device.err;
  EXPECT_EQ(count_lines(device.err), 1u) << device.err;  // only regular files are data files
  const fs::path huge = scratch / "huge.csv";
  { std::ofstream(huge).put('x'); }
  fs::resize_file(huge, 100u << 20);  // sparse: no disk used
  const CliResult big = run_cli(scratch, "run '" + computed + "' --set 'source.table=\"" + huge.string() + "\"'");
  EXPECT_EQ(big.exit_code, 2) << big.err;
  EXPECT_NE(big.err.find("larger than a spectrum file may be (64 MiB)"), std::string::npos) << big.err;
  EXPECT_EQ(count_lines(big.err), 1u) << big.err;
}

// --- inputs that are no files, counts that are no counts ------------------------------------------------------

// A sensor file that is a FIFO (which would block for ever), a device (/dev/zero: gigabytes in seconds), a folder,
// or larger than any sensor file: one line, exit 2, before anything is read.
TEST(HostileInput, ASensorFileThatIsNoRegularFileOrHugeIsRefusedBeforeReading) {
  Scratch scratch;
  const fs::path fifo = scratch / "sensor.toml";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const fs::path huge = scratch / "huge.toml";
  { std::ofstream(huge).put('#'); }
  fs::resize_file(huge, 32u << 20);  // sparse
  const std::pair<std::string, std::string> cases[] = {
      {fifo.string(), "is not a regular file"},
      {"/dev/zero", "is not a regular file"},
      {scratch.path().string(), "is a directory, not a file"},
      {huge.string(), "larger than a sensor file may be (16 MiB)"},
  };
  for (const auto& [path, message] : cases) {
    const CliResult r = run_shell(scratch, "timeout 20 '" RADCHAIN_CLI "' run '" + path + "'");
    EXPECT_EQ(r.exit_code, 2) << path << ": " << r.err;
    EXPECT_EQ(count_lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << path << ": " << r.err;
  }
}

// Counts that CLI11 would wrap (-1 into 2⁶⁴ − 1) or that ask for gigabytes: exit 2 with the option named.
TEST(HostileInput, ThreadAndSampleCountsOutsideTheirRangeAreBadInput) {
  Scratch scratch;
  const std::string sweep = "sweep '" + sbv_file + "' --set 'optics.aperture=15 cm:30 cm:3' --threads ";
  for (const char* threads : {"-1", "100000", "1e3"}) {
    const CliResult r = run_cli(scratch, sweep + threads);
    EXPECT_EQ(r.exit_code, 2) << threads << ": " << r.err;
    EXPECT_NE(r.err.find("--threads"), std::string::npos) << r.err;
  }
  const std::string uncertainty = "uncertainty '" + sbv_file + "' --results target.magnitude "
                                  "--vary 'optics.transmittance=normal(0.56, 0.02)' --samples ";
  for (const char* samples : {"-5", "9223372036854775808", "18446744073709551615", "1000000000", "0"}) {
    const CliResult r = run_shell(scratch, "timeout 60 '" RADCHAIN_CLI "' " + uncertainty + samples);
    EXPECT_EQ(r.exit_code, 2) << samples << ": " << r.err;
    EXPECT_EQ(count_lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("--samples"), std::string::npos) << r.err;
  }
}

// A PNG scene that declares 20000 × 20000 pixels in 70 bytes is refused from its header, before 8 GB are allocated.
std::uint32_t crc32(const unsigned char* data, std::size_t n, std::uint32_t crc = 0xFFFFFFFFu) {
  for (std::size_t i = 0; i < n; ++i) {  // (PNG's CRC-32, ISO 3309; bitwise)
    crc ^= data[i];
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return crc;
}
void put_chunk(std::string& png, const char* type, const std::string& data) {
  auto be32 = [&](std::uint32_t v) {
    for (int s = 24; s >= 0; s -= 8) png.push_back(static_cast<char>((v >> s) & 0xFF));
  };
  be32(static_cast<std::uint32_t>(data.size()));
  const std::string body = std::string(type, 4) + data;
  png += body;
  be32(crc32(reinterpret_cast<const unsigned char*>(body.data()), body.size()) ^ 0xFFFFFFFFu);
}

TEST(HostileInput, AnImageDeclaringHugeDimensionsIsRefusedFromItsHeader) {
  Scratch scratch;
  std::string png = "\x89PNG\r\n\x1a\n";
  std::string ihdr;
  for (std::uint32_t v : {20000u, 20000u})
    for (int s = 24; s >= 0; s -= 8) ihdr.push_back(static_cast<char>((v >> s) & 0xFF));
  ihdr += std::string("\x08\x00\x00\x00\x00", 5);  // 8-bit grey, deflate, no filter, no interlace
  put_chunk(png, "IHDR", ihdr);
  put_chunk(png, "IDAT", std::string("\x78\x9c\x03\x00\x00\x00\x00\x01", 8));
  put_chunk(png, "IEND", "");
  const fs::path scene = scratch / "bomb.png", out = scratch / "frame.fits";
  write_text(scene, png);
  const CliResult r = run_shell(scratch, "timeout 60 '" RADCHAIN_CLI "' render '" + source_dir +
                                             "/sensors/kolobrodov-1996-ccd151-computed.toml' --scene '" + scene.string() +
                                             "' --scene-sampling '1 m' --out '" + out.string() + "'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("declares 20000 × 20000 pixels"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

// A sensor name carrying escape sequences (retitle the window, erase the line, a C1 CSI) reaches a terminal escaped;
// written to a file it stays as it was. `script` (util-linux) gives the command a terminal.
TEST(HostileInput, ControlCharactersFromAFileAreEscapedOnATerminal) {
  Scratch scratch;
  const fs::path sensor = scratch / "evil.toml", saved = scratch / "report.txt";
  write_text(sensor, sbv_with("name = \"MSX SBV (Pan 2010, Table 1)\"",
                              "name = \"evil\\u001b]0;pwned\\u0007\\u001b[2K\\u009b31m\""));
  const CliResult tty = run_shell(scratch, "script -qec \"'" RADCHAIN_CLI "' run '" + sensor.string() + "'\" /dev/null");
  EXPECT_EQ(tty.exit_code, 0) << tty.out << tty.err;
  EXPECT_NE(tty.out.find("evil\\x1b]0;pwned\\x07\\x1b[2K\\u009b31m"), std::string::npos) << tty.out;
  EXPECT_EQ(tty.out.find('\x1b'), std::string::npos);
  EXPECT_EQ(tty.out.find('\x07'), std::string::npos);
  EXPECT_EQ(tty.out.find("\xc2\x9b"), std::string::npos);
  ASSERT_EQ(run_shell(scratch, "'" RADCHAIN_CLI "' run '" + sensor.string() + "' >'" + saved.string() + "'").exit_code, 0);
  EXPECT_NE(read_text(saved).find("evil\x1b]0;pwned\x07\x1b[2K\xc2\x9b" "31m"), std::string::npos);
}

}  // namespace
