// One run spread over the ranks of an MPI job (mpm/solver_ranks.cpp) against the same run on one
// rank: every field of every point, the solver state, the removal events and the energies,
// bitwise; and its snapshot and checkpoint, written by every rank into one file. Run under mpirun
// on 2 and 3 ranks (tests/parallel/CMakeLists.txt); started plainly it is one rank and checks that
// the one-rank path is the plain solver's.
//
// The scene: an Al6061 sphere at 2 km/s into an Al6061 plate (Johnson-Cook strength and damage,
// Mie-Grueneisen), and a cube at 3 km/s that crosses the ranks' pieces of the grid and leaves the
// domain during the run, on a 48 x 16 x 16 grid of 1 mm cells cut into 7 x 3 x 3 block groups;
// also with the node-averaged dilatation, and with contact between the sphere and the rest.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "../mpm/mpm_test_helpers.hpp"
#include "cases/parallel/mpi_communicator.hpp"
#include "cases/parallel/mpi_file_access.hpp"
#include "cases/parallel/ranks.hpp"
#include "mpm/io/checkpoint.hpp"
#include "mpm/io/snapshot_writer.hpp"
#include "mpm/materials/hydro_material.hpp"
#include "mpm/materials/library.hpp"

namespace hvi::mpm::test {
namespace {

const parallel::Ranks* ranks = nullptr;
constexpr int kSteps = 100;

std::unique_ptr<Solver> impact_solver(SolverSettings settings) {
  const double h = 1e-3;
  std::vector<std::unique_ptr<Material>> materials;
  materials.push_back(
      std::make_unique<HydroMaterial>("Al6061", find_library_material("Al6061")->parameters));
  materials.push_back(
      std::make_unique<HydroMaterial>("Al5052", find_library_material("Al5052")->parameters));
  return std::make_unique<Solver>(
      grid({-24 * h, -8 * h, -8 * h}, h, {48, 16, 16}), settings, std::move(materials),
      std::vector<std::string>{"plate", "projectile", "cube"}, std::vector<GridBoundary>{});
}

void add_impact_bodies(Solver& solver) {
  const double h = 1e-3;
  add_body(solver, geometry::Box({0.0, -7 * h, -7 * h}, {3 * h, 7 * h, 7 * h}), 2, 0, 0,
           uniform({0.0, 0.0, 0.0}));
  add_body(solver, geometry::Sphere({-4 * h, 0.5 * h, 0.0}, 3 * h), 2, 1, 0,
           uniform({2000.0, 0.0, 0.0}));
  add_body(solver, geometry::Box({10 * h, 4 * h, -7 * h}, {12 * h, 6 * h, -5 * h}), 2, 2, 1,
           uniform({3000.0, 0.0, 0.0}));
}

struct Outcome {
  std::unique_ptr<Solver> solver;
  std::vector<RemovalEvent> events;
  EnergyReport energy;
  std::size_t most_points = 0;  // on this rank, at any step
};

// With `comm`, the bodies start on rank 0 only and the first step spreads them; `gather` brings
// them back to rank 0 at the end.
Outcome run(SolverSettings settings, Communicator* comm, bool gather = true) {
  Outcome o{impact_solver(settings), {}, {}, 0};
  if (!comm || comm->rank() == 0) add_impact_bodies(*o.solver);
  o.solver->distribute(comm);
  o.solver->initialise();
  for (int k = 0; k < kSteps; ++k) {
    o.solver->step();
    o.most_points = std::max(o.most_points, o.solver->particles().size());
    for (auto& e : o.solver->take_removal_events()) o.events.push_back(e);
  }
  o.energy = o.solver->energy();
  if (gather) o.solver->gather_to_root();
  return o;
}

struct Case {
  ShapeFunction shape;
  UpdateScheme scheme;
  const char* name;
  Dilatation dilatation = Dilatation::particle;
  // Contact (the sphere on a velocity field of its own) with this friction coefficient; < 0: none.
  double friction = -1.0;
};

void PrintTo(const Case& c, std::ostream* os) {
  *os << c.name;
}

class DistributedRun : public ::testing::TestWithParam<Case> {};

TEST_P(DistributedRun, IsBitwiseTheOneRankRun) {
  SolverSettings settings;
  settings.shape = GetParam().shape;
  settings.scheme = GetParam().scheme;
  settings.dilatation = GetParam().dilatation;
  if (GetParam().friction >= 0.0)
    settings.contact = ContactSettings{{0, 1, 0}, GetParam().friction, std::nullopt};
  settings.reorder_interval = 7;
  const Outcome one = run(settings, nullptr);
  // What the scene promises: the cube left during the run, the sphere struck the plate.
  EXPECT_GT(one.solver->removed().particles, 0);
  EXPECT_GT(one.energy.dissipated, 0.0);
  if (GetParam().friction > 0.0) {
    EXPECT_GT(one.energy.contact, 0.0);  // friction heat booked
  }

  const auto comm = parallel::make_communicator(*ranks);
  const Outcome spread = run(settings, comm.get());
  EXPECT_TRUE(identical_state(*one.solver, *spread.solver));
  EXPECT_TRUE(same_events(one.events, spread.events));
  EXPECT_EQ(std::memcmp(&one.energy, &spread.energy, sizeof(EnergyReport)), 0);
  if (!comm) {
    EXPECT_TRUE(identical_by_id(one.solver->particles(), spread.solver->particles()));
    return;
  }
  if (comm->rank() == 0) {
    EXPECT_TRUE(identical_by_id(one.solver->particles(), spread.solver->particles()));
  } else {
    EXPECT_EQ(spread.solver->particles().size(), 0u);  // all gathered to rank 0
  }
  // Every rank held points, but never all of them; points migrated, and blocks were shared.
  const auto all =
      one.solver->particles().size() + static_cast<std::size_t>(one.solver->removed().particles);
  EXPECT_GT(spread.most_points, 0u);
  EXPECT_LT(spread.most_points, all);
  const auto& s = spread.solver->sharing();
  EXPECT_GE(s.cuts, 1);
  EXPECT_GT(s.shared_blocks, 0);
  EXPECT_GT(comm->max(static_cast<double>(s.migrated)), 0.0);
}

std::string bytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The collective snapshot and checkpoint: every rank writes the rows of its slab of ids
// (mpm/io/id_slabs.hpp) into one file, which holds the one-rank run's bytes, and a checkpoint
// written so is read back in shares, one per rank, to the same points.
TEST(DistributedOutput, OneFileWrittenTogetherHoldsTheOneRankRunsBytes) {
  SolverSettings settings;
  settings.shape = ShapeFunction::gimp;
  const Outcome one = run(settings, nullptr);
  const auto comm = parallel::make_communicator(*ranks);
  const auto shared = parallel::make_file_access(*ranks);
  if (comm && !shared) GTEST_SKIP() << "hvi is built with an HDF5 that cannot share a file";
  const Outcome spread = run(settings, comm.get(), false);
  const auto dir = std::filesystem::temp_directory_path();
  const auto file = [&](const char* name) {
    return dir / fmt::format("hvi_{}_{}.h5", name, ranks->size());
  };
  const auto alone = file("snapshot_alone"), together = file("snapshot"),
             checkpoint = file("checkpoint");
  if (ranks->rank() == 0) io::write_snapshot_file(alone, *one.solver);
  io::write_snapshot_file(together, *spread.solver, shared.get());
  io::write_checkpoint(checkpoint, *spread.solver, {{"answer", 42.0}}, shared.get());
  if (comm) comm->max(0.0);  // a barrier: rank 0 has completed the checkpoint (its attributes)
  if (ranks->rank() == 0) {
    EXPECT_EQ(bytes(alone), bytes(together));
    EXPECT_GT(bytes(alone).size(), 100000u);
  }
  // Every rank reads its share; gathered, they are the one-rank run's points.
  const Outcome fresh{impact_solver(settings), {}, {}, 0};
  fresh.solver->distribute(comm.get());
  EXPECT_EQ(io::read_checkpoint(checkpoint, *fresh.solver).at("answer"), 42.0);
  const std::size_t all = one.solver->particles().size();
  EXPECT_LE(fresh.solver->particles().size(), all / ranks->size() + 1);
  EXPECT_EQ(fresh.solver->point_count(), all);
  EXPECT_TRUE(identical_state(*one.solver, *fresh.solver));
  fresh.solver->gather_to_root();
  if (ranks->rank() == 0) {
    EXPECT_TRUE(identical_by_id(one.solver->particles(), fresh.solver->particles()));
  }
}

INSTANTIATE_TEST_SUITE_P(
    Schemes, DistributedRun,
    ::testing::Values(Case{ShapeFunction::linear, UpdateScheme::musl, "linear_musl"},
                      Case{ShapeFunction::gimp, UpdateScheme::musl, "gimp_musl"},
                      Case{ShapeFunction::cpgimp, UpdateScheme::usl, "cpgimp_usl"},
                      Case{ShapeFunction::gimp, UpdateScheme::usf, "gimp_usf"},
                      // The node average's sums (the mean stress in the force scatter, the
                      // dilatation in the gradient pass) are shared like the grid's.
                      Case{ShapeFunction::gimp, UpdateScheme::musl, "gimp_musl_node_average",
                           Dilatation::node_average},
                      Case{ShapeFunction::linear, UpdateScheme::usl, "linear_usl_node_average",
                           Dilatation::node_average},
                      // Contact: each field's grid also holds the other's shared blocks; the
                      // normals are shared too, the friction heat counted once per block.
                      Case{ShapeFunction::gimp, UpdateScheme::musl, "gimp_musl_contact",
                           Dilatation::particle, 0.0},
                      Case{ShapeFunction::cpgimp, UpdateScheme::usf, "cpgimp_usf_contact_friction",
                           Dilatation::node_average, 0.3}),
    [](const ::testing::TestParamInfo<Case>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace hvi::mpm::test

int main(int argc, char** argv) {
  const hvi::parallel::Ranks ranks(argc, argv);
  hvi::mpm::test::ranks = &ranks;
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
