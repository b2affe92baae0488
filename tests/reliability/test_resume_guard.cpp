// A resumed run goes on with the physics its checkpoint was computed with: a --set or an edit of
// scene.resolved.toml that changes the state (cell size, density) is refused with exit 2 and
// nothing written, while when to stop and what to write may change (a later end time resumes).
#include <sys/wait.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/support/run_hvi.hpp"

namespace {

namespace fs = std::filesystem;

const std::string scene = std::string(HVI_SOURCE_DIR) + "/tests/driver/data/drift.toml";

using hvi::test::read;
using hvi::test::run_logged;

TEST(ResumeGuard, AChangedStateIsRefusedAndALaterEndTimeResumes) {
  const fs::path dir = fs::path(testing::TempDir()) / "hvi_resume_guard";
  const fs::path log = fs::path(testing::TempDir()) / "hvi_resume_guard.log";
  fs::remove_all(dir);
  // Stopped after 5 steps with a checkpoint.
  ASSERT_EQ(
      run_logged("run " + scene + " --out " + dir.string() + " --threads 1 --set run.max_steps=5",
                 log),
      0)
      << read(log);
  const std::string resolved = read(dir / "scene.resolved.toml");
  const auto checkpoint_time = fs::last_write_time(dir / "checkpoint.h5");

  EXPECT_EQ(run_logged("run --resume " + dir.string() + " --set grid.cell_size=0.3mm", log), 2);
  EXPECT_NE(read(log).find("the scene differs from the one its checkpoint was computed with"),
            std::string::npos)
      << read(log);
  EXPECT_EQ(read(dir / "scene.resolved.toml"), resolved);  // nothing written
  EXPECT_EQ(fs::last_write_time(dir / "checkpoint.h5"), checkpoint_time);

  std::string edited = resolved;
  const auto at = edited.find("density = 7850");
  ASSERT_NE(at, std::string::npos) << resolved;
  edited.replace(at, 14, "density = 7800");
  std::ofstream(dir / "scene.resolved.toml") << edited;
  EXPECT_EQ(run_logged("run --resume " + dir.string(), log), 2) << read(log);
  std::ofstream(dir / "scene.resolved.toml") << resolved;

  EXPECT_EQ(
      run_logged("run --resume " + dir.string() + " --set run.end_time=3us --set run.max_steps=0",
                 log),
      0)
      << read(log);
}

// A checkpoint damaged on disk (64 bytes flipped in its data) is refused on resume, by the
// Fletcher-32 checksum of its datasets; it once resumed with eight points' pressures wrong.
TEST(ResumeGuard, ADamagedCheckpointIsRefused) {
  const fs::path dir = fs::path(testing::TempDir()) / "hvi_resume_damaged";
  const fs::path log = fs::path(testing::TempDir()) / "hvi_resume_damaged.log";
  fs::remove_all(dir);
  ASSERT_EQ(
      run_logged("run " + scene + " --out " + dir.string() + " --threads 1 --set run.max_steps=5",
                 log),
      0)
      << read(log);
  std::string bytes = read(dir / "checkpoint.h5");
  for (std::size_t k = 0; k < 64; ++k) bytes[bytes.size() / 2 + k] ^= '\xff';
  std::ofstream(dir / "checkpoint.h5", std::ios::binary) << bytes;
  EXPECT_EQ(run_logged("run --resume " + dir.string(), log), 2);
  EXPECT_NE(read(log).find("checkpoint.h5"), std::string::npos) << read(log);
}

}  // namespace
