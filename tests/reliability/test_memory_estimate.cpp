// Points and bytes estimated before sampling (cases/run/memory_estimate.hpp): on the demo scene
// each body's estimate against the points its sampling gives, and a plate impact on 1 um cells
// (once grown until the machine ran out of memory) refused at once with the keys that drive it;
// under an address-space limit (ulimit -v, where std::bad_alloc once escaped a parallel loop) the
// limit is what a run is held against.
#include <sys/resource.h>

#include <chrono>
#include <fstream>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "cases/run/bodies.hpp"
#include "cases/run/build_solver.hpp"
#include "cases/run/memory_estimate.hpp"

namespace hvi::driver {
namespace {

const std::string cases = std::string(HVI_SOURCE_DIR) + "/cases/";

// Never more than 10% below the points sampled, and at most 30% above: a 0.5 mm facesheet on a
// 0.2 mm lattice is 2.5 spacings thick and sampled as 2 layers (+25%); the sphere and the core
// (walls one point across) within 5%.
TEST(MemoryEstimate, DemoBodiesAgainstTheirSampledPoints) {
  const scene::Scene s = scene::load_scene(cases + "demo.toml");
  for (std::size_t b = 0; b < s.bodies.size(); ++b) {
    const auto solid = make_body_solid(s, b);
    const double estimate = estimated_points(s, b, *solid);
    const double sampled = static_cast<double>(sample_body(s, b, *solid).size());
    EXPECT_GE(estimate / sampled, 0.9) << s.bodies[b].name << ": " << estimate << " estimated";
    EXPECT_LE(estimate / sampled, 1.3) << s.bodies[b].name << ": " << estimate << " estimated";
    if (s.bodies[b].name == "projectile" || s.bodies[b].name == "panel.core") {
      EXPECT_NEAR(estimate / sampled, 1.0, 0.05) << s.bodies[b].name;
    }
  }
}

TEST(MemoryEstimate, MicronCellsAreRefusedBeforeSampling) {
  const scene::Scene s =
      scene::load_scene(cases + "verification/plate_impact.toml", {"grid.cell_size=0.001mm"});
  auto solver = make_solver(s);
  try {
    add_bodies(s, *solver, 1e9);
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("above 1 GB (--max-memory)"), std::string::npos) << message;
    EXPECT_NE(message.find("grid.cell_size 1e-06 m over particles_per_cell"), std::string::npos)
        << message;
  }
  EXPECT_EQ(solver->particles().size(), 0u);  // nothing sampled
}

TEST(MemoryEstimate, AnAddressSpaceLimitIsHeld) {
  const MemoryLimit free = available_memory();
  ASSERT_GT(free.bytes, 0.0);
  // The limit: what this process maps now and 200 MB more.
  std::ifstream status("/proc/self/status");
  std::string line;
  double mapped = 0;
  while (std::getline(status, line))
    if (line.rfind("VmSize:", 0) == 0) mapped = std::stod(line.substr(7)) * 1024.0;
  ASSERT_GT(mapped, 0.0);
  const rlimit as{static_cast<rlim_t>(mapped + 200e6), RLIM_INFINITY};
  ASSERT_EQ(setrlimit(RLIMIT_AS, &as), 0);
  const MemoryLimit held = available_memory();
  EXPECT_NE(held.what.find("ulimit -v"), std::string::npos) << held.what;
  EXPECT_LE(held.bytes, 200e6);

  // The demo on 0.1 mm cells: about 8e6 points, 5 GB.
  const scene::Scene s = scene::load_scene(cases + "demo.toml", {"grid.cell_size=0.1mm"});
  std::vector<std::unique_ptr<geometry::Solid>> solids;
  for (std::size_t b = 0; b < s.bodies.size(); ++b) solids.push_back(make_body_solid(s, b));
  try {
    check_memory(s, solids, 0);
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("(what the address-space limit (ulimit -v) leaves)"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace hvi::driver
