// Validation of scene documents against the declared key schema. The walk mirrors the schema:
// for every declared table it checks the keys that were written, reports the ones that were not
// declared, fills in defaults and recurses into sub-tables. Every problem becomes a Diagnostic and
// the walk continues, so one run of the validator reports all mistakes of a scene file at once.
#include "cases/driver/schema.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <utility>

#include <fmt/format.h>

namespace hvi::scene {

// ---------------------------------------------------------------------------------------------
// Ranges

namespace {

std::string format_number(double v) {
  return fmt::format("{}", v);
}

}  // namespace

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

namespace {

Diagnostic diagnostic_at(const toml::source_region& where, const std::string& fallback_file) {
  Diagnostic d;
  d.file = where.path && !where.path->empty() ? *where.path : fallback_file;
  d.line = static_cast<int>(where.begin.line);
  d.column = static_cast<int>(where.begin.column);
  return d;
}

}  // namespace

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

// ---------------------------------------------------------------------------------------------
// Helpers for messages

namespace {

// Optimal string alignment distance (Levenshtein plus adjacent transpositions), so that the
// common typos "cell_szie" (transposition) and "cellsize" (deletion) are both one edit away.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::vector<std::size_t>> d(n + 1, std::vector<std::size_t>(m + 1));
  for (std::size_t i = 0; i <= n; ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= m; ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= n; ++i) {
    for (std::size_t j = 1; j <= m; ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
      }
    }
  }
  return d[n][m];
}

