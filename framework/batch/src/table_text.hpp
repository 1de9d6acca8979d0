#pragma once
// Text shared by the table writer (table.cpp) and the shard reader (shard.cpp): CSV records, JSON strings, the
// shard file's framing. Private to radchain::batch.
#include "radchain/batch/table.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <istream>
#include <ostream>
#include <string>
#include <vector>

namespace radchain::table_detail {

inline constexpr const char* shard_magic = "# radchain shard ";
inline constexpr const char* trailer_magic = "# end ";

inline std::string csv_cell(const std::string& cell) {
  if (cell.find_first_of(",\"\n\r") == std::string::npos) return cell;
  std::string quoted = "\"";
  for (char c : cell) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

inline void write_csv_record(std::ostream& out, const std::vector<std::string>& cells, const std::string* first = nullptr) {
  std::string line;
  if (first) line = *first;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (first || i > 0) line += ',';
    line += csv_cell(cells[i]);
  }
  line += '\n';
  out << line;
}

// One CSV record starting with `line` (further lines are read while a quoted cell is open).
inline bool parse_csv_record(std::istream& in, std::string line, std::vector<std::string>& cells) {
  cells.clear();
  std::string cell;
  bool quoted = false;
  for (std::size_t i = 0;; ++i) {
    if (i == line.size()) {
      if (!quoted) break;
      std::string more;
      if (!std::getline(in, more)) return false;  // an open quote at the end of the file
      cell += '\n';
      line = std::move(more);
      i = static_cast<std::size_t>(-1);
      continue;
    }
    const char c = line[i];
    if (quoted) {
      if (c == '"') {
        if (i + 1 < line.size() && line[i + 1] == '"') {
          cell += '"';
          ++i;
        } else {
          quoted = false;
        }
      } else {
        cell += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      cells.push_back(std::move(cell));
      cell.clear();
    } else {
      cell += c;
    }
  }
  cells.push_back(std::move(cell));
  return true;
}

inline std::string json_string(const std::string& text) {
  return nlohmann::json(text).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

// A numeric cell as a JSON value: the number as written (without a leading '+'), null when empty or not finite.
inline std::string json_number(const std::string& cell) {
  std::string text = cell;
  if (!text.empty() && text.front() == '+') text.erase(0, 1);
  if (text.empty()) return "null";
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size()) return json_string(cell);
  if (!std::isfinite(v)) return "null";
  // JSON wants a digit before '.', and no leading zeros.
  if (text.front() == '.') text.insert(0, "0");
  if (text.size() > 1 && text[0] == '-' && text[1] == '.') text.insert(1, "0");
  return text;
}

// Display width of UTF-8 text (code points; every character the tables print is one column wide).
inline std::size_t display_width(const std::string& text) {
  std::size_t width = 0;
  for (unsigned char c : text)
    if ((c & 0xC0) != 0x80) ++width;
  return width;
}

// The first `width` columns of UTF-8 text, the last of them "…" when the text is longer.
inline std::string truncated(const std::string& text, std::size_t width) {
  if (display_width(text) <= width) return text;
  if (width == 0) return {};
  std::string out;
  std::size_t columns = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if ((c & 0xC0) != 0x80 && ++columns > width - 1) break;
    out += text[i];
  }
  return out + "…";
}

inline std::string padded(const std::string& text, std::size_t width, bool right) {
  const std::size_t w = display_width(text);
  if (w >= width) return text;
  const std::string pad(width - w, ' ');
  return right ? pad + text : text + pad;
}

inline std::string types_text(const std::vector<bool>& numeric) {
  std::string types;
  for (bool n : numeric) types += n ? 'n' : 't';
  return types;
}

inline std::size_t parse_count(const std::string& text) {
  std::size_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || text.empty()) throw std::invalid_argument(text);
  return value;
}

}  // namespace radchain::table_detail
