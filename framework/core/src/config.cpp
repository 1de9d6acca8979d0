// The only file that sees toml++: it turns a TOML document into the framework's ConfigValue tree.
#include "radchain/config.hpp"
#include "radchain/input_file.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <fmt/format.h>

namespace radchain {
namespace {

SourceLocation location_of(const toml::node& node, const std::string& file) {
  const auto& begin = node.source().begin;
  return SourceLocation{file, static_cast<int>(begin.line), static_cast<int>(begin.column)};
}

// Limits on the shape of a document: a dotted key of thousands of parts overflowed the stack, in the
// conversion below and (at ~50,000 parts) inside toml++. No sensor file needs more than a few levels.
constexpr std::size_t max_key_parts = 64;    // parts of one dotted key or table header
constexpr std::size_t max_depth = 128;       // tables and arrays nested (toml++ caps inline nesting at 256)
constexpr std::size_t max_key_length = 256;  // characters of one key

// Before toml++ sees the text: the dots of each key, outside strings and comments. A value has at most one dot
// (1.5, a time's fraction), so counting every dot between two of = [ ] { } , and a line end is conservative.
void check_key_parts(std::string_view text, const std::string& file) {
  int line = 1, column = 0;
  std::size_t dots = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      column = 0;
      dots = 0;
      continue;
    }
    ++column;
    if (c == '#') {
      while (i + 1 < text.size() && text[i + 1] != '\n') ++i;
    } else if (c == '"' || c == '\'') {
      const bool triple = text.substr(i, 3) == std::string(3, c);
      i += triple ? 3 : 1;
      for (; i < text.size(); ++i) {
        if (text[i] == '\n') {
          if (!triple) break;  // an unterminated string: toml++ reports it
          ++line;
          column = 0;
        } else if (c == '"' && text[i] == '\\' && i + 1 < text.size() && text[i + 1] != '\n') {
          ++i;
        } else if (text[i] == c && (!triple || text.substr(i, 3) == std::string(3, c))) {
          if (triple) i += 2;
          break;
        }
      }
      if (i < text.size() && text[i] == '\n') --i;  // the line end is counted above
    } else if (c == '=' || c == '[' || c == ']' || c == '{' || c == '}' || c == ',') {
      dots = 0;
    } else if (c == '.' && ++dots >= max_key_parts) {
      throw InputError(SourceLocation{file, line, column}, "TOML syntax", "",
                       fmt::format("a dotted key of more than {} parts (no sensor file nests that deep)", max_key_parts));
    }
  }
}

ConfigValue convert(const toml::node& node, const std::string& file, std::size_t depth = 0) {
  ConfigValue out;
  out.where = location_of(node, file);
  if (depth > max_depth)
    throw InputError(out.where, "TOML syntax", "", fmt::format("tables or arrays nested more than {} deep", max_depth));
  switch (node.type()) {
    case toml::node_type::string:
      out.type = ConfigValue::Type::string;
      out.string_value = std::string(*node.value<std::string_view>());
      break;
    case toml::node_type::integer:
      out.type = ConfigValue::Type::integer;
      out.integer_value = *node.value<std::int64_t>();
      break;
    case toml::node_type::floating_point:
      out.type = ConfigValue::Type::floating;
      out.floating_value = *node.value<double>();
      break;
    case toml::node_type::boolean:
      out.type = ConfigValue::Type::boolean;
      out.boolean_value = *node.value<bool>();
      break;
    case toml::node_type::array:
      out.type = ConfigValue::Type::array;
      for (const auto& item : *node.as_array()) out.items.push_back(convert(item, file, depth + 1));
      break;
    case toml::node_type::table: {
      out.type = ConfigValue::Type::table;
      for (const auto& [key, value] : *node.as_table()) {
        if (key.str().size() > max_key_length)
          throw InputError(location_of(value, file), "TOML syntax", std::string(key.str().substr(0, 40)) + "…",
                           fmt::format("a key of {} characters: at most {}", key.str().size(), max_key_length));
        ConfigValue member = convert(value, file, depth + 1);
        // The key's own position is where an "unknown key" error should point.
        const auto& key_begin = key.source().begin;
        if (key_begin.line) member.where = SourceLocation{file, int(key_begin.line), int(key_begin.column)};
        out.members.emplace_back(std::string(key.str()), std::move(member));
      }
      // toml++ keeps keys sorted; messages and reports follow the file's order instead.
      std::stable_sort(out.members.begin(), out.members.end(), [](const auto& a, const auto& b) {
        return std::tie(a.second.where.line, a.second.where.column) < std::tie(b.second.where.line, b.second.where.column);
      });
      break;
    }
    default:
      out.type = ConfigValue::Type::other;  // dates and times: no radchain key takes them
      break;
  }
  return out;
}

