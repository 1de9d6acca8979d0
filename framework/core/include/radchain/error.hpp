#pragma once
// One error type for every kind of bad input. It renders as one line:
//   sensors/sbv.toml:14:15: optics (plugin "telescope"): aperture = "15 kg": expected a length, e.g. "15 cm"
// The CLI prints what() and exits with ExitCode::bad_input.
#include <stdexcept>
#include <string>
#include <vector>

namespace radchain {

enum class ExitCode : int { ok = 0, failed_check = 1, bad_input = 2 };

// Where a value came from: a file and a 1-based line and column (0 = unknown).
struct SourceLocation {
  std::string file;
  int line = 0;
  int column = 0;
  std::string str() const;  // "file:line:col", "file:line", "file" or ""
};

class InputError : public std::runtime_error {
 public:
  // context: e.g. `optics (plugin "telescope")`; subject: e.g. `aperture = "15 kg"`; problem: what is
  // expected or wrong. Empty parts are left out of the rendered line.
  InputError(SourceLocation where, std::string context, std::string subject, std::string problem);

  const SourceLocation& where() const noexcept { return where_; }
  const std::string& context() const noexcept { return context_; }
  const std::string& subject() const noexcept { return subject_; }
  const std::string& problem() const noexcept { return problem_; }

  // A copy with the context filled in (used when a lower layer did not know the section).
  InputError with_context(const std::string& context) const;
  InputError with_location(const SourceLocation& where) const;

 private:
  SourceLocation where_;
  std::string context_, subject_, problem_;
};

// The accepted value closest to `given` (Damerau-free Levenshtein), or "" if nothing is close.
std::string nearest_match(const std::string& given, const std::vector<std::string>& accepted);
// Every "did you mean" of a message: ` (did you mean "<nearest>"?)`, or "" if nothing is close.
std::string did_you_mean(const std::string& given, const std::vector<std::string>& accepted);
// "a, b, c"
std::string join(const std::vector<std::string>& items, const std::string& separator = ", ");

}  // namespace radchain
