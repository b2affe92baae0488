// The schema's declarations: ranges, the key builders of TableSpec, and the diagnostics that
// validation (schema_validate.cpp) reports. Overrides are in schema_overrides.cpp, the Markdown
// reference in schema_markdown.cpp.
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

// ---------------------------------------------------------------------------------------------
// Ranges

using text::format_number;

bool Range::contains(double v) const {
  if (std::isnan(v)) return false;
  if (min && (min_inclusive ? v < *min : v <= *min)) return false;
  if (max && (max_inclusive ? v > *max : v >= *max)) return false;
  return true;
}

std::string Range::describe() const {
  if (min && max) {
    return fmt::format("in {}{}, {}{}", min_inclusive ? '[' : '(', format_number(*min),
                       format_number(*max), max_inclusive ? ']' : ')');
  }
  if (min) return fmt::format("{} {}", min_inclusive ? ">=" : ">", format_number(*min));
  if (max) return fmt::format("{} {}", max_inclusive ? "<=" : "<", format_number(*max));
  return "";
}

Range positive() {
  return Range{0.0, std::nullopt, false, true};
}
Range non_negative() {
  return Range{0.0, std::nullopt, true, true};
}
Range closed(double lo, double hi) {
  return Range{lo, hi, true, true};
}
Range left_open(double lo, double hi) {
  return Range{lo, hi, false, true};
}
Range right_open(double lo, double hi) {
  return Range{lo, hi, true, false};
}
Range open_interval(double lo, double hi) {
  return Range{lo, hi, false, false};
}

// ---------------------------------------------------------------------------------------------
// Schema builders

namespace {

template <typename T>
std::shared_ptr<const toml::node> make_default(T value) {
  return std::make_shared<const toml::value<T>>(std::move(value));
}

std::shared_ptr<const toml::node> make_array_default(const std::vector<double>& values) {
  auto array = std::make_shared<toml::array>();
  for (double v : values) array->push_back(v);
  return array;
}

std::shared_ptr<const toml::node> make_array_default(const std::vector<std::string>& values) {
  auto array = std::make_shared<toml::array>();
  for (const std::string& v : values) array->push_back(v);
  return array;
}

Key make_key(std::string name, ValueKind kind, std::string doc) {
  Key key;
  key.name = std::move(name);
  key.kind = kind;
  key.doc = std::move(doc);
  return key;
}

}  // namespace

TableSpec& TableSpec::quantity(std::string name, Dim dim, Range range,
                               std::optional<double> default_si, std::string doc) {
  Key key = make_key(std::move(name), ValueKind::quantity, std::move(doc));
  key.dim = dim;
  key.range = range;
  if (default_si) key.default_value = make_default(*default_si);
  keys.push_back(std::move(key));
  return *this;
}

TableSpec& TableSpec::quantity_required(std::string name, Dim dim, Range range, std::string doc) {
  quantity(std::move(name), dim, range, std::nullopt, std::move(doc));
  keys.back().required = true;
  return *this;
}

TableSpec& TableSpec::optional_quantity(std::string name, Dim dim, Range range, std::string doc) {
  return quantity(std::move(name), dim, range, std::nullopt, std::move(doc));
}

TableSpec& TableSpec::vector(std::string name, Dim dim,
                             std::optional<std::vector<double>> default_si, std::string doc,
                             int components) {
  Key key = make_key(std::move(name), ValueKind::quantity_vector, std::move(doc));
  key.dim = dim;
  key.components = components;
  if (default_si) key.default_value = make_array_default(*default_si);
  keys.push_back(std::move(key));
  return *this;
}

TableSpec& TableSpec::vector_required(std::string name, Dim dim, std::string doc, int components) {
  vector(std::move(name), dim, std::nullopt, std::move(doc), components);
  keys.back().required = true;
  return *this;
}

TableSpec& TableSpec::number(std::string name, Range range, std::optional<double> default_value,
                             std::string doc) {
  Key key = make_key(std::move(name), ValueKind::number, std::move(doc));
  key.range = range;
  if (default_value) key.default_value = make_default(*default_value);
  keys.push_back(std::move(key));
  return *this;
}

TableSpec& TableSpec::integer(std::string name, Range range, std::optional<long long> default_value,
                              std::string doc) {
  Key key = make_key(std::move(name), ValueKind::integer, std::move(doc));
  key.range = range;
  if (default_value) key.default_value = make_default(static_cast<std::int64_t>(*default_value));
  keys.push_back(std::move(key));
  return *this;
}

TableSpec& TableSpec::boolean(std::string name, bool default_value, std::string doc) {
  Key key = make_key(std::move(name), ValueKind::boolean, std::move(doc));
  key.default_value = make_default(default_value);
  keys.push_back(std::move(key));
  return *this;
}

TableSpec& TableSpec::string(std::string name, std::optional<std::string> default_value,
                             std::string doc) {
  Key key = make_key(std::move(name), ValueKind::string, std::move(doc));
  if (default_value) key.default_value = make_default(std::move(*default_value));
  keys.push_back(std::move(key));
  return *this;
}

TableSpec& TableSpec::string_required(std::string name, std::string doc) {
  string(std::move(name), std::nullopt, std::move(doc));
  keys.back().required = true;
  return *this;
}

TableSpec& TableSpec::choice(std::string name, std::vector<std::string> choices,
                             std::optional<std::string> default_value, std::string doc) {
  Key key = make_key(std::move(name), ValueKind::choice, std::move(doc));
  key.choices = std::move(choices);
  if (default_value) key.default_value = make_default(std::move(*default_value));
  keys.push_back(std::move(key));
  return *this;
}

TableSpec& TableSpec::choice_required(std::string name, std::vector<std::string> choices,
                                      std::string doc) {
  choice(std::move(name), std::move(choices), std::nullopt, std::move(doc));
  keys.back().required = true;
  return *this;
}

TableSpec& TableSpec::string_list(std::string name, std::vector<std::string> default_value,
                                  std::string doc) {
  Key key = make_key(std::move(name), ValueKind::string_list, std::move(doc));
  key.default_value = make_array_default(default_value);
  keys.push_back(std::move(key));
  return *this;
}

TableSpec& TableSpec::string_list_required(std::string name, std::string doc) {
  keys.push_back(make_key(std::move(name), ValueKind::string_list, std::move(doc)));
  keys.back().required = true;
  return *this;
}

TableSpec& TableSpec::table(TableSpec sub) {
  tables.push_back(std::move(sub));
  return *this;
}

// ---------------------------------------------------------------------------------------------
// Diagnostics

std::string Diagnostic::text() const {
  std::string out = file;
  if (line > 0) out += fmt::format(":{}:{}", line, column);
  out += ": ";
  if (!key.empty()) {
    out += fmt::format("key '{}'", key);
    if (!value.empty()) out += " = " + value;
    out += ": ";
  }
  out += message;
  return out;
}

using text::diagnostic_at;

Diagnostic Validated::at(const std::string& key, std::string message) const {
  // Walk up the dotted path until something that was written is found ("body.p.radius" ->
  // "body.p" -> "body"); the root is 1:1 of the scene file.
  Diagnostic d;
  std::string path = key;
  while (true) {
    if (auto it = locations.find(path); it != locations.end()) {
      d = diagnostic_at(it->second, file);
      break;
    }
    const std::size_t dot = path.rfind('.');
    if (dot == std::string::npos) {
      d.file = file;
      d.line = 1;
      d.column = 1;
      break;
    }
    path.resize(dot);
  }
  d.key = key;
  d.message = std::move(message);
  return d;
}

}  // namespace hvi::scene
