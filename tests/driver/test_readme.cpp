// The README is the user's manual: its Scene keys section must equal what `hvi keys` prints
// (regenerate it with scripts/update_readme_keys.py after changing the schema).
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "cases/driver/scene_schema.hpp"

TEST(Readme, SceneKeysSectionMatchesTheSchema) {
  std::ifstream in(std::string(HVI_SOURCE_DIR) + "/README.md");
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string readme = buffer.str();
  const std::string begin = "<!-- keys:begin -->\n", end = "<!-- keys:end -->";
  const auto b = readme.find(begin), e = readme.find(end);
  ASSERT_NE(b, std::string::npos);
  ASSERT_NE(e, std::string::npos);
  const std::string section = readme.substr(b + begin.size(), e - b - begin.size());
  EXPECT_TRUE(section == hvi::scene::markdown_reference(hvi::scene::scene_schema()))
      << "README.md Scene keys section is stale: run scripts/update_readme_keys.py";
}
