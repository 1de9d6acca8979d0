// Outputs are atomic and replace nothing they should not. Every file radchain writes goes to a temporary in the same
// folder and is renamed when complete; a write error (a full disk, /dev/full, a file size limit) is one line on
// stderr and exit 3, never a truncated file with exit 0; a killed sweep leaves no output; an output naming one of the
// command's inputs is refused; a replaced file keeps its mode, owner and links; a failed merge leaves an existing
// --out untouched.
#include "cli_helpers.hpp"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <signal.h>

#include <chrono>
#include <thread>

namespace {
using namespace radchain::test;

const std::string cli = RADCHAIN_CLI;
const std::string small_sweep = "sweep '" + sbv_file + "' --set 'optics.aperture=15 cm:30 cm:4'";

// Files of the scratch folder whose name starts with ".radchain-" (temporaries left behind).
std::vector<std::string> leftovers(const Scratch& scratch) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(scratch.path()))
    if (entry.path().filename().string().rfind(".radchain-", 0) == 0) names.push_back(entry.path().filename().string());
  return names;
}

TEST(AtomicOutput, DevFullAsOutIsAnErrorForEveryTableCommand) {
  Scratch scratch;
  const fs::path shard = scratch / "one.shard";
  ASSERT_EQ(run_cli(scratch, small_sweep + " --shard 1/1 --out '" + shard.string() + "'").exit_code, 0);
  const std::string commands[] = {
      small_sweep + " --out /dev/full",
      small_sweep + " --shard 1/2 --out /dev/full",
      "catalogue '" + sbv_file + "' --out /dev/full",
      "merge '" + shard.string() + "' --out /dev/full",
      "compare '" + sbv_file + "' '" + sbv_file + "' --out /dev/full",
  };
  for (const auto& command : commands) {
    const CliResult r = run_cli(scratch, command);
    EXPECT_EQ(r.exit_code, 3) << command << "\n" << r.err;
    EXPECT_EQ(count_lines(r.err), 1u) << command << "\n" << r.err;
    EXPECT_NE(r.err.find("cannot write /dev/full: No space left on device"), std::string::npos) << command << "\n" << r.err;
  }
}

TEST(AtomicOutput, StandardOutputOnAFullDeviceIsAnError) {
  Scratch scratch;
  for (const std::string& command : {"run '" + sbv_file + "'", "run '" + sbv_file + "' --format json", small_sweep,
                                     "catalogue '" + sbv_file + "'"}) {
    const CliResult r = run_shell(scratch, "'" + cli + "' " + command + " >/dev/full");
    EXPECT_EQ(r.exit_code, 3) << command << "\n" << r.err;
    EXPECT_NE(r.err.find("radchain: cannot write standard output: "), std::string::npos) << command << "\n" << r.err;
    EXPECT_EQ(count_lines(r.err), 1u) << command << "\n" << r.err;
  }
}

// A full disk, simulated by a file size limit in the child (SIGXFSZ ignored, so the write fails with EFBIG).
TEST(AtomicOutput, AFileSizeLimitLeavesNoTruncatedFileAndAnExistingOutUntouched) {
  Scratch scratch;
  const fs::path out = scratch / "sweep.csv";
  const std::string big_sweep = "sweep '" + sbv_file + "' --set 'optics.aperture=15 cm:30 cm:400'";
  // without the limit the output is larger than the limit
  const CliResult full = run_cli(scratch, big_sweep);
  ASSERT_EQ(full.exit_code, 0) << full.err;
  ASSERT_GT(full.out.size(), 64u * 1024u);
  write_text(out, "previous contents\n");
  // dash counts ulimit -f in 512-byte blocks, bash in 1024: either way 16-32 KiB
  const CliResult r = run_shell(scratch, "trap '' XFSZ; ulimit -f 32; exec '" + cli + "' " + big_sweep + " --out '" + out.string() + "'");
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("File too large"), std::string::npos) << r.err;
  EXPECT_EQ(read_text(out), "previous contents\n");
  EXPECT_TRUE(leftovers(scratch).empty());
  // catalogue and merge the same way
  const CliResult cat = run_shell(scratch, "trap '' XFSZ; ulimit -f 0; exec '" + cli + "' catalogue '" + sbv_file + "' --out '" + out.string() + "'");
  EXPECT_EQ(cat.exit_code, 3) << cat.err;
  EXPECT_EQ(read_text(out), "previous contents\n");
  EXPECT_TRUE(leftovers(scratch).empty());
}

