// The command line itself: --version, the plugins header, --no-solve, the warning when --set names a solved
// unknown, and the imaging commands living in a module the executable loads only for them.
#include "cli_helpers.hpp"
#include "radchain/version.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace {
using namespace radchain;
using namespace radchain::test;

double result_si(const nlohmann::json& report, const std::string& name) {
  for (const auto& r : report["results"])
    if (r["name"] == name) return r["value_si"].get<double>();
  throw std::out_of_range(name);
}

TEST(CliVersion, PrintsTheFrameworkVersionAndThePluginAbi) {
  Scratch scratch;
  const CliResult r = run_cli(scratch, "--version");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, fmt::format("radchain {} (plugin ABI {})\n", framework_version, plugin_abi_version));
}

TEST(CliPlugins, HeaderLineNamesThePluginAbi) {
  Scratch scratch;
  const CliResult r = run_cli(scratch, "plugins");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.substr(0, r.out.find('\n')), fmt::format("radchain {}, plugin ABI {}", framework_version, plugin_abi_version));
}

TEST(CliNoSolve, EvaluatesAtTheValueGivenWithoutSolving) {
  Scratch scratch;
  const CliResult solved = run_cli(scratch, "run '" + sbv_file + "' --format json");
  ASSERT_EQ(solved.exit_code, 0) << solved.err;
  const CliResult forward = run_cli(scratch, "run '" + sbv_file + "' --no-solve --set target.magnitude=14 --format json");
  EXPECT_EQ(forward.err, "");  // nothing overwrites the magnitude: no warning
  const auto a = nlohmann::json::parse(solved.out), b = nlohmann::json::parse(forward.out);
  EXPECT_EQ(a["solves"].size(), 1u);
  EXPECT_EQ(b["solves"].size(), 0u);
  EXPECT_EQ(result_si(b, "target.magnitude"), 14.0);
  EXPECT_NEAR(result_si(a, "detector.snr"), 5.0, 1e-9);  // the solve drives SNR to the threshold
  EXPECT_GT(result_si(b, "detector.snr"), 5.0);          // 1.56 magnitudes brighter than the limit
  // The [expected] limiting magnitude (15.55 ± 0.05) is not met at 14: the exit code still says so.
  EXPECT_EQ(forward.exit_code, 1);
}

TEST(CliNoSolve, WithoutSetTheFileValueIsUsed) {
  Scratch scratch;
  const CliResult r = run_cli(scratch, "run '" + sbv_file + "' --no-solve --format json");
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(result_si(j, "target.magnitude"), 15.5);  // the start value written in the file
}

// --no-solve in a sweep: the solved unknown becomes an axis, each point forward only, equal to `run --no-solve`.
TEST(CliNoSolve, SweepsASolvedUnknownForwardOnly) {
  Scratch scratch;
  const CliResult refused = run_cli(scratch, "sweep '" + sbv_file + "' --set target.magnitude=14:16:3");
  EXPECT_EQ(refused.exit_code, 2);  // without --no-solve the [[solve]] would overwrite the axis
  const CliResult r = run_cli(scratch, "sweep '" + sbv_file + "' --no-solve --set target.magnitude=14:16:3 --results detector.snr");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(count_lines(r.out), 4u) << r.out;  // header + 3 points
  const CliResult at14 = run_cli(scratch, "run '" + sbv_file + "' --no-solve --set target.magnitude=14 --format json");
  const double snr14 = result_si(nlohmann::json::parse(at14.out), "detector.snr");
  const std::string first = r.out.substr(r.out.find('\n') + 1, r.out.find('\n', r.out.find('\n') + 1) - r.out.find('\n') - 1);
  EXPECT_EQ(first.substr(0, 3), "14,");
  EXPECT_NEAR(std::stod(first.substr(3)), snr14, 1e-8 * snr14);
}

// --no-solve in a catalogue: the unknown stays at its start value and the [expected] check is judged on it.
TEST(CliNoSolve, CatalogueEvaluatesEachFileForwardOnly) {
  Scratch scratch;
  const CliResult solved = run_cli(scratch, "catalogue '" + sbv_file + "' --format csv");
  EXPECT_EQ(solved.exit_code, 0) << solved.err;
  EXPECT_NE(solved.out.find("target.magnitude,paper,15.5565"), std::string::npos) << solved.out;
  const CliResult forward = run_cli(scratch, "catalogue '" + sbv_file + "' --no-solve --format csv");
  EXPECT_EQ(forward.exit_code, 1) << forward.err;  // 15.5 is not the published 15.55 ± 0.05 limit
  EXPECT_NE(forward.out.find("target.magnitude,paper,15.5,15.55,"), std::string::npos) << forward.out;
}

