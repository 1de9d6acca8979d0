#include "radchain/error.hpp"

#include <algorithm>
#include <fmt/format.h>

namespace radchain {

std::string SourceLocation::str() const {
  if (file.empty()) return {};
  if (line <= 0) return file;
  if (column <= 0) return fmt::format("{}:{}", file, line);
  return fmt::format("{}:{}:{}", file, line, column);
}

static std::string render(const SourceLocation& where, const std::string& context, const std::string& subject,
                          const std::string& problem) {
  std::string line;
  for (const std::string* part : {&context, &subject, &problem}) {
    if (part->empty()) continue;
    if (!line.empty()) line += ": ";
    line += *part;
  }
  const std::string location = where.str();
  return location.empty() ? line : location + ": " + line;
}

InputError::InputError(SourceLocation where, std::string context, std::string subject, std::string problem)
    : std::runtime_error(render(where, context, subject, problem)),
      where_(std::move(where)),
      context_(std::move(context)),
      subject_(std::move(subject)),
      problem_(std::move(problem)) {}

InputError InputError::with_context(const std::string& context) const {
  return InputError(where_, context, subject_, problem_);
}
InputError InputError::with_location(const SourceLocation& where) const {
  return InputError(where, context_, subject_, problem_);
}

static std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0u : 1u)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string did_you_mean(const std::string& given, const std::vector<std::string>& accepted) {
  const std::string near = nearest_match(given, accepted);
  return near.empty() ? std::string() : " (did you mean \"" + near + "\"?)";
}

std::string nearest_match(const std::string& given, const std::vector<std::string>& accepted) {
  std::string best;
  std::size_t best_distance = std::max<std::size_t>(2, given.size() / 3) + 1;
  for (const auto& candidate : accepted) {
    const std::size_t d = edit_distance(given, candidate);
    if (d < best_distance) {
      best_distance = d;
      best = candidate;
    }
  }
  return best;
}

std::string join(const std::vector<std::string>& items, const std::string& separator) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i) out += separator;
    out += items[i];
  }
  return out;
}

}  // namespace radchain
