#pragma once
// Helpers for the CLI tests: run `radchain ...` and capture exit code, stdout and stderr; a scratch folder per
// test process; sensor files derived from sensors/msx-sbv.toml.
// radchain headers first: <sys/wait.h> pulls in <signal.h>, whose si_value macro breaks schema.hpp's
// in_range(double si_value).
#include "radchain/chain.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace radchain::test {
namespace fs = std::filesystem;

inline const std::string source_dir = RADCHAIN_SOURCE_DIR;
inline const std::string sbv_file = source_dir + "/sensors/msx-sbv.toml";

inline std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

inline void write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

// A folder of its own for each test process (gtest_discover_tests runs every test in a process of its own).
class Scratch {
 public:
  Scratch() : dir_(fs::temp_directory_path() / ("radchain_cli_test_" + std::to_string(::getpid()))) {
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path operator/(const std::string& name) const { return dir_ / name; }
  const fs::path& path() const { return dir_; }

 private:
  fs::path dir_;
};

struct CliResult {
  int exit_code = -1;
  std::string out, err;
};

// Runs the CLI with `arguments` (shell syntax) and captures its output.
inline CliResult run_cli(const Scratch& scratch, const std::string& arguments) {
  static int counter = 0;
  const fs::path out = scratch / ("out" + std::to_string(counter) + ".txt");
  const fs::path err = scratch / ("err" + std::to_string(counter++) + ".txt");
  const std::string command = "'" RADCHAIN_CLI "' " + arguments + " >'" + out.string() + "' 2>'" + err.string() + "'";
  const int status = std::system(command.c_str());
  CliResult result;
  if (WIFEXITED(status)) result.exit_code = WEXITSTATUS(status);
  result.out = read_text(out);
  result.err = read_text(err);
  return result;
}

// A shell command line with stderr (and stdout unless the command redirects it) captured.
inline CliResult run_shell(const Scratch& scratch, const std::string& command_line) {
  static int counter = 0;
  const fs::path out = scratch / ("shell_out" + std::to_string(counter) + ".txt");
  const fs::path err = scratch / ("shell_err" + std::to_string(counter++) + ".txt");
  const std::string command = "{ " + command_line + " ; } >'" + out.string() + "' 2>'" + err.string() + "'";
  const int status = std::system(command.c_str());
  CliResult result;
  if (WIFEXITED(status)) result.exit_code = WEXITSTATUS(status);
  result.out = read_text(out);
  result.err = read_text(err);
  return result;
}

// sensors/msx-sbv.toml with one text replaced (the test fails loudly if `from` is not in the file).
inline std::string sbv_with(const std::string& from, const std::string& to) {
  std::string text = read_text(sbv_file);
  const auto at = text.find(from);
  if (at == std::string::npos) return "# replacement target not found: " + from + "\n" + text + "\n[[[";
  return text.replace(at, from.size(), to);
}

inline std::size_t count_lines(const std::string& text) {
  std::size_t n = 0;
  for (char c : text) n += c == '\n' ? 1 : 0;
  return n;
}

}  // namespace radchain::test