// An output that is one of the command's inputs is refused, whichever kind of input it is: the sensor file, a member
// of the catalogue, a shard being merged, a results file being compared. The input is left as it was.
TEST(AtomicOutput, AnOutputNamingOneOfTheCommandsInputsIsRefused) {
  Scratch scratch;
  const fs::path sensor = scratch / "sbv.toml", a = scratch / "a.shard", b = scratch / "b.shard", json = scratch / "r.json";
  write_text(sensor, read_text(sbv_file));
  ASSERT_EQ(run_cli(scratch, small_sweep + " --shard 1/2 --out '" + a.string() + "'").exit_code, 0);
  ASSERT_EQ(run_cli(scratch, small_sweep + " --shard 2/2 --out '" + b.string() + "'").exit_code, 0);
  ASSERT_EQ(run_shell(scratch, "'" + cli + "' run '" + sbv_file + "' --format json >'" + json.string() + "'").exit_code, 0);
  const std::string s = sensor.string();
  const std::pair<std::string, fs::path> cases[] = {
      {"sweep '" + s + "' --set 'optics.aperture=15 cm:30 cm:4' --out '" + s + "'", sensor},
      {"catalogue '" + scratch.path().string() + "' --out '" + s + "'", sensor},
      {"merge '" + a.string() + "' '" + b.string() + "' --out '" + a.string() + "'", a},
      {"compare '" + json.string() + "' '" + sbv_file + "' --out '" + json.string() + "'", json},
  };
  for (const auto& [command, input] : cases) {
    const std::string before = read_text(input);
    const CliResult r = run_cli(scratch, command);
    EXPECT_EQ(r.exit_code, 2) << command << "\n" << r.err;
    EXPECT_EQ(count_lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("is one of this command's inputs"), std::string::npos) << command << "\n" << r.err;
    EXPECT_EQ(read_text(input), before) << command;
  }
  EXPECT_TRUE(leftovers(scratch).empty());
}

// Replacing an output keeps what its owner made of it: its mode (a 0600 file stays private) and owner, a symbolic
// link keeps naming the file it named, and a file with hard links is refused rather than split from them.
TEST(AtomicOutput, ReplacingAnOutputKeepsItsModeOwnerAndLinks) {
  Scratch scratch;
  const fs::path private_out = scratch / "private.csv";
  write_text(private_out, "old\n");
  ASSERT_EQ(::chmod(private_out.c_str(), 0600), 0);
  const bool root = ::geteuid() == 0;
  if (root) {
    ASSERT_EQ(::chown(private_out.c_str(), 65534, 65534), 0);  // nobody's, replaced by root
  }
  ASSERT_EQ(run_cli(scratch, small_sweep + " --out '" + private_out.string() + "'").exit_code, 0);
  struct stat st {};
  ASSERT_EQ(::stat(private_out.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0600u);
  if (root) {
    EXPECT_EQ(st.st_uid, 65534u);
  }
  EXPECT_NE(read_text(private_out), "old\n");

  const fs::path real = scratch / "real.csv", link = scratch / "link.csv";
  write_text(real, "old\n");
  fs::create_symlink(real, link);
  const CliResult via_link = run_cli(scratch, small_sweep + " --out '" + link.string() + "'");
  ASSERT_EQ(via_link.exit_code, 0) << via_link.err;
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_NE(read_text(real), "old\n");

  const fs::path first = scratch / "first.csv", second = scratch / "second.csv";
  write_text(first, "shared\n");
  fs::create_hard_link(first, second);
  const CliResult hard = run_cli(scratch, small_sweep + " --out '" + second.string() + "'");
  EXPECT_EQ(hard.exit_code, 2) << hard.err;
  EXPECT_NE(hard.err.find("hard links"), std::string::npos) << hard.err;
  EXPECT_EQ(read_text(first), "shared\n");
  EXPECT_EQ(fs::hard_link_count(first), 2u);
  EXPECT_TRUE(leftovers(scratch).empty());
}

TEST(AtomicOutput, AFailedMergeLeavesAnExistingOutUntouched) {
  Scratch scratch;
  const fs::path a = scratch / "a.shard", out = scratch / "merged.csv";
  ASSERT_EQ(run_cli(scratch, small_sweep + " --shard 1/2 --out '" + a.string() + "'").exit_code, 0);
  write_text(out, "previous contents\n");
  const CliResult r = run_cli(scratch, "merge '" + a.string() + "' --out '" + out.string() + "'");  // 2/2 missing
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(read_text(out), "previous contents\n");
  EXPECT_TRUE(leftovers(scratch).empty());
}

// Starts a sweep far too large to finish, waits (bounded) until its temporary output exists, sends `signal` and
// expects: death by that signal, a message, no output file, no temporary.
void kill_a_running_sweep(int signal, const std::string& message) {
  Scratch scratch;
  const fs::path out = scratch / "killed.csv", err = scratch / "killed.err";
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const int e = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(e, STDERR_FILENO);
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, STDOUT_FILENO);
    for (int s : {SIGINT, SIGHUP, SIGUSR1, SIGALRM, SIGXCPU}) ::signal(s, SIG_DFL);  // (an ignored one stays ignored)
    ::execl(cli.c_str(), cli.c_str(), "sweep", sbv_file.c_str(), "--set", "optics.aperture=15 cm:30 cm:3000", "--set",
            "detector.integration_time=0.1 s:10 s:3000", "--out", out.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  bool started = false;
  for (int i = 0; i < 1500 && !started; ++i) {  // at most 15 s
    started = !leftovers(scratch).empty();
    if (!started) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_TRUE(started) << read_text(err);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));  // some rows written
  ::kill(pid, signal);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == signal) << status << " " << read_text(err);
  EXPECT_NE(read_text(err).find(message), std::string::npos) << read_text(err);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_TRUE(leftovers(scratch).empty());
}

