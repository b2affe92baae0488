#pragma once
// Scene tests: the diagnostic a scene that must fail gives for a key.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cases/scene/scene.hpp"

namespace hvi::scene::test {

// The diagnostic about `key` of the scene `text` (named `file`, with `overrides`); fails the test
// when the scene is accepted or has none about `key`.
inline Diagnostic error_for(const std::string& text, const std::string& key,
                            const std::vector<std::string>& overrides = {},
                            const std::string& file = "scene.toml") {
  try {
    parse_scene(text, file, overrides);
  } catch (const SceneError& e) {
    for (const auto& d : e.diagnostics())
      if (d.key == key) return d;
    ADD_FAILURE() << "no diagnostic for " << key << "; first: " << e.diagnostics().front().text();
    return {};
  }
  ADD_FAILURE() << "scene was accepted";
  return {};
}

}  // namespace hvi::scene::test
