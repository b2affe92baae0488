// The Markdown reference of every key (`hvi keys`, docs/user/scene_keys.md).
#include "cases/scene/schema.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <utility>

#include <fmt/format.h>

#include "cases/scene/schema_text.hpp"

namespace hvi::scene {

using namespace text;

// ---------------------------------------------------------------------------------------------
// Markdown reference

namespace {

std::string cell(std::string text) {
  std::string out;
  for (const char c : text) {
    if (c == '|')
      out += "\\|";
    else if (c == '\n')
      out += ' ';
    else
      out += c;
  }
  return out.empty() ? "—" : out;
}

std::string type_cell(const Key& key) {
  switch (key.kind) {
    case ValueKind::quantity:
      return key.dim == dims::none ? "number" : dimension_name(key.dim);
    case ValueKind::quantity_vector:
      return fmt::format("{} vector[{}]", dimension_name(key.dim), key.components);
    case ValueKind::number:
      return "number";
    case ValueKind::integer:
      return "integer";
    case ValueKind::boolean:
      return "boolean";
    case ValueKind::string:
      return "string";
    case ValueKind::choice:
      return "choice";
    case ValueKind::string_list:
      return "string list";
  }
  return "";
}

std::string range_cell(const Key& key) {
  switch (key.kind) {
    case ValueKind::quantity:
    case ValueKind::quantity_vector:
    case ValueKind::number:
    case ValueKind::integer:
      return key.range.describe();
    case ValueKind::choice: {
      std::vector<std::string> items;
      for (const std::string& c : key.choices) items.push_back(fmt::format("`{}`", c));
      return fmt::format("{}", fmt::join(items, ", "));
    }
    default:
      return "";
  }
}

std::string default_cell(const Key& key) {
  if (key.required) return "required";
  if (!key.default_value) return "";
  return fmt::format("`{}`", with_unit(render(*key.default_value, false), unit_of(key)));
}

void append_table(std::string& out, const TableSpec& spec, const std::string& spec_path) {
  const bool has_content = !spec.keys.empty() || !spec.doc.empty() || !spec_path.empty();
  if (has_content) {
    out +=
        fmt::format("### {}\n\n", spec_path.empty() ? "Top level" : heading(spec_path, spec.array));
    if (!spec.doc.empty()) out += spec.doc + "\n\n";
    if (spec.required) out += spec.array ? "At least one is required.\n\n" : "Required.\n\n";
    if (!spec.one_of.empty()) {
      std::vector<std::string> alternatives;
      for (const std::string& name : spec.one_of) {
        alternatives.push_back(heading(join_path(spec_path, name), false));
      }
      out += fmt::format("Exactly one of {}.\n\n", fmt::join(alternatives, ", "));
    }
  }
  if (!spec.keys.empty()) {
    out += "| key | type | unit | range | default | description |\n";
    out += "|---|---|---|---|---|---|\n";
    for (const Key& key : spec.keys) {
      out += fmt::format("| `{}` | {} | {} | {} | {} | {} |\n", key.name, cell(type_cell(key)),
                         cell(unit_of(key)), cell(range_cell(key)), cell(default_cell(key)),
                         cell(key.doc));
    }
    out += "\n";
  }
  for (const TableSpec& sub : spec.tables) append_table(out, sub, join_path(spec_path, sub.name));
}

}  // namespace

std::string markdown_reference(const TableSpec& root) {
  std::string out;
  append_table(out, root, "");
  return out;
}

}  // namespace hvi::scene
