#pragma once
// Displacement probes: the [[measure]]s of kind "displacement", followed through a run.
// A probe reads, in the undeformed configuration chosen at the start,
//   - in a hybrid's far field (its point outside the MPM zone in plane): the nearest far-field
//     node, u = its displacement; when a zone that grows takes that node's cells over
//     (zone_grew), the probe goes on with the points that took over there, chosen as below by
//     their undeformed positions: u = the node's u at the take-over + the points' mean
//     displacement since, so its reading continues (the points' own mean u(X) at the take-over
//     would differ from the node's by the field's gradient across the cells beside it);
//   - otherwise the particles within one grid cell of the point, of the body of the nearest
//     particle (or of the measure's `body`): u = mean (x_p - x_p^0) over them, so a probe in a
//     0.5 mm facesheet averages over its thickness rather than following one noisy point.
// Every energy.csv row appends (step, time, one column per probe) to DIR/probes.csv; the final
// value goes to summary.json like every measure, and as <name>_peak the value of largest
// magnitude over those rows (a deflection's final value depends on the phase of the panel's
// vibration at the end time; its peak less so). The chosen particles and their undeformed
// positions travel in the checkpoint, so a resumed run follows the same ones.
#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "cases/run/hybrid.hpp"
#include "cases/scene/scene.hpp"
#include "mpm/io/checkpoint.hpp"
#include "mpm/solver.hpp"

namespace hvi::driver {

// Whether the scene has a displacement probe.
bool has_probes(const scene::Scene& scene);

class Probes {
 public:
  // Chooses what each probe reads (call before the first step). `hybrid` may be null.
  Probes(const scene::Scene& scene, const mpm::Solver& solver, const Hybrid* hybrid);
  bool empty() const { return probes_.empty(); }

  void save(mpm::io::CheckpointExtras& extras) const;
  // A resumed run: the same particles and nodes as the checkpointed run's.
  void load(const mpm::io::CheckpointExtras& extras);

  // Opens DIR/probes.csv (a resumed run keeps its rows up to `resume_step`).
  void open(const std::filesystem::path& dir, std::int64_t resume_step);
  void record(const mpm::Solver& solver);  // and updates the peaks
  // After Hybrid::grow took over far-field cells: probes on a node it detached move to its points.
  void zone_grew(const mpm::Solver& solver, std::int64_t first_id);
  std::map<std::string, double> values(const mpm::Solver& solver) const;

 private:
  struct Probe {
    std::string name;
    std::array<double, 3> point{};
    std::string body;  // the measure's `body`, or empty
    int axis = 2;
    bool far_field = false;
    std::size_t node = 0;           // far field
    std::vector<std::int64_t> ids;  // particles
    std::vector<double> reference;  // their undeformed positions, 3 per particle
    std::unordered_map<std::int64_t, std::size_t> slot;  // particle id -> index into ids
    double peak = 0.0;                                   // of largest magnitude so far
  };
  // Where each particle probe's points are now, by id: one call for all probes, which on a run
  // spread over ranks asks every rank for its points among them (mpm::Solver::positions_of).
  using Positions = std::unordered_map<std::int64_t, std::array<double, 3>>;
  Positions positions(const mpm::Solver& solver) const;
  double value(const Probe& p, const Positions& at) const;
  // Follows the particles from `first` (index) near the probe's point, taking their undeformed
  // positions from `reference` (3 per particle, in the order of their ids from `first_id`), or
  // their positions now when it is empty.
  void choose_particles(Probe& p, const mpm::Solver& solver, double cell, std::int64_t first_id,
                        const std::vector<double>& reference);

  const Hybrid* hybrid_;
  double cell_ = 0.0;
  std::vector<Probe> probes_;
  std::ofstream log_;
};

}  // namespace hvi::driver