ConfigValue parse(std::string_view text, const std::string& name) {
  try {
    check_key_parts(text, name);
    toml::table table = toml::parse(text, std::string_view(name));
    ConfigValue root = convert(table, name);
    root.where = SourceLocation{name, 0, 0};
    return root;
  } catch (const toml::parse_error& error) {
    const auto& begin = error.source().begin;
    throw InputError(SourceLocation{name, int(begin.line), int(begin.column)}, "TOML syntax", "",
                     std::string(error.description()));
  }
}

}  // namespace

const ConfigValue* ConfigValue::find(const std::string& key) const {
  for (const auto& [name, value] : members)
    if (name == key) return &value;
  return nullptr;
}
ConfigValue* ConfigValue::find(const std::string& key) {
  for (auto& [name, value] : members)
    if (name == key) return &value;
  return nullptr;
}

std::string ConfigValue::as_toml() const {
  switch (type) {
    case Type::string: return "\"" + string_value + "\"";
    case Type::integer: return std::to_string(integer_value);
    case Type::floating: {
      // As written: 12.0 stays a float in messages ("adc_bits = 12.0: expected an integer"), not "12".
      std::string text = fmt::format("{}", floating_value);
      if (text.find_first_of(".eEni") == std::string::npos) text += ".0";
      return text;
    }
    case Type::boolean: return boolean_value ? "true" : "false";
    case Type::array: {
      std::vector<std::string> parts;
      for (const auto& item : items) parts.push_back(item.as_toml());
      return "[" + join(parts) + "]";
    }
    case Type::table: {
      std::vector<std::string> parts;
      for (const auto& [key, value] : members) parts.push_back(key + " = " + value.as_toml());
      return "{ " + join(parts) + " }";
    }
    default: return "(date/time)";
  }
}

std::string ConfigValue::type_name() const {
  switch (type) {
    case Type::string: return "a string";
    case Type::integer: return "an integer";
    case Type::floating: return "a number";
    case Type::boolean: return "a boolean";
    case Type::array: return "an array";
    case Type::table: return "a table";
    default: return "a date/time";
  }
}

ConfigValue parse_toml_file(const std::string& path) {
  return parse(read_input_file(path, "sensor file", max_sensor_file_bytes), path);
}

ConfigValue parse_toml_text(const std::string& text, const std::string& name_for_messages) {
  return parse(text, name_for_messages);
}

ConfigValue parse_toml_value(const std::string& text, const std::string& name_for_messages) {
  try {
    check_key_parts(text, name_for_messages);
    toml::table table = toml::parse("v = " + text, std::string_view(name_for_messages));
    ConfigValue value = convert(*table.get("v"), name_for_messages);
    value.where = SourceLocation{name_for_messages, 0, 0};
    return value;
  } catch (const toml::parse_error&) {
    ConfigValue value;  // not TOML: a bare word such as 20 cm is meant as a string
    value.type = ConfigValue::Type::string;
    value.string_value = text;
    value.where = SourceLocation{name_for_messages, 0, 0};
    return value;
  }
}

}  // namespace radchain
