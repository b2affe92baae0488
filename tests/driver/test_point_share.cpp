// The bodies of a run spread over ranks: every rank samples them and keeps the points whose id is
// its rank modulo the rank count (cases/run/build_solver.hpp). The shares of 3 ranks are the
// points of one rank, each exactly once, with the same id, position, velocity, volume, mass and
// GIMP domain; the memory check is of a share.
#include <map>

#include <gtest/gtest.h>

#include "cases/run/build_solver.hpp"
#include "cases/run/memory_estimate.hpp"
#include "cases/scene/scene.hpp"

namespace hvi {
namespace {

scene::Scene plate_impact(const std::vector<std::string>& overrides = {}) {
  return scene::load_scene(std::string(HVI_SOURCE_DIR) + "/cases/verification/plate_impact.toml",
                           overrides);
}

TEST(PointShare, ThreeSharesAreTheOneRankPointsEachOnce) {
  const auto scene = plate_impact();  // cpGIMP: each point carries its domain
  auto whole = driver::make_solver(scene);
  const auto counts = driver::add_bodies(scene, *whole);
  const mpm::Particles& W = whole->particles();
  std::map<std::int64_t, std::size_t> at;  // id -> index in the whole
  for (std::size_t p = 0; p < W.size(); ++p) at[W.id[p]] = p;
  ASSERT_EQ(at.size(), W.size());
  const auto& whole_width = W.field(mpm::Solver::half_width_field);

  std::size_t seen = 0;
  for (int r = 0; r < 3; ++r) {
    auto share = driver::make_solver(scene);
    EXPECT_EQ(driver::add_bodies(scene, *share, 0, nullptr, {r, 3}), counts);
    const mpm::Particles& S = share->particles();
    const auto& width = S.field(mpm::Solver::half_width_field);
    EXPECT_LE(S.size(), W.size() / 3 + counts.size());
    for (std::size_t p = 0; p < S.size(); ++p) {
      ASSERT_EQ(S.id[p] % 3, r);
      const std::size_t w = at.at(S.id[p]);
      EXPECT_EQ(S.body[p], W.body[w]);
      EXPECT_EQ(S.material[p], W.material[w]);
      EXPECT_EQ(S.volume[p], W.volume[w]);
      EXPECT_EQ(S.mass[p], W.mass[w]);
      for (int d = 0; d < 3; ++d) {
        EXPECT_EQ(S.position[3 * p + d], W.position[3 * w + d]);
        EXPECT_EQ(S.velocity[3 * p + d], W.velocity[3 * w + d]);
        EXPECT_EQ(width[3 * p + d], whole_width[3 * w + d]);
      }
    }
    seen += S.size();
  }
  EXPECT_EQ(seen, W.size());
}

// A limit the whole model exceeds but a third of it does not: refused on one rank, taken on 3.
TEST(PointShare, TheMemoryCheckIsOfAShare) {
  const auto scene = plate_impact();
  auto probe = driver::make_solver(scene);
  driver::add_bodies(scene, *probe);
  // 0.6 of the whole: robust to an estimate of the point count 40% low or 80% high.
  const double limit =
      0.6 * static_cast<double>(probe->particles().size()) * driver::bytes_per_point;
  auto one = driver::make_solver(scene);
  try {
    driver::add_bodies(scene, *one, limit);
    ADD_FAILURE() << "the whole model fits in " << limit << " bytes";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).find("on each of"), std::string::npos) << e.what();
  }
  auto share = driver::make_solver(scene);
  EXPECT_NO_THROW(driver::add_bodies(scene, *share, limit, nullptr, {1, 3}));
}

}  // namespace
}  // namespace hvi
