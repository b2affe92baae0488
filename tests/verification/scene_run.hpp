#pragma once
// Runs a scene of cases/ in-process (no output files), so a verification test measures the same
// scene a user runs with `hvi run`.
#include <memory>
#include <string>
#include <vector>

#include "cases/run/build_solver.hpp"
#include "cases/scene/scene.hpp"

namespace hvi::test {

struct SceneRun {
  scene::Scene scene;
  std::unique_ptr<mpm::Solver> solver;

  SceneRun(const std::string& case_file, const std::vector<std::string>& overrides)
      : scene(scene::load_scene(std::string(HVI_SOURCE_DIR) + "/cases/" + case_file, overrides)),
        solver(driver::make_solver(scene)) {
    driver::add_bodies(scene, *solver);
    solver->initialise();
  }
  // Steps to time t exactly (the last step is shortened).
  void run_to(double t) {
    while (solver->time() < t * (1 - 1e-12)) solver->step(t - solver->time());
  }
  const mpm::Particles& particles() const { return solver->particles(); }
};

}  // namespace hvi::test
