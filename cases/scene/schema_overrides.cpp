// Command-line overrides (--set key.path=value) applied to a parsed scene before validation.
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
// Command-line overrides

namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

std::vector<std::string> split_path(std::string_view path, const std::string& assignment) {
  std::vector<std::string> parts;
  while (true) {
    const std::size_t dot = path.find('.');
    const std::string_view part = trim(path.substr(0, dot));
    if (part.empty()) {
      throw std::invalid_argument(
          fmt::format("override '{}': empty key in path (expected key.path=value)", assignment));
    }
    parts.emplace_back(part);
    if (dot == std::string_view::npos) break;
    path.remove_prefix(dot + 1);
  }
  return parts;
}

// Parses "v = <text>" with the override as source path, so that the nodes it yields carry
// "--set ..." as their file in later diagnostics.
toml::table parse_override(const std::string& text, const std::string& source) {
  return toml::parse(std::string_view("v = " + text), std::string_view(source));
}

// An element of an array of tables, by its `name` or by its index.
toml::table* find_element(toml::array& array, const std::string& label) {
  for (toml::node& item : array) {
    auto* element = item.as_table();
    if (!element) continue;
    const auto* name = element->get_as<std::string>("name");
    if (name && name->get() == label) return element;
  }
  std::size_t index = 0;
  const auto [end, ec] = std::from_chars(label.data(), label.data() + label.size(), index);
  if (ec == std::errc{} && end == label.data() + label.size() && index < array.size()) {
    return array.get(index)->as_table();
  }
  return nullptr;
}

std::string element_names(const toml::array& array) {
  std::vector<std::string> names;
  for (std::size_t i = 0; i < array.size(); ++i) {
    const auto* element = array.get(i)->as_table();
    const auto* name = element ? element->get_as<std::string>("name") : nullptr;
    names.push_back(name ? name->get() : std::to_string(i));
  }
  return names.empty() ? "none" : fmt::format("{}", fmt::join(names, ", "));
}

}  // namespace

void apply_override(toml::table& document, const std::string& assignment) {
  apply_override(document, assignment, "--set " + assignment);
}

void apply_override(toml::table& document, const std::string& assignment,
                    const std::string& source) {
  const std::size_t eq = assignment.find('=');
  if (eq == std::string::npos) {
    throw std::invalid_argument(
        fmt::format("override '{}' has no '=': expected key.path=value", assignment));
  }
  const std::vector<std::string> parts =
      split_path(std::string_view(assignment).substr(0, eq), assignment);
  const std::string value(trim(std::string_view(assignment).substr(eq + 1)));

  // The key region of "v" in the parsed override: used for every key the override creates, so
  // that an unknown key introduced on the command line is reported against "--set ...".
  toml::table parsed;
  try {
    parsed = parse_override(value, source);
  } catch (const toml::parse_error&) {
    // Not TOML ("0.25 mm", "linear"): take the raw text as a string.
    parsed = parse_override(quoted(value), source);
  }
  const auto v = parsed.find("v");
  const toml::source_region key_region = v->first.source();

  toml::table* current = &document;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    toml::node* next = current->get(parts[i]);
    if (!next) {
      // Created tables get a source too (by parsing), so diagnostics about them name the override.
      toml::table created = std::move(*parse_override("{}", source).get_as<toml::table>("v"));
      created.is_inline(false);
      current->insert_or_assign(toml::key(parts[i], key_region), std::move(created));
      current = current->get_as<toml::table>(parts[i]);
    } else if (auto* table = next->as_table()) {
      current = table;
    } else if (auto* array = next->as_array()) {
      if (i + 2 >= parts.size()) {
        throw std::invalid_argument(
            fmt::format("override '{}': '{}' is an array of tables; name an element and a key, as "
                        "in {}.<name>.<key>",
                        assignment, parts[i], parts[i]));
      }
      ++i;
      current = find_element(*array, parts[i]);
      if (!current) {
        throw std::invalid_argument(
            fmt::format("override '{}': there is no [[{}]] element named '{}' (elements: {})",
                        assignment, parts[i - 1], parts[i], element_names(*array)));
      }
    } else {
      throw std::invalid_argument(
          fmt::format("override '{}': '{}' is a value, not a table", assignment, parts[i]));
    }
  }
  // Erase first: insert_or_assign would keep the old key and with it the old source position.
  current->erase(parts.back());
  v->second.visit([&](auto& node) {
    current->insert_or_assign(toml::key(parts.back(), key_region), std::move(node));
  });
}

}  // namespace hvi::scene
