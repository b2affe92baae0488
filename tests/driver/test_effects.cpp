// A scene simulates only the effects it asks for: a model a material does not name declares no
// particle field (so none is allocated or written) and runs no code (so no phase names it).
#include <algorithm>
#include <filesystem>
#include <set>

#include <gtest/gtest.h>
#include <omp.h>

#include "cases/run/build_solver.hpp"
#include "cases/scene/scene.hpp"
#include "mpm/io/hdf5_file.hpp"
#include "mpm/io/snapshot_writer.hpp"

namespace hvi {
namespace {

// Runs 5 steps of the plate-impact scene with the given material models and returns the
// particle fields, the timed phases and the datasets of a snapshot.
struct Effects {
  std::set<std::string> fields, phases, datasets;
  // A phase of the timing table names it: a material's models share one phase, whose name lists
  // them ("strength: johnson-cook | eos: mie-gruneisen + viscosity | ...").
  bool runs(const std::string& name) const {
    return std::any_of(phases.begin(), phases.end(),
                       [&](const std::string& p) { return p.find(name) != std::string::npos; });
  }
};

Effects run_with(const std::vector<std::string>& models,
                 const std::vector<std::string>& scene_keys = {}) {
  omp_set_num_threads(1);
  // Every model key set: what `models` does not name is switched off.
  std::vector<std::string> overrides = {"strength=none", "eos=none",     "viscosity=none",
                                        "damage=none",   "failure=none", "heating=none",
                                        "erosion=none"};
  for (const auto& m : models) overrides.push_back(m);
  for (auto& o : overrides) o = "material.Al6061." + o;
  overrides.insert(overrides.end(), scene_keys.begin(), scene_keys.end());
  const auto scene = scene::load_scene(
      std::string(HVI_SOURCE_DIR) + "/cases/verification/plate_impact.toml", overrides);
  auto solver = driver::make_solver(scene);
  driver::add_bodies(scene, *solver);
  solver->initialise();
  for (int k = 0; k < 5; ++k) solver->step();
  Effects e;
  for (const auto& f : solver->particles().real_fields()) e.fields.insert(f.name);
  for (const auto& p : solver->timer().entries()) e.phases.insert(p.name);
  // One folder per test: ctest runs the tests of this file side by side.
  const auto dir =
      std::filesystem::path(testing::TempDir()) /
      ("hvi_effects_" + std::string(testing::UnitTest::GetInstance()->current_test_info()->name()));
  std::filesystem::remove_all(dir);
  mpm::io::SnapshotWriter writer(dir);
  writer.write(*solver);
  mpm::io::Hdf5File file((dir / mpm::io::SnapshotWriter::file_name(0)).string(),
                         mpm::io::Hdf5File::Mode::read);
  for (const auto& d : file.dataset_names()) e.datasets.insert(d);
  return e;
}

struct Model {
  std::string key;                  // scene setting that names it
  std::vector<std::string> fields;  // particle fields it owns (also snapshot datasets)
  std::string phase;                // its row in the timing table
};

const std::vector<Model> models = {
    {"strength=johnson-cook",
     {"plastic_strain", "plastic_strain_rate", "plastic_work"},
     "strength: johnson-cook"},
    {"damage=johnson-cook", {"damage", "failed"}, "damage: johnson-cook"},
    {"failure=max-principal-stress", {"failed"}, "failure: max-principal-stress"},
    {"heating=adiabatic", {"temperature"}, "heating: adiabatic"},
    {"viscosity=bulk", {"viscous_work"}, "eos: mie-gruneisen + viscosity"},
    {"erosion=compression", {"failed"}, "erosion: compression"},
};

// The scene names every model; taking out one removes exactly its fields and phase.
TEST(Effects, AModelNotNamedIsNotAllocatedComputedOrWritten) {
  std::vector<std::string> all = {
      "strength=johnson-cook",        "eos=mie-gruneisen",  "viscosity=bulk",
      "damage=johnson-cook",          "heating=adiabatic",  "max_principal_stress.limit=1.5e9",
      "failure=max-principal-stress", "erosion=compression"};
  const Effects full = run_with(all);
  for (const auto& m : models) {
    for (const auto& f : m.fields) {
      EXPECT_TRUE(full.fields.count(f)) << f;
      EXPECT_TRUE(full.datasets.count(f)) << f;
    }
    EXPECT_TRUE(full.runs(m.phase)) << m.phase;
  }
  // Drop each model in turn (damage and heating need johnson-cook strength, so keep it for them).
  for (const auto& m : models) {
    SCOPED_TRACE(m.key);
    std::vector<std::string> without;
    for (const auto& k : all) {
      if (k == m.key) continue;
      if (m.key == "failure=max-principal-stress" && k.rfind("max_principal_stress", 0) == 0)
        continue;
      without.push_back(k);
    }
    if (m.key == "strength=johnson-cook") without = {"eos=mie-gruneisen", "viscosity=bulk"};
    const Effects e = run_with(without);
    EXPECT_FALSE(e.runs(m.phase)) << m.phase;
    for (const auto& f : m.fields) {
      // "failed" belongs to damage, failure and erosion: it goes only when none is named.
      const bool shared = f == "failed" && (m.key == "damage=johnson-cook" ||
                                            m.key == "failure=max-principal-stress" ||
                                            m.key == "erosion=compression");
      if (shared) continue;
      EXPECT_FALSE(e.fields.count(f)) << f;
      EXPECT_FALSE(e.datasets.count(f)) << f;
    }
  }
  // With no damage, failure or erosion there is no failure state at all.
  const Effects plain = run_with({"strength=johnson-cook"});
  EXPECT_FALSE(plain.fields.count("failed"));
  EXPECT_TRUE(plain.runs("strength: johnson-cook"));
  EXPECT_TRUE(plain.runs("eos: elastic bulk"));
}

// Tuler-Butcher spall is the other choice of `failure`: its damage field, the failure state and
// its phase exist only when it is named.
TEST(Effects, TulerButcherIsAllocatedComputedAndWrittenOnlyWhenNamed) {
  const std::vector<std::string> jc = {"strength=johnson-cook", "eos=mie-gruneisen"};
  const Effects plain = run_with(jc);
  const Effects named =
      run_with({"strength=johnson-cook", "eos=mie-gruneisen", "failure=tuler-butcher",
                "tuler_butcher.threshold=1.5e9", "tuler_butcher.time=1e-8"});
  for (const std::string f : {"spall_damage", "failed"}) {
    EXPECT_FALSE(plain.fields.count(f)) << f;
    EXPECT_FALSE(plain.datasets.count(f)) << f;
    EXPECT_TRUE(named.fields.count(f)) << f;
    EXPECT_TRUE(named.datasets.count(f)) << f;
  }
  EXPECT_FALSE(plain.runs("failure: tuler-butcher"));
  EXPECT_TRUE(named.runs("failure: tuler-butcher"));
}

// A scene setting that adds phases to the step runs them only when named, and adds no particle
// field or snapshot dataset.
void phases_only_when_named(const std::string& setting, const std::vector<std::string>& phases) {
  const std::vector<std::string> jc = {"strength=johnson-cook", "eos=mie-gruneisen"};
  const Effects plain = run_with(jc);
  const Effects named = run_with(jc, {setting});
  for (const auto& phase : phases) {
    EXPECT_FALSE(plain.runs(phase)) << phase;
    EXPECT_TRUE(named.runs(phase)) << phase;
  }
  EXPECT_EQ(plain.fields, named.fields);
  EXPECT_EQ(plain.datasets, named.datasets);
}

// A fracture energy and a scatter of the failure thresholds (issue #83): each its field and its
// name in the material's phase, only when named.
TEST(Effects, FractureEnergyAndScatterAreAllocatedComputedAndWrittenOnlyWhenNamed) {
  const std::vector<std::string> jc = {"strength=johnson-cook", "eos=mie-gruneisen",
                                       "damage=johnson-cook"};
  const Effects plain = run_with(jc);
  std::vector<std::string> both = jc;
  for (const char* k : {"damage_evolution=fracture-energy", "fracture_energy.energy=14 kJ/m^2",
                        "scatter=weibull", "weibull.modulus=8"})
    both.push_back(k);
  const Effects named = run_with(both);
  for (const std::string f : {"fracture_work", "failure_scale"}) {
    EXPECT_FALSE(plain.fields.count(f)) << f;
    EXPECT_FALSE(plain.datasets.count(f)) << f;
    EXPECT_TRUE(named.fields.count(f)) << f;
    EXPECT_TRUE(named.datasets.count(f)) << f;
  }
  for (const std::string phase : {"+ fracture-energy", "scatter: weibull"}) {
    EXPECT_FALSE(plain.runs(phase)) << phase;
    EXPECT_TRUE(named.runs(phase)) << phase;
  }
}

// The node-averaged dilatation (grid.dilatation): two passes over the points.
TEST(Effects, NodeAveragedDilatationRunsOnlyWhenNamed) {
  phases_only_when_named("grid.dilatation=node-average",
                         {"dilatation: node average", "mean stress: node average"});
}

// Contact ([contact]): a second grid, a normal pass and the corrections.
TEST(Effects, ContactRunsOnlyWhenNamed) {
  phases_only_when_named("contact.bodies=[\"flyer\"]", {"contact", "contact: normals"});
}

// The energy ledger (output.energy_ledger): one more gradient pass and the phases' sums.
TEST(Effects, EnergyLedgerRunsOnlyWhenNamed) {
  phases_only_when_named("output.energy_ledger=true", {"energy ledger"});
}

}  // namespace
}  // namespace hvi
