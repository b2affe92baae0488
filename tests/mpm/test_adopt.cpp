// Points adopted between steps (Solver::adopt_particles, as a growing hybrid zone's take-over
// appends them): each run of one material among the new points is initialised by its own
// material and only over its own points, and the next time step is the CFL limit of the fastest
// material among them, cfl h / c with c = sqrt((lambda + 2 mu) / rho) for points at rest.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "mpm_test_helpers.hpp"

namespace hvi::mpm::test {
namespace {

// A linear-elastic material that records which points it was asked to initialise, and whether
// every one of them was its own.
class Recording : public LinearElastic {
 public:
  Recording(std::string name, double E, std::int64_t index, std::vector<std::int64_t>& ids,
            bool& foreign)
      : LinearElastic(std::move(name), 2700.0, E, 0.25),
        index_(index),
        ids_(ids),
        foreign_(foreign) {}
  void initialise(Particles& particles, ParticleRange range) const override {
    for (std::size_t p = range.begin; p < range.end; ++p) {
      ids_.push_back(particles.id[p]);
      foreign_ = foreign_ || particles.material[p] != index_;
    }
  }

 private:
  std::int64_t index_;
  std::vector<std::int64_t>& ids_;
  bool& foreign_;
};

TEST(AdoptParticles, EachMaterialsRunIsInitialisedByItAndTheStiffestSetsTheStep) {
  const Threads threads(1);
  const double h = 1e-3, soft = 1e9, stiff = 100e9;
  std::vector<std::int64_t> soft_ids, stiff_ids;
  bool soft_foreign = false, stiff_foreign = false;
  std::vector<std::unique_ptr<Material>> materials;
  materials.push_back(std::make_unique<Recording>("soft", soft, 0, soft_ids, soft_foreign));
  materials.push_back(std::make_unique<Recording>("stiff", stiff, 1, stiff_ids, stiff_foreign));
  SolverSettings settings;
  Solver solver(grid({0, 0, 0}, h, {8, 8, 8}), settings, std::move(materials), {"block"}, {});
  add_body(solver, geometry::Box({2 * h, 2 * h, 2 * h}, {4 * h, 4 * h, 4 * h}), 2, 0, 0,
           uniform({0, 0, 0}));
  solver.initialise();
  const auto* soft_material = dynamic_cast<const LinearElastic*>(solver.materials()[0].get());
  const auto* stiff_material = dynamic_cast<const LinearElastic*>(solver.materials()[1].get());
  const double c_soft = soft_material->p_wave_speed(2700.0),
               c_stiff = stiff_material->p_wave_speed(2700.0);
  // Before: only the soft block, so its wave speed sets the step (to round-off: rho = m / V).
  EXPECT_NEAR(solver.next_time_step(), settings.cfl * h / c_soft, 1e-12 * h / c_soft);
  soft_ids.clear();

  // Five points in three runs (soft, stiff, soft, soft, stiff): the last run is a single stiff
  // point, so a step set by the soft ones alone would be 10 times too long.
  const std::vector<std::int64_t> kinds = {0, 1, 0, 0, 1};
  Particles& P = solver.particles();
  const std::size_t first = P.size();
  P.resize(first + kinds.size());
  for (std::size_t k = 0; k < kinds.size(); ++k) {
    const std::size_t p = first + k;
    const double x[3] = {(5.25 + 0.5 * static_cast<double>(k % 2)) * h, 5.25 * h,
                         (5.25 + 0.5 * static_cast<double>(k / 2)) * h};
    for (int d = 0; d < 3; ++d) P.position[3 * p + d] = x[d];
    P.volume0[p] = P.volume[p] = h * h * h / 8;
    P.mass[p] = 2700.0 * P.volume[p];
    P.id[p] = static_cast<std::int64_t>(p);
    P.body[p] = 0;
    P.material[p] = kinds[k];
  }
  solver.adopt_particles(first);

  const auto f = static_cast<std::int64_t>(first);
  EXPECT_EQ(soft_ids, (std::vector<std::int64_t>{f, f + 2, f + 3}));
  EXPECT_EQ(stiff_ids, (std::vector<std::int64_t>{f + 1, f + 4}));
  EXPECT_FALSE(soft_foreign);
  EXPECT_FALSE(stiff_foreign);
  EXPECT_NEAR(solver.next_time_step(), settings.cfl * h / c_stiff, 1e-12 * h / c_stiff);
}

}  // namespace
}  // namespace hvi::mpm::test
