// The bond in a scene ([bond]; mpm/bond.hpp): the bonded core is the second velocity field, its
// points within a spacing of each facesheet carry the strip of the bond's width under their walls
// (together: the width times the walls' length in plan), and a bond that cannot be built is
// refused where it is written.
#include <cmath>

#include <gtest/gtest.h>

#include "cases/run/bodies.hpp"
#include "cases/run/build_solver.hpp"
#include "cases/scene/scene.hpp"
#include "tests/driver/scene_errors.hpp"

namespace hvi {
namespace {

const std::string shot = std::string(HVI_SOURCE_DIR) + "/cases/experiments/shot.toml";
const std::vector<std::string> bonded = {"grid.cell_size=0.4 mm", "bond.panel=panel",
                                         "bond.normal_strength=40 MPa",
                                         "bond.shear_strength=30 MPa", "bond.width=0.3 mm"};

TEST(BondScene, TheCoresPointsAtTheSheetsCarryTheBondsStrip) {
  const auto scene = scene::load_scene(shot, bonded);
  auto solver = driver::make_solver(scene);
  ASSERT_TRUE(solver->settings().contact && solver->settings().contact->bond);
  const std::size_t core = driver::core_body(scene, 0);
  EXPECT_EQ(solver->settings().contact->impactor.at(core), 1);
  driver::add_bodies(scene, *solver);
  const mpm::Particles& P = solver->particles();
  const auto& area = P.field(mpm::bond_field::area);
  const auto& normal = P.field(mpm::bond_field::normal);
  double rear = 0.0, front = 0.0;
  for (std::size_t p = 0; p < P.size(); ++p) {
    if (!(area[p] > 0.0)) continue;
    EXPECT_EQ(P.body[p], static_cast<std::int64_t>(core));
    EXPECT_EQ(P.field(mpm::bond_field::bonded)[p], 1.0);
    (normal[3 * p + 2] < 0 ? rear : front) += area[p];
  }
  // The walls' length in plan: the core's volume over its height and the foil's thickness.
  const auto& panel = scene.panels[0];
  const double walls =
      driver::make_body_solid(scene, core)->volume() / (panel.core_height * panel.wall_thickness);
  EXPECT_NEAR(rear / (0.3e-3 * walls), 1.0, 0.01);
  EXPECT_NEAR(front / (0.3e-3 * walls), 1.0, 0.01);
}

TEST(BondScene, ABondThatCannotBeBuiltIsRefusedWhereItIsWritten) {
  auto overrides = bonded;
  overrides.push_back("contact.bodies=[\"projectile\"]");
  try {
    scene::load_scene(shot, overrides);
    FAIL() << "accepted";
  } catch (const scene::SceneError& e) {
    bool found = false;
    for (const auto& d : e.diagnostics())
      found |= d.key == "bond" && d.message.find("[contact] takes too") != std::string::npos;
    EXPECT_TRUE(found) << e.diagnostics().front().text();
  }
  overrides = bonded;
  overrides.push_back("bond.panel=plate");
  try {
    scene::load_scene(shot, overrides);
    FAIL() << "accepted";
  } catch (const scene::SceneError& e) {
    EXPECT_EQ(e.diagnostics().front().key, "bond.panel");
    EXPECT_NE(e.diagnostics().front().message.find("no [[panel]] named 'plate'; panels: 'panel'"),
              std::string::npos)
        << e.diagnostics().front().text();
  }
}

}  // namespace
}  // namespace hvi
