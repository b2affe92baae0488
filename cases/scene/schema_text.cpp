#include "cases/scene/schema_text.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>

#include <fmt/format.h>

namespace hvi::scene::text {

std::string format_number(double v) {
  return fmt::format("{}", v);
}

Diagnostic diagnostic_at(const toml::source_region& where, const std::string& fallback_file) {
  Diagnostic d;
  d.file = where.path && !where.path->empty() ? *where.path : fallback_file;
  d.line = static_cast<int>(where.begin.line);
  d.column = static_cast<int>(where.begin.column);
  return d;
}

std::string quoted(std::string_view s) {
  std::string out = "\"";
  for (const char c : s) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\r':
        out += "\\r";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
          out += fmt::format("\\u{:04X}", static_cast<unsigned char>(c));
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

// A floating point number in TOML syntax: "1.0" rather than "1", so that a message about an
// integer key written as 1.0 shows what was actually written.
std::string toml_float(double v) {
  std::string s = format_number(v);
  if (std::isfinite(v) && s.find_first_of(".eE") == std::string::npos) s += ".0";
  return s;
}

// A value as it would be written in TOML, shortened so that a diagnostic stays one line.
// toml++'s own formatter is not used because it prints 5e-4 as 0.00050000000000000001.
// `toml_syntax` false prints floats the short way ("0" instead of "0.0"), for documentation.
std::string render(const toml::node& node, bool toml_syntax) {
  std::string out;
  if (const auto* s = node.as_string()) {
    out = quoted(s->get());
  } else if (const auto* i = node.as_integer()) {
    out = fmt::format("{}", i->get());
  } else if (const auto* f = node.as_floating_point()) {
    out = toml_syntax ? toml_float(f->get()) : format_number(f->get());
  } else if (const auto* b = node.as_boolean()) {
    out = b->get() ? "true" : "false";
  } else if (const auto* a = node.as_array()) {
    std::vector<std::string> items;
    for (const toml::node& item : *a) items.push_back(render(item, toml_syntax));
    out = fmt::format("[{}]", fmt::join(items, ", "));
  } else if (node.is_table()) {
    out = "{...}";
  } else {
    std::ostringstream os;  // dates and times
    node.visit([&](const auto& v) { os << v; });
    out = os.str();
  }
  constexpr std::size_t kMaxLength = 60;
  if (out.size() > kMaxLength) out = out.substr(0, kMaxLength - 3) + "...";
  return out;
}

// "a string", "an integer", ...: what the user wrote, for "got ..." messages.
std::string type_phrase(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a floating point number";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return node.is_array_of_tables() ? "an array of tables" : "an array";
    case toml::node_type::date:
      return "a date";
    case toml::node_type::time:
      return "a time";
    case toml::node_type::date_time:
      return "a date-time";
    default:
      return "nothing";
  }
}

std::string join_path(const std::string& path, std::string_view name) {
  return path.empty() ? std::string(name) : fmt::format("{}.{}", path, name);
}

std::string quoted_list(const std::vector<std::string>& items) {
  std::vector<std::string> q;
  for (const std::string& item : items) q.push_back(quoted(item));
  return fmt::format("{}", fmt::join(q, ", "));
}

// The phrase for what a key expects: "a length (e.g. "0.5 mm")", "a number", ...
std::string expected_phrase(const Key& key) {
  switch (key.kind) {
    case ValueKind::quantity:
      if (key.dim == dims::none) return "a number";
      return fmt::format("{} (e.g. \"{}\")", dimension_phrase(key.dim), example_value(key.dim));
    case ValueKind::quantity_vector: {
      std::vector<std::string> example(static_cast<std::size_t>(std::max(key.components, 1)), "0");
      example.front() = quoted(example_value(key.dim));
      return fmt::format("an array of {} {} values (e.g. [{}])", key.components,
                         dimension_name(key.dim), fmt::join(example, ", "));
    }
    case ValueKind::number:
      return "a number";
    case ValueKind::integer:
      return "an integer";
    case ValueKind::boolean:
      return "true or false";
    case ValueKind::string:
      return "a string";
    case ValueKind::choice:
      return "one of " + quoted_list(key.choices);
    case ValueKind::string_list:
      return "an array of strings";
  }
  return "a value";
}

// The unit to print after a range bound or default of a key ("m/s"); empty when dimensionless.
std::string unit_of(const Key& key) {
  if (key.kind != ValueKind::quantity && key.kind != ValueKind::quantity_vector) return "";
  return si_unit(key.dim);
}

std::string with_unit(std::string text, const std::string& unit) {
  return unit.empty() ? text : text + " " + unit;
}

// Heading of a table spec path for messages and Markdown: "[grid]", "[[body]]", "[body.sphere]".
std::string heading(const std::string& spec_path, bool array) {
  if (spec_path.empty()) return "the top level";
  return array ? fmt::format("[[{}]]", spec_path) : fmt::format("[{}]", spec_path);
}

}  // namespace hvi::scene::text