TEST(AtomicOutput, SigtermStopsASweepWithoutOutput) { kill_a_running_sweep(SIGTERM, "terminated (SIGTERM); no output file was written"); }
TEST(AtomicOutput, SigintStopsASweepWithoutOutput) { kill_a_running_sweep(SIGINT, "interrupted (SIGINT); no output file was written"); }
// Every other signal that ends a process and can be caught cleans up as well.
TEST(AtomicOutput, EveryCatchableTerminatingSignalLeavesNoTemporary) {
  kill_a_running_sweep(SIGHUP, "hung up (SIGHUP); no output file was written");
  kill_a_running_sweep(SIGUSR1, "stopped by SIGUSR1; no output file was written");
  kill_a_running_sweep(SIGALRM, "stopped by SIGALRM; no output file was written");
  kill_a_running_sweep(SIGXCPU, "CPU time limit reached (SIGXCPU); no output file was written");
}

}  // namespace

namespace {
using namespace radchain::test;

// Images, MTF tables and plots: under a file size limit too small for them, each command fails
// with one line naming the file, exit 3 (a write error), an existing file at the target untouched and no temporary
// left — including the PNGs gnuplot draws (a child process) and the FITS frames CFITSIO writes. The limit is set in
// bytes with prlimit (util-linux), not the shell's ulimit, whose block size differs between dash and bash.
TEST(AtomicOutput, ImagesTablesAndPlotsUnderAFileSizeLimit) {
  Scratch scratch;
  const std::string kolobrodov = source_dir + "/sensors/kolobrodov-1996-ccd151-computed.toml";
  const std::string worldview = source_dir + "/sensors/worldview-2-pan.toml";
  const std::string sbv_frame = "render '" + sbv_file + "' --focal-length \"45 cm\" --pixel-pitch \"27 um\" --seed 3";
  struct Case {
    std::string file, command;  // the command writes `file` (in the scratch folder), larger than `limit_bytes`
    std::uintmax_t limit_bytes;
    std::string reason = "";    // what the error line must also say
  };
  const std::vector<Case> cases = {
      {"frame.fits", sbv_frame + " --width 256 --height 256 --out '" + (scratch / "frame.fits").string() + "'", 8192},
      // a 64×64 frame (14 400 bytes of FITS) fits under the limit, its 1024×1024 TIFF preview does not
      {"preview.tif", sbv_frame + " --width 64 --height 64 --upscale 16 --out '" + (scratch / "small.fits").string() + "' --png '" +
                          (scratch / "preview.tif").string() + "'", 20000},
      {"scene.tif", "render '" + kolobrodov + "' --out '" + (scratch / "scene.tif").string() + "'", 8192},
      {"mtf.csv", "mtf '" + worldview + "' --out '" + (scratch / "mtf.csv").string() + "'", 8192},
      // the MTF curves' data file (201 rows) is larger than the limit: refused before gnuplot runs
      {"mtf.png", "mtf '" + worldview + "' --out /dev/null --plot '" + (scratch / "mtf.png").string() + "'", 8192, "data.tsv for gnuplot"},
      // small data, a PNG larger than the limit: gnuplot writes a cut PNG and exits 0; the IEND check refuses it
      {"sweep.png", small_sweep + " --out /dev/null --plot '" + (scratch / "sweep.png").string() + "'", 8192, "no IEND chunk"},
      {"hist.png", "uncertainty '" + sbv_file + "' --vary 'optics.transmittance=normal(0.56, 0.02)' --results target.magnitude "
                   "--samples 200 --plot '" + (scratch / "hist.png").string() + "'", 8192, "no IEND chunk"},
  };
  for (const Case& k : cases) {
    const fs::path target = scratch / k.file;
    const CliResult full = run_cli(scratch, k.command);
    ASSERT_EQ(full.exit_code, 0) << k.command << "\n" << full.err;
    ASSERT_GT(fs::file_size(target), k.limit_bytes) << k.file;
    write_text(target, "previous contents\n");
    const CliResult r = run_shell(scratch, "trap '' XFSZ; exec prlimit --fsize=" + std::to_string(k.limit_bytes) + " '" + cli + "' " + k.command);
    EXPECT_EQ(r.exit_code, 3) << k.command << "\n" << r.err;
    EXPECT_EQ(count_lines(r.err), 1u) << k.command << "\n" << r.err;
    // the line names the file asked for (not a temporary) and, where given, why
    EXPECT_EQ(r.err.rfind("radchain: cannot write " + target.string(), 0), 0u) << k.command << "\n" << r.err;
    EXPECT_NE(r.err.find(k.reason), std::string::npos) << k.command << "\n" << r.err;
    EXPECT_EQ(read_text(target), "previous contents\n") << k.file;
    EXPECT_TRUE(leftovers(scratch).empty()) << k.file;
  }
}

}  // namespace
