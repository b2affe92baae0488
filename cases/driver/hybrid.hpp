#pragma once
// The hybrid of a scene that names a [far_field]: the finite-element far field of its panel
// (coupling/panel_far_field.hpp), coupled to the solver through the grid nodes of the interface
// band (coupling/far_field_coupling.hpp). A scene without [far_field] never constructs one, so
// nothing of fem/ runs, is allocated or is written for it.
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cases/driver/scene.hpp"
#include "coupling/far_field_coupling.hpp"
#include "fem/far_field.hpp"
#include "mpm/solver.hpp"

namespace hvi::driver {

class Hybrid {
 public:
  // Builds the far-field mesh from the scene's panel, its conditions (a node on or beyond a
  // [[boundary]] plane takes that condition; clamped edges hold every other outer side), and
  // adds the coupling to `solver`, which must outlive this. Throws std::invalid_argument.
  Hybrid(const scene::Scene& scene, mpm::Solver& solver);

  const fem::FarField& far_field() const { return *far_field_; }
  const coupling::FarFieldCoupling& coupling() const { return *coupling_; }
  // One line for the run's header: nodes, elements, tied nodes, stable step, memory.
  std::string describe() const;

  // DIR/far_field/far_field_<step>.vtu and the collection DIR/far_field.pvd for ParaView.
  void write_snapshot(const std::filesystem::path& dir, std::int64_t step, double time);
  // A resumed run keeps the snapshots up to `last_step` (read back from far_field.pvd).
  void resume(const std::filesystem::path& dir, std::int64_t last_step);

 private:
  std::unique_ptr<fem::FarField> far_field_;
  std::unique_ptr<coupling::FarFieldCoupling> coupling_;
  std::vector<std::pair<double, std::string>> snapshots_;  // (time, file)
  std::size_t fixed_nodes_ = 0;
  bool plastic_faces_ = false, failing_faces_ = false, yielding_core_ = false, failing_core_ = false;
};

// The scene's hybrid, or null when it names no far field.
std::unique_ptr<Hybrid> make_hybrid(const scene::Scene& scene, mpm::Solver& solver);

}  // namespace hvi::driver