// --solver: the closed form (auto) and the bracketing solver give the same limit; the report names the path.
TEST(CliSolver, AutoAndRootAgreeAndTheReportSaysWhichRan) {
  Scratch scratch;
  const CliResult closed = run_cli(scratch, "run '" + sbv_file + "' --format json");
  const CliResult root = run_cli(scratch, "run '" + sbv_file + "' --solver root --format json");
  ASSERT_EQ(closed.exit_code, 0) << closed.err;
  ASSERT_EQ(root.exit_code, 0) << root.err;
  const auto a = nlohmann::json::parse(closed.out), b = nlohmann::json::parse(root.out);
  EXPECT_EQ(a["solves"][0]["method"], "closed form (noise equation)");
  EXPECT_EQ(b["solves"][0]["method"], "root (TOMS 748)");
  const double m_closed = result_si(a, "target.magnitude"), m_root = result_si(b, "target.magnitude");
  EXPECT_NEAR(m_closed, m_root, 1e-10 * m_root);
  const CliResult text = run_cli(scratch, "run '" + sbv_file + "' --solver root");
  EXPECT_NE(text.out.find("converged in"), std::string::npos);
  EXPECT_NE(text.out.find("root (TOMS 748)"), std::string::npos) << text.out;
  const CliResult bad = run_cli(scratch, "run '" + sbv_file + "' --solver newton");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(count_lines(bad.err), 1u) << bad.err;
  EXPECT_NE(bad.err.find("--solver"), std::string::npos) << bad.err;
}

TEST(CliSolvedOverride, WarnsOnceOnStderrAndKeepsTheExitCode) {
  Scratch scratch;
  const CliResult r = run_cli(scratch, "run '" + sbv_file + "' --set target.magnitude=14");
  EXPECT_EQ(r.exit_code, 0);  // the solve still finds the limit and the [expected] check holds
  EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  EXPECT_EQ(r.err.rfind("radchain: warning: --set target.magnitude=14", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("--no-solve"), std::string::npos) << r.err;
  // A key no solve touches: no warning.
  const CliResult quiet = run_cli(scratch, "run '" + sbv_file + "' --set optics.transmittance=0.5");
  EXPECT_EQ(quiet.err, "");
}

TEST(CliSolvedOverride, CompareWarnsToo) {
  Scratch scratch;
  const CliResult r = run_cli(scratch, "compare '" + sbv_file + "' '" + sbv_file + "' --set target.magnitude=14");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  EXPECT_EQ(r.err.rfind("radchain: warning: --set target.magnitude=14", 0), 0u) << r.err;
}

TEST(CliSolvedOverride, SweepWarnsForAFixedSetOnASolvedUnknown) {
  Scratch scratch;
  const std::string axis = " --set \"optics.aperture=15 cm:30 cm:3\" --results target.magnitude";
  const CliResult r = run_cli(scratch, "sweep '" + sbv_file + "'" + axis + " --set target.magnitude=14");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  EXPECT_EQ(r.err.rfind("radchain: warning: --set target.magnitude=14", 0), 0u) << r.err;
  const CliResult quiet = run_cli(scratch, "sweep '" + sbv_file + "'" + axis);
  EXPECT_EQ(quiet.err, "");
  EXPECT_EQ(quiet.out, r.out);  // the solve overwrote the value set at every point
}

// The executable links neither OpenImageIO nor FFTW: render, validate and mtf load them through the module.
TEST(CliImagingModule, TheExecutableLinksNoImagingLibraries) {
  Scratch scratch;
  const fs::path listing = scratch / "ldd.txt";
  ASSERT_EQ(std::system(("ldd '" RADCHAIN_CLI "' >'" + listing.string() + "'").c_str()), 0);
  const std::string libraries = read_text(listing);
  EXPECT_EQ(libraries.find("libOpenImageIO"), std::string::npos) << libraries;
  EXPECT_EQ(libraries.find("libfftw3"), std::string::npos) << libraries;
  EXPECT_EQ(libraries.find("libradchain-imaging"), std::string::npos) << libraries;
}

// A copy of the executable without the module next to it: the other commands run, the imaging ones fail
// with one line and exit 2.
TEST(CliImagingModule, MissingModuleIsOneLineAndExitTwo) {
  Scratch scratch;
  const fs::path copy = scratch / "bin" / "radchain";
  fs::create_directories(copy.parent_path());
  fs::copy_file(RADCHAIN_CLI, copy);
  auto run_copy = [&](const std::string& arguments) {
    const fs::path out = scratch / "copy-out.txt", err = scratch / "copy-err.txt";
    const int status = std::system(("'" + copy.string() + "' " + arguments + " >'" + out.string() + "' 2>'" + err.string() + "'").c_str());
    return CliResult{WIFEXITED(status) ? WEXITSTATUS(status) : -1, read_text(out), read_text(err)};
  };
  EXPECT_EQ(run_copy("run '" + sbv_file + "'").exit_code, 0);
  const CliResult r = run_copy("mtf '" + source_dir + "/sensors/kolobrodov-1996-ccd151-computed.toml'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("radchain-imaging-commands.so: not found"), std::string::npos) << r.err;
}

}  // namespace
