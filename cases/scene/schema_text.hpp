#pragma once
// Wording shared by the schema's validator, its overrides and its Markdown reference: how a value,
// a key's expected type and a table's heading are written in messages and documentation.
#include <string>
#include <string_view>
#include <vector>

#include <toml++/toml.h>

#include "cases/scene/schema.hpp"

namespace hvi::scene::text {

std::string format_number(double v);
// A string as TOML writes it, in double quotes with escapes.
std::string quoted(std::string_view s);
// A number as TOML writes a float (always with a '.' or an exponent).
std::string toml_float(double v);
// A value as written in a scene (toml_syntax) or for a message.
std::string render(const toml::node& node, bool toml_syntax = true);
// "a string", "an array of 3 numbers", ...: what a value is, for "got ..." in messages.
std::string type_phrase(const toml::node& node);
std::string join_path(const std::string& path, std::string_view name);
// "'a', 'b' or 'c'".
std::string quoted_list(const std::vector<std::string>& items);
// What a key expects, as in "expected a length (e.g. \"0.5 mm\")".
std::string expected_phrase(const Key& key);
// The unit a key's value is shown in ("mm", "km/s"), or empty.
std::string unit_of(const Key& key);
std::string with_unit(std::string text, const std::string& unit);
// Heading of a table spec path for messages and Markdown: "[grid]", "[[body]]", "[body.sphere]".
std::string heading(const std::string& spec_path, bool array);
// The file, line and column of a source region (the fallback file when it has none).
Diagnostic diagnostic_at(const toml::source_region& where, const std::string& fallback_file);

}  // namespace hvi::scene::text
