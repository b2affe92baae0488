#pragma once
// The hybrid of a scene that names a [far_field]: the finite-element far field of its panel
// (coupling/panel_far_field.hpp), coupled to the solver through the grid nodes of the interface
// band (coupling/far_field_coupling.hpp). A scene without [far_field] never constructs one, so
// nothing of fem/ runs, is allocated or is written for it.
#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cases/scene/scene.hpp"
#include "coupling/far_field_coupling.hpp"
#include "coupling/panel_far_field.hpp"
#include "coupling/zone_growth.hpp"
#include "fem/far_field.hpp"
#include "geometry/honeycomb.hpp"
#include "mpm/solver.hpp"

namespace hvi::driver {

class Hybrid {
 public:
  // Builds the far-field mesh from the scene's panel, its conditions (a node on or beyond a
  // [[boundary]] plane takes that condition; clamped edges hold every other outer side), and
  // adds the coupling to `solver`, which must outlive this, as must `scene`. Throws
  // std::invalid_argument.
  Hybrid(const scene::Scene& scene, mpm::Solver& solver);

  const fem::FarField& far_field() const { return *far_field_; }
  const coupling::FarFieldCoupling& coupling() const { return *coupling_; }
  // One line for the run's header: nodes, elements, tied nodes, stable step, memory.
  std::string describe() const;

  // DIR/far_field/far_field_<step>.vtu and the collection DIR/far_field.pvd for ParaView, and
  // beside them DIR/far_field/nodes_<step>.h5 for programs (hvi probe, h5py): every node's
  // undeformed position, displacement and lumped mass (0 at a node a grown zone took over), in
  // node order; attributes time and step.
  static std::string nodes_file(std::int64_t step);
  void write_snapshot(const std::filesystem::path& dir, std::int64_t step, double time);
  // A resumed run keeps the snapshots up to `last_step` (read back from far_field.pvd), and
  // restores the zone.
  void resume(const std::filesystem::path& dir, std::int64_t last_step);
  // A zone that grew (its band read back from the checkpoint) takes its cells out of the far field
  // again (every rank of a spread run; rank 0 in resume()).
  void restore_zone();

  // A zone that grows ([far_field.zone.grow]): between two steps, grows the zone where the panel's
  // damage reaches its edge (coupling::grown_zone): the panel's three bodies are sampled over the
  // ring it adds, as at the start (the lattice anchored at the grid, the thin-wall model, the
  // refinement zones), and take over the far field's cells there (coupling::take_over). Returns
  // what was taken over, or nothing when the zone stays. Collective in a run spread over ranks:
  // the damage of every rank's points counts, and rank 0 adds the new points.
  bool growing() const { return growth_.has_value(); }
  // With a zone that grows, the points of the start take their positions as their undeformed
  // ones (coupling::reference_position_field); call it once they are all added.
  void record_reference_positions(mpm::Solver& solver) const;
  std::optional<coupling::TakeoverReport> grow(mpm::Solver& solver);
  // The undeformed positions of the points the last growth added (3 per point; the point k has
  // the id first_id + k of grow()'s report).
  const std::vector<double>& last_points() const { return last_points_; }
  // The zone now (x0, y0, x1, y1, m).
  const std::array<double, 4>& zone() const { return coupling_->band().zone; }

  // Where grow() found the panel's damage at a side of the zone already at its limit
  // (coupling::sides_held_at_limit): at how many steps, the first and last time, and which sides
  // (x0, y0, x1, y1). A limit that stops the zone while the damage goes on tells the user to widen
  // it. Kept in the checkpoint, so a resumed run reports the whole run's.
  struct LimitRecord {
    std::int64_t steps = 0;
    double first_time = 0.0, last_time = 0.0;
    std::array<bool, 4> sides{};
  };
  const LimitRecord& held_at_limit() const { return held_at_limit_; }
  void save(std::map<std::string, double>& checkpoint_extras) const;
  void load(const std::map<std::string, double>& checkpoint_extras);
  // The points a grown zone gets over the ring's `boxes` (in plane, x0, y0, x1, y1;
  // coupling::ring): the panel's bodies cut to each and sampled, undeformed.
  coupling::NewPoints sample_ring(const std::vector<std::array<double, 4>>& boxes,
                                  const mpm::Solver& solver) const;

 private:
  const scene::Scene& scene_;
  coupling::PanelFarFieldSpec spec_;
  std::optional<coupling::ZoneGrowth> growth_;
  std::array<std::size_t, 3> panel_bodies_{};    // front, core, rear
  std::optional<geometry::HexPattern> pattern_;  // the panel's cells, for its walls' directions
  std::vector<double> last_points_;
  LimitRecord held_at_limit_;
  std::unique_ptr<fem::FarField> far_field_;
  std::unique_ptr<coupling::FarFieldCoupling> coupling_;
  std::vector<std::pair<double, std::string>> snapshots_;  // (time, file)
  std::size_t fixed_nodes_ = 0;
  bool plastic_faces_ = false, failing_faces_ = false, yielding_core_ = false,
       failing_core_ = false;
};

// The scene's hybrid, or null when it names no far field.
std::unique_ptr<Hybrid> make_hybrid(const scene::Scene& scene, mpm::Solver& solver);

}  // namespace hvi::driver
