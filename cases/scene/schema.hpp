#pragma once
// Declared scene keys. Every key of a scene file is declared once, here-style, with its type,
// unit (dimension), range and default; validate() checks a parsed TOML document against the
// declaration and returns the fully resolved scene (every default filled in, every quantity in SI)
// or a list of diagnostics that name file:line:column, the key, the value and what was expected.
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <toml++/toml.h>  // Debian 12 ships toml.h only (no toml.hpp)

#include "cases/scene/units.hpp"

namespace hvi::scene {

enum class ValueKind {
  quantity,         // number with a unit of a given dimension ("0.5 mm") or a plain SI number
  quantity_vector,  // array of `components` quantities of one dimension
  number,           // dimensionless floating point number (integers accepted)
  integer,
  boolean,
  string,
  choice,  // one of a fixed list of strings
  string_list,
};

// A closed/open interval for numbers and quantities (in SI).
struct Range {
  std::optional<double> min, max;
  bool min_inclusive = true, max_inclusive = true;
  bool contains(double v) const;
  std::string describe() const;  // "> 0", "in [0, 1]", "in (0, 1]", ">= 1"
};
Range positive();                           // > 0
Range non_negative();                       // >= 0
Range closed(double lo, double hi);         // [lo, hi]
Range left_open(double lo, double hi);      // (lo, hi]
Range right_open(double lo, double hi);     // [lo, hi)
Range open_interval(double lo, double hi);  // (lo, hi)

struct Key {
  std::string name;
  ValueKind kind = ValueKind::number;
  Dim dim{};                         // quantity, quantity_vector
  int components = 3;                // quantity_vector
  Range range{};                     // number, integer, quantity, quantity_vector (each component)
  std::vector<std::string> choices;  // choice
  // Default in SI (for quantities) as a TOML value; std::nullopt with required == false means
  // "optional, no default": the driver computes and records the value (e.g. depends on other keys).
  std::shared_ptr<const toml::node> default_value;  // null: no default
  bool required = false;
  std::string doc;  // one line for `hvi keys` and docs/user/scene_keys.md
};

struct TableSpec {
  std::string name{};  // key of the table in its parent ("grid", "body", "sphere")
  std::string doc{};
  bool array = false;     // [[name]]: array of tables; each element is checked against this spec
  bool required = false;  // the table (or at least one element of the array) must be present
  // Initialized with {} so that designated initializers (TableSpec{.name = "grid"}) do not warn
  // under -Wextra (-Wmissing-field-initializers).
  std::vector<Key> keys{};
  std::vector<TableSpec> tables{};
  // Exactly one of these sub-tables (names of entries in `tables`) must be present, e.g. a body's
  // shape: one of "sphere", "box", "cylinder".
  std::vector<std::string> one_of{};

  // Builder helpers so a schema reads as a declaration.
  TableSpec& quantity(std::string name, Dim dim, Range range, std::optional<double> default_si,
                      std::string doc);
  TableSpec& quantity_required(std::string name, Dim dim, Range range, std::string doc);
  TableSpec& vector(std::string name, Dim dim, std::optional<std::vector<double>> default_si,
                    std::string doc, int components = 3);
  TableSpec& vector_required(std::string name, Dim dim, std::string doc, int components = 3);
  TableSpec& number(std::string name, Range range, std::optional<double> default_value,
                    std::string doc);
  TableSpec& integer(std::string name, Range range, std::optional<long long> default_value,
                     std::string doc);
  TableSpec& boolean(std::string name, bool default_value, std::string doc);
  TableSpec& string(std::string name, std::optional<std::string> default_value, std::string doc);
  TableSpec& string_required(std::string name, std::string doc);
  TableSpec& choice(std::string name, std::vector<std::string> choices,
                    std::optional<std::string> default_value, std::string doc);
  TableSpec& choice_required(std::string name, std::vector<std::string> choices, std::string doc);
  TableSpec& string_list(std::string name, std::vector<std::string> default_value, std::string doc);
  TableSpec& string_list_required(std::string name, std::string doc);
  TableSpec& optional_quantity(std::string name, Dim dim, Range range, std::string doc);
  TableSpec& table(TableSpec sub);
};

struct Diagnostic {
  std::string file;
  int line = 0, column = 0;  // 1-based; 0 when unknown
  std::string key;    // dotted path, arrays of tables by element name: "body.projectile.radius"
  std::string value;  // the offending value as written (TOML syntax), empty when not about a value
  std::string message;  // what is wrong and what was expected
  // One line: "file:line:column: key 'grid.cell_size' = \"0.5 kg\": <message>"; the " = <value>"
  // part only when `value` is set.
  std::string text() const;
};

struct Validated {
  toml::table resolved;  // every declared key present (unless optional without default),
                         // quantities as SI floating point numbers
  std::vector<Diagnostic> errors;
  std::map<std::string, toml::source_region> locations;  // dotted key path -> where it was written
  std::string file;  // the scene file name given to validate(), for locations without a source
  bool ok() const { return errors.empty(); }
  // A diagnostic located at `key` (or at the closest enclosing table that was written).
  Diagnostic at(const std::string& key, std::string message) const;
};

// Checks `document` against `root` and collects every problem (it does not stop at the first).
// Diagnostics of the document itself name `file`; nodes inserted by apply_override name their
// "--set ..." source instead. Absent optional tables are created with their defaults, except
// those in a one_of and those that declare something required (they cannot be made from
// defaults); absent optional arrays of tables resolve to empty arrays.
Validated validate(const toml::table& document, const TableSpec& root, const std::string& file);

// Parses and applies a command-line override "key.path=value" to a parsed document before
// validation. Arrays of tables are addressed by the element's `name`: "body.projectile.velocity".
// The value is parsed as a TOML value ("0.5", "\"0.5 mm\"", "[1, 2, 3]"); text that is not valid
// TOML is taken as a string ("0.5 mm"). Errors name the override: the inserted nodes carry the
// source path "--set <assignment>", line 1. Throws std::invalid_argument when the assignment has
// no '=', has an empty path component, or names an array element or table that does not exist.
void apply_override(toml::table& document, const std::string& assignment);
// The same with the diagnostics' source named `source` (e.g. "scene.toml [resolutions.coarse]").
void apply_override(toml::table& document, const std::string& assignment,
                    const std::string& source);

// Markdown reference of every key (for `hvi keys` and docs/user/scene_keys.md).
std::string markdown_reference(const TableSpec& root);

}  // namespace hvi::scene