// The candidate closest to `word`, if it is close enough to be a plausible typo.
std::optional<std::string> closest(std::string_view word,
                                   const std::vector<std::string>& candidates) {
  const std::size_t limit = std::max<std::size_t>(2, word.size() / 3);
  std::optional<std::string> best;
  std::size_t best_distance = limit + 1;
  for (const std::string& candidate : candidates) {
    const std::size_t distance = edit_distance(word, candidate);
    if (distance < best_distance) {
      best_distance = distance;
      best = candidate;
    }
  }
  return best;
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
std::string render(const toml::node& node, bool toml_syntax = true) {
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

// A table that cannot be created from defaults alone because something in it must be written.
bool needs_input(const TableSpec& spec) {
  if (!spec.one_of.empty()) return true;
  for (const Key& key : spec.keys) {
    if (key.required) return true;
  }
  for (const TableSpec& sub : spec.tables) {
    if (sub.required) return true;
  }
  return false;
}

bool contains(const std::vector<std::string>& list, std::string_view item) {
  return std::find(list.begin(), list.end(), item) != list.end();
}

void insert_copy(toml::table& out, std::string_view name, const toml::node& value) {
  value.visit([&](const auto& v) { out.insert_or_assign(name, v); });
}

// Where a key/value or table was written: key position for key/value pairs (what an editor
// should jump to), header position for tables; `fallback` when the node has no source (it was
// created programmatically).
toml::source_region region_of(const toml::node& node, const toml::source_region& fallback) {
  return node.source().begin.line > 0 ? node.source() : fallback;
}

toml::source_region region_of(const toml::key& key, const toml::node& node,
                              const toml::source_region& fallback) {
  return key.source().begin.line > 0 ? key.source() : region_of(node, fallback);
}

// A key/value pair of a written table, or nothing.
struct Entry {
  const toml::key* key = nullptr;
  const toml::node* node = nullptr;
  explicit operator bool() const { return node != nullptr; }
};

Entry find_entry(const toml::table* table, std::string_view name) {
  if (!table) return {};
  const auto it = table->find(name);
  if (it == table->end()) return {};
  return Entry{&it->first, &it->second};
}

// ---------------------------------------------------------------------------------------------
// The validator

// Paths of a table being validated: `data` names array elements ("body.projectile"), `spec`
// names the declaration ("body") and is what headings in messages show.
struct TablePath {
  std::string data;
  std::string spec;
  bool array = false;
  std::string child_data(std::string_view name) const { return join_path(data, name); }
  std::string child_spec(std::string_view name) const { return join_path(spec, name); }
};

class Validator {
 public:
  Validator(const toml::table& document, const std::string& file, Validated& out)
      : out_(out), file_(file), file_ptr_(std::make_shared<const std::string>(file)) {
    if (document.source().path) main_path_ = *document.source().path;
  }

  toml::table table(const toml::table* given, const TableSpec& spec, const TablePath& path,
                    const toml::source_region& where) {
    toml::table resolved;
    if (given) report_unknown_keys(*given, spec, path);
    for (const Key& key : spec.keys) resolve_key(given, key, path, where, resolved);
    for (const TableSpec& sub : spec.tables) {
      if (sub.array) {
        resolve_array(given, sub, path, where, resolved);
      } else {
        resolve_sub_table(given, sub, spec, path, where, resolved);
      }
    }
    if (!spec.one_of.empty()) check_one_of(given, spec, path, where);
    return resolved;
  }

  // Sorts diagnostics into reading order: the scene file by line and column, then overrides in
  // the order given.
  void sort_errors() {
    auto rank = [&](const Diagnostic& d) {
      const bool main = d.file == file_;
      return std::make_tuple(main ? 0 : 1, main ? d.line : 0, main ? d.column : 0);
    };
    std::stable_sort(out_.errors.begin(), out_.errors.end(),
                     [&](const Diagnostic& a, const Diagnostic& b) { return rank(a) < rank(b); });
  }

  // Regions of the scene file itself are renamed to `file` (the caller's name for it); regions
  // from elsewhere (command-line overrides) keep their own name.
  toml::source_region normalize(toml::source_region region) const {
    if (!region.path || region.path->empty() || *region.path == main_path_) region.path = file_ptr_;
    return region;
  }

 private:
  Validated& out_;
  const std::string& file_;
  std::shared_ptr<const std::string> file_ptr_;
  std::string main_path_;

  void error(const toml::source_region& where, std::string key, std::string value,
             std::string message) {
    Diagnostic d = diagnostic_at(normalize(where), file_);
    d.key = std::move(key);
    d.value = std::move(value);
    d.message = std::move(message);
    out_.errors.push_back(std::move(d));
  }

  void record(const std::string& path, const toml::source_region& where) {
    if (where.begin.line > 0) out_.locations[path] = normalize(where);
  }

  // --- keys ------------------------------------------------------------------------------------

  void report_unknown_keys(const toml::table& given, const TableSpec& spec, const TablePath& path) {
    std::vector<std::string> known;
    std::vector<std::string> listed;  // for the message: tables shown with their brackets
    for (const Key& key : spec.keys) {
      known.push_back(key.name);
      listed.push_back(key.name);
    }
    for (const TableSpec& sub : spec.tables) {
      known.push_back(sub.name);
      listed.push_back(heading(path.child_spec(sub.name), sub.array));
    }
    for (auto&& [key, node] : given) {
      const std::string name(key.str());
      if (contains(known, name)) continue;
      std::string message = path.spec.empty() ? "unknown top-level key"
                                              : "unknown key in " + heading(path.spec, path.array);
      if (const std::optional<std::string> suggestion = closest(name, known)) {
        message += fmt::format("; did you mean '{}'?", *suggestion);
      } else if (listed.empty()) {
        message += " (it declares no keys)";
      } else {
        message += fmt::format("; valid keys: {}", fmt::join(listed, ", "));
      }
      error(region_of(key, node, {}), path.child_data(name), "", std::move(message));
    }
  }

  void resolve_key(const toml::table* given, const Key& key, const TablePath& path,
                   const toml::source_region& where, toml::table& resolved) {
    const std::string key_path = path.child_data(key.name);
    if (const Entry entry = find_entry(given, key.name)) {
      const toml::source_region at = region_of(*entry.key, *entry.node, where);
      record(key_path, at);
      convert(key, *entry.node, key_path, at, resolved);
    } else if (key.required) {
      error(where, key_path, "", "missing required key: expected " + expected_phrase(key));
    } else if (key.default_value) {
      insert_copy(resolved, key.name, *key.default_value);
    }
  }

  void convert(const Key& key, const toml::node& node, const std::string& key_path,
               const toml::source_region& at, toml::table& resolved) {
    switch (key.kind) {
      case ValueKind::quantity:
        if (auto v = quantity_value(key, node, key_path, at, "")) {
          resolved.insert_or_assign(key.name, *v);
        }
        break;
      case ValueKind::quantity_vector:
        if (auto v = vector_value(key, node, key_path, at)) {
          resolved.insert_or_assign(key.name, std::move(*v));
        }
        break;
      case ValueKind::number:
        if (auto v = number_value(key, node, key_path, at)) resolved.insert_or_assign(key.name, *v);
        break;
      case ValueKind::integer:
        if (auto v = integer_value(key, node, key_path, at)) {
          resolved.insert_or_assign(key.name, *v);
        }
        break;
      case ValueKind::boolean:
        if (const auto* b = node.as_boolean()) {
          resolved.insert_or_assign(key.name, b->get());
        } else {
          wrong_type(key, node, key_path, at);
        }
        break;
      case ValueKind::string:
        if (const auto* s = node.as_string()) {
          resolved.insert_or_assign(key.name, s->get());
        } else {
          wrong_type(key, node, key_path, at);
        }
        break;
      case ValueKind::choice:
        if (auto v = choice_value(key, node, key_path, at)) {
          resolved.insert_or_assign(key.name, std::move(*v));
        }
        break;
      case ValueKind::string_list:
        if (auto v = string_list_value(key, node, key_path, at)) {
          resolved.insert_or_assign(key.name, std::move(*v));
        }
        break;
    }
  }

  void wrong_type(const Key& key, const toml::node& node, const std::string& key_path,
                  const toml::source_region& at, const std::string& prefix = "") {
    error(at, key_path, node.is_table() ? "" : render(node),
          fmt::format("{}expected {}, got {}", prefix, expected_phrase(key), type_phrase(node)));
  }

  bool check_range(const Key& key, double v, const toml::node& node, const std::string& key_path,
                   const toml::source_region& at, const std::string& prefix) {
    if (std::isfinite(v) && key.range.contains(v)) return true;
    const std::string unit = unit_of(key);
    const std::string what = key.kind == ValueKind::integer ? "an integer"
                             : key.dim == dims::none        ? "a number"
                                                            : dimension_phrase(key.dim);
    std::string message;
    if (!std::isfinite(v)) {
      message = fmt::format("{}expected a finite {}", prefix,
                            key.dim == dims::none ? "number" : dimension_name(key.dim));
    } else {
      message =
          fmt::format("{}expected {} {}", prefix, what, with_unit(key.range.describe(), unit));
      // For a value written with a unit the SI value makes the comparison with the bound clear.
      if (!unit.empty() && node.is_string()) {
        message += fmt::format(", got {}", with_unit(format_number(v), unit));
      }
    }
    error(at, key_path, render(node), std::move(message));
    return false;
  }

  // A quantity: a plain number (SI) or a string "<number> <unit>" of the key's dimension.
  // `prefix` names the component for vectors ("component 2: ").
  std::optional<double> quantity_value(const Key& key, const toml::node& node,
                                       const std::string& key_path, const toml::source_region& at,
                                       const std::string& prefix) {
    double v = 0.0;
    if (node.is_number()) {
      v = node.value<double>().value_or(0.0);
    } else if (const auto* s = node.as_string()) {
      Quantity q;
      try {
        q = parse_quantity(s->get());
      } catch (const UnitError& e) {
        error(at, key_path, render(node), prefix + e.what());
        return std::nullopt;
      }
      // A unitless string ("0.5") is a number in SI, like an unquoted number.
      if (q.dim != key.dim && q.dim != dims::none) {
        error(at, key_path, render(node),
              fmt::format("{}expected {}, got {}", prefix, expected_phrase(key),
                          dimension_phrase(q.dim)));
        return std::nullopt;
      }
      v = q.si;
    } else {
      wrong_type(key, node, key_path, at, prefix);
      return std::nullopt;
    }
    if (!check_range(key, v, node, key_path, at, prefix)) return std::nullopt;
    return v;
  }

  std::optional<toml::array> vector_value(const Key& key, const toml::node& node,
                                          const std::string& key_path,
                                          const toml::source_region& at) {
    const auto* array = node.as_array();
    if (!array) {
      wrong_type(key, node, key_path, at);
      return std::nullopt;
    }
    if (array->size() != static_cast<std::size_t>(key.components)) {
      error(at, key_path, render(node),
            fmt::format("expected {}, got {} component{}", expected_phrase(key), array->size(),
                        array->size() == 1 ? "" : "s"));
      return std::nullopt;
    }
    toml::array result;
    bool ok = true;
    for (std::size_t i = 0; i < array->size(); ++i) {
      const toml::node& component = *array->get(i);
      const std::string prefix = fmt::format("component {} of {}: ", i + 1, key.components);
      Key scalar = key;
      scalar.kind = ValueKind::quantity;
      const std::optional<double> v =
          quantity_value(scalar, component, key_path, region_of(component, at), prefix);
      ok = ok && v.has_value();
      if (v) result.push_back(*v);
    }
    if (!ok) return std::nullopt;
    return result;
  }

  // A dimensionless number; a string is accepted when it parses as a unitless number ("0.3").
  std::optional<double> number_value(const Key& key, const toml::node& node,
                                     const std::string& key_path, const toml::source_region& at) {
    double v = 0.0;
    if (node.is_number()) {
      v = node.value<double>().value_or(0.0);
    } else if (const auto* s = node.as_string()) {
      Quantity q;
      try {
        q = parse_quantity(s->get());
      } catch (const UnitError& e) {
        error(at, key_path, render(node), fmt::format("expected a number: {}", e.what()));
        return std::nullopt;
      }
      if (q.dim != dims::none) {
        error(at, key_path, render(node),
              fmt::format("expected a number without unit, got {}", dimension_phrase(q.dim)));
        return std::nullopt;
      }
      v = q.si;
    } else {
      wrong_type(key, node, key_path, at);
      return std::nullopt;
    }
    if (!check_range(key, v, node, key_path, at, "")) return std::nullopt;
    return v;
  }

  std::optional<std::int64_t> integer_value(const Key& key, const toml::node& node,
                                            const std::string& key_path,
                                            const toml::source_region& at) {
    const auto* i = node.as_integer();
    if (!i) {
      wrong_type(key, node, key_path, at);
      return std::nullopt;
    }
    if (!check_range(key, static_cast<double>(i->get()), node, key_path, at, "")) {
      return std::nullopt;
    }
    return i->get();
  }

  std::optional<std::string> choice_value(const Key& key, const toml::node& node,
                                          const std::string& key_path,
                                          const toml::source_region& at) {
    const auto* s = node.as_string();
    if (!s) {
      wrong_type(key, node, key_path, at);
      return std::nullopt;
    }
    if (contains(key.choices, s->get())) return s->get();
    std::string message = "invalid choice: expected one of " + quoted_list(key.choices);
    if (const std::optional<std::string> suggestion = closest(s->get(), key.choices)) {
      message += fmt::format("; did you mean {}?", quoted(*suggestion));
    }
    error(at, key_path, render(node), std::move(message));
    return std::nullopt;
  }

  std::optional<toml::array> string_list_value(const Key& key, const toml::node& node,
                                               const std::string& key_path,
                                               const toml::source_region& at) {
    const auto* array = node.as_array();
    if (!array) {
      wrong_type(key, node, key_path, at);
      return std::nullopt;
    }
    toml::array result;
    bool ok = true;
    for (std::size_t i = 0; i < array->size(); ++i) {
      const toml::node& item = *array->get(i);
      if (const auto* s = item.as_string()) {
        result.push_back(s->get());
      } else {
        error(region_of(item, at), key_path, render(item),
              fmt::format("element {}: expected a string, got {}", i + 1, type_phrase(item)));
        ok = false;
      }
    }
    if (!ok) return std::nullopt;
    return result;
  }

  // --- tables ----------------------------------------------------------------------------------

  void resolve_sub_table(const toml::table* given, const TableSpec& sub, const TableSpec& parent,
                         const TablePath& path, const toml::source_region& where,
                         toml::table& resolved) {
    const TablePath sub_path{path.child_data(sub.name), path.child_spec(sub.name), false};
    if (const Entry entry = find_entry(given, sub.name)) {
      const toml::node& node = *entry.node;
      const toml::source_region key_at = region_of(*entry.key, node, where);
      const toml::source_region at = region_of(node, key_at);
      if (const auto* t = node.as_table()) {
        record(sub_path.data, at);
        resolved.insert_or_assign(sub.name, table(t, sub, sub_path, at));
      } else {
        error(key_at, sub_path.data, render(node),
              fmt::format("expected a table {}, got {}", heading(sub_path.spec, false),
                          type_phrase(node)));
      }
      return;
    }
    if (sub.required) {
      error(where, sub_path.data, "",
            fmt::format("missing required table {}", heading(sub_path.spec, false)));
    } else if (!contains(parent.one_of, sub.name) && !needs_input(sub)) {
      // Absent optional tables still appear in the resolved scene with their defaults, so that
      // the driver never needs to know which defaults exist.
      resolved.insert_or_assign(sub.name, table(nullptr, sub, sub_path, where));
    }
  }

  // The name of an array element in paths: its `name` key, or its index when it has none or the
  // name is already taken (paths must stay unique).
  std::string element_label(const toml::table& element, std::size_t index,
                            std::vector<std::string>& seen, const std::string& array_path,
                            const std::string& array_spec, const toml::source_region& where) {
    const auto* name = element.get_as<std::string>("name");
    if (!name) return std::to_string(index);
    if (contains(seen, name->get())) {
      error(region_of(*name, where), fmt::format("{}.{}.name", array_path, index), render(*name),
            fmt::format("duplicate name: every {} needs a unique name", heading(array_spec, true)));
      return std::to_string(index);
    }
    seen.push_back(name->get());
    return name->get();
  }

  void resolve_array(const toml::table* given, const TableSpec& sub, const TablePath& path,
                     const toml::source_region& where, toml::table& resolved) {
    const std::string data = path.child_data(sub.name);
    const std::string spec = path.child_spec(sub.name);
    const std::string head = heading(spec, true);
    toml::array elements;
    const Entry entry = find_entry(given, sub.name);
    const toml::node* node = entry.node;
    const toml::source_region at = entry ? region_of(*entry.key, *node, where) : where;
    if (node && !node->is_array()) {
      error(at, data, node->is_table() ? "" : render(*node),
            fmt::format(
                "expected an array of tables {}, got {}{}", head, type_phrase(*node),
                node->is_table() ? fmt::format(" (write {} instead of [{}])", head, spec) : ""));
      return;
    }
    if (node) {
      record(data, at);
      std::vector<std::string> seen;
      const toml::array& array = *node->as_array();
      for (std::size_t i = 0; i < array.size(); ++i) {
        const toml::node& item = *array.get(i);
        const auto* element = item.as_table();
        if (!element) {
          error(
              region_of(item, at), fmt::format("{}.{}", data, i), render(item),
              fmt::format("expected a table (an element of {}), got {}", head, type_phrase(item)));
          continue;
        }
        const toml::source_region element_at = region_of(item, at);
        const TablePath element_path{
            join_path(data, element_label(*element, i, seen, data, spec, element_at)), spec, true};
        record(element_path.data, element_at);
        elements.push_back(table(element, sub, element_path, element_at));
      }
    }
    if (sub.required && (!node || node->as_array()->empty())) {
      error(at, data, "", fmt::format("missing {}: at least one is required", head));
    }
    resolved.insert_or_assign(sub.name, std::move(elements));
  }

  void check_one_of(const toml::table* given, const TableSpec& spec, const TablePath& path,
                    const toml::source_region& where) {
    std::vector<std::string> alternatives, present;
    const toml::node* second = nullptr;
    for (const std::string& name : spec.one_of) {
      alternatives.push_back(heading(path.child_spec(name), false));
      const toml::node* node = given ? given->get(name) : nullptr;
      if (!node) continue;
      present.push_back(alternatives.back());
      if (present.size() == 2) second = node;
    }
    if (present.size() == 1) return;
    if (present.empty()) {
      error(
          where, path.data, "",
          fmt::format("missing one of {}: exactly one is required", fmt::join(alternatives, ", ")));
    } else {
      error(region_of(*second, where), path.data, "",
            fmt::format("only one of {} may be given, found {}", fmt::join(alternatives, ", "),
                        fmt::join(present, " and ")));
    }
  }
};

}  // namespace

Validated validate(const toml::table& document, const TableSpec& root, const std::string& file) {
  Validated out;
  out.file = file;
  Validator validator(document, file, out);
  // Missing keys of the root table are reported at 1:1: the root has no header.
  toml::source_region start;
  start.begin = {1, 1};
  start.end = {1, 1};
  out.resolved = validator.table(&document, root, TablePath{}, start);
  validator.sort_errors();
  return out;
}

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

void apply_override(toml::table& document, const std::string& assignment, const std::string& source) {
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
