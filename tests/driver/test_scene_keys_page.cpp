// The manual's scene keys page (docs/user/scene_keys.md) must equal what `hvi keys` prints
// (regenerate it with scripts/update_scene_keys.py after changing the schema).
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "cases/scene/scene_schema.hpp"

TEST(Manual, SceneKeysPageMatchesTheSchema) {
  std::ifstream in(std::string(HVI_SOURCE_DIR) + "/docs/user/scene_keys.md");
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string page = buffer.str();
  const std::string begin = "<!-- keys:begin -->\n", end = "<!-- keys:end -->";
  const auto b = page.find(begin), e = page.find(end);
  ASSERT_NE(b, std::string::npos);
  ASSERT_NE(e, std::string::npos);
  const std::string section = page.substr(b + begin.size(), e - b - begin.size());
  EXPECT_TRUE(section == hvi::scene::markdown_reference(hvi::scene::scene_schema()))
      << "docs/user/scene_keys.md is stale: run scripts/update_scene_keys.py";
}
