#pragma once
// What the readers of a scene's tables share (scene.cpp, scene_materials.cpp): typed access to a
// validated table, whose keys the schema has checked and defaulted, and the collector of the
// problems that span keys. Internal to scene/.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "cases/scene/scene.hpp"

namespace hvi::scene::reading {

inline double number(const toml::table& t, const char* key) {
  return t[key].value<double>().value();
}
inline std::int64_t integer(const toml::table& t, const char* key) {
  return t[key].value<std::int64_t>().value();
}
inline std::string text(const toml::table& t, const char* key) {
  return t[key].value<std::string>().value();
}
inline std::optional<double> optional_number(const toml::table& t, const char* key) {
  return t[key].value<double>();
}
inline Vec3 vec3(const toml::table& t, const char* key) {
  const toml::array& a = *t[key].as_array();
  return {a[0].value<double>().value(), a[1].value<double>().value(), a[2].value<double>().value()};
}
inline int axis_index(const std::string& name) {
  return name[0] - 'x';
}

inline std::string element_path(const char* array, const toml::table& element, std::size_t index) {
  if (auto name = element["name"].value<std::string>()) return fmt::format("{}.{}", array, *name);
  return fmt::format("{}.{}", array, index);
}

// Collects cross-key problems while the typed scene is assembled.
struct Checker {
  const Validated& v;
  std::vector<Diagnostic> errors;
  void error(const std::string& key, std::string message) {
    errors.push_back(v.at(key, std::move(message)));
  }
};

// Reads the [[material]] tables: each model a material names, its parameters from the table or
// the library material (scene_materials.cpp).
void read_materials(toml::array& array, Scene& s, Checker& c);

}  // namespace hvi::scene::reading
