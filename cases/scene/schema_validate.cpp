// Validation of scene documents against the declared key schema. The walk mirrors the schema:
// for every declared table it checks the keys that were written, reports the ones that were not
// declared, fills in defaults and recurses into sub-tables. Every problem becomes a Diagnostic and
// the walk continues, so one run of the validator reports all mistakes of a scene file at once.
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

  // A value written for a key: the key's declaration, the value, its path in the scene and
  // where it stands in the file.
  struct Written {
    const Key& key;
    const toml::node& node;
    const std::string& path;
    toml::source_region at;
  };

  void error(const Written& w, std::string message) {
    error(w.at, w.path, w.node.is_table() ? "" : render(w.node), std::move(message));
  }

  void resolve_key(const toml::table* given, const Key& key, const TablePath& path,
                   const toml::source_region& where, toml::table& resolved) {
    const std::string key_path = path.child_data(key.name);
    if (const Entry entry = find_entry(given, key.name)) {
      const toml::source_region at = region_of(*entry.key, *entry.node, where);
      record(key_path, at);
      convert({key, *entry.node, key_path, at}, resolved);
    } else if (key.required) {
      error(where, key_path, "", "missing required key: expected " + expected_phrase(key));
    } else if (key.default_value) {
      insert_copy(resolved, key.name, *key.default_value);
    }
  }

  // Stores the value, in SI and checked against the declaration; or reports why it cannot.
  void convert(const Written& w, toml::table& resolved) {
    const auto keep = [&](auto&& v) {
      if (v) resolved.insert_or_assign(w.key.name, std::move(*v));
    };
    switch (w.key.kind) {
      case ValueKind::quantity:
      case ValueKind::number:
        keep(scalar_value(w, ""));
        break;
      case ValueKind::quantity_vector:
        keep(vector_value(w));
        break;
      case ValueKind::integer:
        keep(integer_value(w));
        break;
      case ValueKind::boolean:
        keep(typed_value<bool>(w));
        break;
      case ValueKind::string:
        keep(typed_value<std::string>(w));
        break;
      case ValueKind::choice:
        keep(choice_value(w));
        break;
      case ValueKind::string_list:
        keep(string_list_value(w));
        break;
    }
  }

  void wrong_type(const Written& w, const std::string& prefix = "") {
    error(w, fmt::format("{}expected {}, got {}", prefix, expected_phrase(w.key),
                         type_phrase(w.node)));
  }

  // The value as the TOML type T (bool, std::string, std::int64_t, toml::array), or nullptr
  // after reporting its wrong type.
  template <class T>
  const auto* typed(const Written& w) {
    const auto* v = w.node.as<T>();
    if (!v) wrong_type(w);
    return v;
  }

  // A boolean or a string, as TOML typed it.
  template <class T>
  std::optional<T> typed_value(const Written& w) {
    if (const auto* v = typed<T>(w)) return v->get();
    return std::nullopt;
  }

  bool check_range(const Written& w, double v, const std::string& prefix) {
    const Key& key = w.key;
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
      if (!unit.empty() && w.node.is_string()) {
        message += fmt::format(", got {}", with_unit(format_number(v), unit));
      }
    }
    error(w, std::move(message));
    return false;
  }

  // A quantity: a plain number (SI) or a string "<number> <unit>" of the key's dimension; or a
  // dimensionless number (ValueKind::number), where a string must parse as a unitless number
  // ("0.3"). `prefix` names the component for vectors ("component 2: ").
  std::optional<double> scalar_value(const Written& w, const std::string& prefix) {
    const bool number = w.key.kind == ValueKind::number;
    double v = 0.0;
    if (w.node.is_number()) {
      v = w.node.value<double>().value_or(0.0);
    } else if (const auto* s = w.node.as_string()) {
      Quantity q;
      try {
        q = parse_quantity(s->get());
      } catch (const UnitError& e) {
        error(w, (number ? "expected a number: " : prefix) + e.what());
        return std::nullopt;
      }
      // A unitless string ("0.5") is a number in SI, like an unquoted number; a unit must be the
      // key's ("3 rad" is no length).
      if (number ? q.dim != dims::none : (q.dim != w.key.dim && !q.bare)) {
        error(w, fmt::format("{}expected {}, got {}", prefix,
                             number ? "a number without unit" : expected_phrase(w.key),
                             dimension_phrase(q.dim)));
        return std::nullopt;
      }
      v = q.si;
    } else {
      wrong_type(w, prefix);
      return std::nullopt;
    }
    if (!check_range(w, v, prefix)) return std::nullopt;
    return v;
  }

  std::optional<toml::array> vector_value(const Written& w) {
    const auto* array = typed<toml::array>(w);
    if (!array) return std::nullopt;
    if (array->size() != static_cast<std::size_t>(w.key.components)) {
      error(w, fmt::format("expected {}, got {} component{}", expected_phrase(w.key), array->size(),
                           array->size() == 1 ? "" : "s"));
      return std::nullopt;
    }
    Key scalar = w.key;
    scalar.kind = ValueKind::quantity;
    toml::array result;
    bool ok = true;
    for (std::size_t i = 0; i < array->size(); ++i) {
      const toml::node& component = *array->get(i);
      const std::optional<double> v =
          scalar_value({scalar, component, w.path, region_of(component, w.at)},
                       fmt::format("component {} of {}: ", i + 1, w.key.components));
      ok = ok && v.has_value();
      if (v) result.push_back(*v);
    }
    if (!ok) return std::nullopt;
    return result;
  }

  std::optional<std::int64_t> integer_value(const Written& w) {
    const auto* i = typed<std::int64_t>(w);
    if (!i) return std::nullopt;
    if (!check_range(w, static_cast<double>(i->get()), "")) return std::nullopt;
    return i->get();
  }

  std::optional<std::string> choice_value(const Written& w) {
    const std::optional<std::string> s = typed_value<std::string>(w);
    if (!s || contains(w.key.choices, *s)) return s;
    std::string message = "invalid choice: expected one of " + quoted_list(w.key.choices);
    if (const std::optional<std::string> suggestion = closest(*s, w.key.choices)) {
      message += fmt::format("; did you mean {}?", quoted(*suggestion));
    }
    error(w, std::move(message));
    return std::nullopt;
  }

  std::optional<toml::array> string_list_value(const Written& w) {
    const auto* array = typed<toml::array>(w);
    if (!array) return std::nullopt;
    toml::array result;
    bool ok = true;
    for (std::size_t i = 0; i < array->size(); ++i) {
      const toml::node& item = *array->get(i);
      if (const auto* s = item.as_string()) {
        result.push_back(s->get());
      } else {
        error(region_of(item, w.at), w.path, render(item),
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

}  // namespace hvi::scene
