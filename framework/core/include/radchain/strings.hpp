#pragma once
// The few text helpers the parsers of sensor files, overrides, ranges and data files share (one copy each). For the
// framework's own libraries, not plugins: plugins see parameters already parsed.
#include <string>
#include <string_view>
#include <vector>

namespace radchain::strings {

// `text` without leading and trailing characters of `blanks` (spaces and tabs by default).
inline std::string trimmed(std::string_view text, std::string_view blanks = " \t") {
  const auto first = text.find_first_not_of(blanks);
  if (first == std::string_view::npos) return {};
  return std::string(text.substr(first, text.find_last_not_of(blanks) - first + 1));
}

// "\"25 cm\"" -> "25 cm": one pair of enclosing double quotes removed (a TOML string written on a command line).
inline std::string unquoted(std::string text) {
  if (text.size() >= 2 && text.front() == '"' && text.back() == '"') text = text.substr(1, text.size() - 2);
  return text;
}

// "a:b::c" -> {"a", "b", "", "c"}: every separator splits, so n separators give n + 1 parts ("" gives {""}).
inline std::vector<std::string> split(std::string_view text, char separator) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (std::size_t at; (at = text.find(separator, start)) != std::string_view::npos; start = at + 1)
    parts.emplace_back(text.substr(start, at - start));
  parts.emplace_back(text.substr(start));
  return parts;
}

}  // namespace radchain::strings
