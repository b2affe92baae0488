#pragma once
// Reading a file a test or a run wrote.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace hvi::test {

// The whole file, byte for byte (empty when it cannot be read).
inline std::string read(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace hvi::test
