#pragma once
// The explicit MPM solver: one step of the update schemes MUSL (default), USL and USF (the
// paper's Sec. 2.3 flowchart) as a short list of named phases. Particles, grid, materials and
// boundary conditions are owned here; coupled models enter through GridCoupling hooks.
#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "mpm/boundary.hpp"
#include "mpm/communicator.hpp"
#include "mpm/contact.hpp"
#include "mpm/energy_ledger.hpp"
#include "mpm/grid.hpp"
#include "mpm/grid_coupling.hpp"
#include "mpm/material.hpp"
#include "mpm/particle_bins.hpp"
#include "mpm/particles.hpp"
#include "mpm/partition.hpp"
#include "mpm/phase_timer.hpp"
#include "mpm/shape_functions.hpp"
#include "mpm/shared_blocks.hpp"
#include "mpm/transfers.hpp"
#include "mpm/types.hpp"
#include "mpm/volumetric_average.hpp"

namespace hvi::mpm {

// Which dilatation tr L a point's volume and pressure follow (volumetric_average.hpp).
enum class Dilatation {
  particle,      // its own (standard MPM, the paper's)
  node_average,  // the average through the grid nodes over the intact points of its body
};

enum class UpdateScheme {
  musl,  // modified update stress last: velocities remapped to the grid before the strain rate
  usl,   // update stress last
  usf,   // update stress first (the paper's flowchart)
};

struct SolverSettings {
  ShapeFunction shape = ShapeFunction::linear;
  UpdateScheme scheme = UpdateScheme::musl;
  double flip = 1.0;  // FLIP fraction of the particle velocity update; 1 = FLIP (paper), 0 = PIC
  double cfl = 0.5;   // dt = cfl h / max_p (c_p + |v_p|)
  double max_time_step = std::numeric_limits<double>::infinity();
  // A run whose time step falls below this fraction of its first one has gone unstable (a
  // particle is racing away): it stops with an error instead of crawling on.
  double min_time_step_fraction = 1e-3;
  int reorder_interval = 16;  // steps between sorting particle arrays by material and block
  Dilatation dilatation = Dilatation::particle;
  // GIMP on one field: keep the points' stencils between a step's transfers (transfers.hpp).
  bool stencil_cache = false;
  // Two velocity fields with contact between them (contact.hpp); none: one field, bodies stick.
  std::optional<ContactSettings> contact;
  // Book each body's energy phase by phase (energy_ledger.hpp): one more gradient pass a step.
  bool energy_ledger = false;
};

// Everything that left the domain, so that nothing is lost silently.
struct RemovedMaterial {
  std::int64_t particles = 0;
  double mass = 0.0;      // kg
  double kinetic = 0.0;   // J, at the moment of removal
  double internal = 0.0;  // J
  Vec3 momentum{};        // kg m/s
};

// One particle leaving the grid.
struct RemovalEvent {
  std::int64_t id, body, material;
  Vec3 position, velocity;
  double mass, time;
  std::int64_t step;
};

struct EnergyReport {
  double kinetic = 0.0;     // sum 1/2 m v^2, J
  double internal = 0.0;    // recoverable (strain) part of the internal energy, J
  double dissipated = 0.0;  // plastic work and viscous heating, J
  double removed = 0.0;     // kinetic + internal energy carried out of the domain, J
  double coupled_kinetic = 0.0, coupled_strain = 0.0;  // held by coupled models (far field), J
  double contact = 0.0;                                // friction heat of contact (contact.hpp), J
  double total() const {
    return kinetic + internal + dissipated + removed + coupled_kinetic + coupled_strain + contact;
  }
  Vec3 momentum{};  // of the particles in the domain and the coupled models, kg m/s
  Vec3 removed_momentum{};
  double mass = 0.0, removed_mass = 0.0;
  // With SolverSettings::energy_ledger: per body, the ledger's columns (energy_ledger.hpp), J.
  std::vector<std::array<double, ledger::columns>> ledger;
};

// A run that cannot continue: names the particle, body, material, position, time and step.
// `every_rank`: in a run spread over ranks, every rank threw it at the same point of the step (with
// the same message), so none waits inside the step for another and the run can end cleanly.
class SolverError : public std::runtime_error {
 public:
  explicit SolverError(const std::string& what, bool every_rank = false)
      : std::runtime_error(what), every_rank_(every_rank) {}
  bool every_rank() const { return every_rank_; }

 private:
  bool every_rank_;
};

// The restartable scalar state of a run (particles are saved separately).
struct SolverState {
  double time = 0.0;
  std::int64_t step = 0;
  double next_dt = 0.0;
  double first_dt = 0.0;  // the first step's, against which a collapsing step is judged
  RemovedMaterial removed;
  double contact_work = 0.0;   // J, see EnergyReport::contact
  std::vector<double> ledger;  // the energy ledger's totals, bodies x columns (J), if kept
};

class Solver {
 public:
  // Per-particle GIMP domain half-widths (3 per particle, m); a creator may set them (sampling
  // spacing / 2 per axis), else they follow from the particle volume.
  static constexpr const char* half_width_field = "gimp_half_width";

  Solver(GridGeometry grid, SolverSettings settings,
         std::vector<std::unique_ptr<Material>> materials, std::vector<std::string> body_names,
         std::vector<GridBoundary> boundaries);

  Particles& particles() { return particles_; }
  const Particles& particles() const { return particles_; }
  const std::vector<std::unique_ptr<Material>>& materials() const { return materials_; }
  const std::vector<std::string>& body_names() const { return body_names_; }
  const SolverSettings& settings() const { return settings_; }
  const SparseGrid& grid() const { return grid_; }
  const BodyContact* contact() const { return contact_.get(); }  // nullptr without contact
  // A coupled model; in a spread run (before or after distribute()) it is handed the ranks.
  void add_coupling(GridCoupling* coupling);
  const std::vector<GridCoupling*>& couplings() const { return couplings_; }

  // Spreads the run over the ranks of `comm` (solver_ranks.cpp), before initialise() or restore().
  // From then on initialise, restore, step, energy, take_removal_events and gather_to_root are
  // collective: every rank calls them alike. The points may start on any ranks (each once); the
  // first step sends each to the rank owning its group. Coupled models are handed the ranks
  // (GridCoupling::spread).
  void distribute(Communicator* comm);
  bool distributed() const { return comm_ != nullptr && comm_->size() > 1; }
  int rank() const { return comm_ ? comm_->rank() : 0; }
  int ranks() const { return distributed() ? comm_->size() : 1; }
  // The ranks of a spread run (nullptr on one rank): output written by every rank at once.
  Communicator* communicator() const { return distributed() ? comm_ : nullptr; }
  // Collective: moves every point to rank 0, for output written there; the next step spreads
  // them again.
  void gather_to_root();
  // Collective: the coupled models bring what they split over ranks to rank 0
  // (GridCoupling::gather_to_root), before rank 0 writes or reports it.
  void gather_coupled_state();
  // A driver that runs on rank 0 only: there, lead() makes each collective call tell the other
  // ranks, which wait in follow(), to make it too. What a follower does beyond the solver's own
  // calls: `restore` when rank 0 restores a checkpoint (read its share of the points, declaring
  // the same fields), and `write(what)` when rank 0 writes a file every rank writes a part of
  // (announce_write(what); mpm/io/), and `measure` when rank 0 takes the closing measures
  // (announce_measure(): each rank gives its points' extrema to max_pairs_over_ranks).
  // stop_followers() (on rank 0, once its driver is done) ends their follow().
  struct FollowerHooks {
    std::function<void()> restore;
    std::function<void(double what)> write;
    std::function<void()> measure;
    std::function<void()> grow;  // a hybrid's zone grows (or not) between two steps
  };
  void lead() { leading_ = true; }
  // Until rank 0 says stop; true when a step failed on every rank (SolverError::every_rank),
  // which rank 0 reports. Any other error propagates.
  bool follow(const FollowerHooks& hooks);
  void announce_write(double what) const { announce(Command::write, what); }
  void announce_measure() const { announce(Command::measure); }
  void announce_grow() const { announce(Command::grow); }
  // Collective: pairs (a, b), one after the other, each replaced by the largest of every rank's,
  // (a, b) ordered by a, then b. The identity on one rank.
  std::vector<double> max_pairs_over_ranks(std::vector<double> pairs) const;
  static void stop_followers(Communicator& comm);
  // The points of the run on every rank (after a step, or when all are on one rank).
  std::size_t point_count() const { return distributed() ? global_points_ : particles_.size(); }
  // What a spread run moved between ranks, seen from this rank: how often the partition was cut
  // (the first cut included; the last one at `cut_step`, taking the fullest rank from
  // `imbalance_before` over the mean to `imbalance_after`), the points it sent or received as
  // migrants, the blocks of nodes it shared with other ranks (summed over steps) and the bytes it
  // sent.
  struct Sharing {
    std::int64_t cuts = 0, migrated = 0, shared_blocks = 0, bytes_sent = 0;
    std::int64_t cut_step = -1;
    double imbalance_before = 0.0, imbalance_after = 0.0;
  };
  const Sharing& sharing() const { return sharing_; }

  // Before the first step: groups particles by material, declares and initialises material state,
  // and chooses the first time step. With `restored`, the particles and state come from a
  // checkpoint and are taken as they are (same order, same next time step).
  void initialise();
  void restore(const SolverState& state);

  // Advances by min(next time step, max_dt).
  void step(double max_dt = std::numeric_limits<double>::infinity());

  // Between steps, takes in the particles from `first` to the end, which the caller appended
  // (Particles::resize) and set (position, velocity, mass, volume0, volume, stress, internal
  // energy, ids, body, material; state fields of the materials' models where they start from
  // other than zero; GIMP half-widths, else V0^(1/3) / 2): checks they lie in the grid, initialises
  // their materials' state as initialise() does, groups the particles by material again and
  // chooses the next time step with them. Throws SolverError naming a particle outside the grid.
  // Collective in a spread run: each rank adopts those it appended (none on most), and the next
  // step sends them to the ranks owning their groups.
  void adopt_particles(std::size_t first);
  // Collective: one more than the largest point id on any rank (0 without points), the first id
  // of points added between steps.
  std::int64_t next_point_id() const;

  double time() const { return state_.time; }
  std::int64_t step_count() const { return state_.step; }
  double next_time_step() const { return state_.next_dt; }
  const SolverState& state() const { return state_; }
  const RemovedMaterial& removed() const { return state_.removed; }
  // The particle moving fastest, and a one-line description of it (for instability messages).
  std::size_t fastest_particle() const;
  // Throws SolverError naming particle p, its body, material, position, the time and step.
  [[noreturn]] void fail(std::size_t particle, const std::string& problem) const;
  std::string failure(std::size_t particle, const std::string& problem) const;
  // Removal events since the last call.
  std::vector<RemovalEvent> take_removal_events();

  EnergyReport energy() const;
  // The largest mean pressure -tr(sigma)/3 of any point now, Pa (collective; -inf without points).
  double peak_pressure() const;
  // The positions of the points with these ids, wherever they are, in the order of their ids
  // (collective: on a run spread over ranks, rank 0 asks with its ids and gets every rank's
  // points; the others call it through follow()). Points no longer in the run are left out.
  struct PointPosition {
    std::int64_t id;
    std::array<double, 3> x;
  };
  std::vector<PointPosition> positions_of(std::vector<std::int64_t> ids) const;
  PhaseTimer& timer() { return timer_; }
  const std::vector<ParticleRange>& material_ranges() const { return ranges_; }
  // Bytes held by particles, grid and bins now.
  std::size_t bytes() const;

 private:
  // Phases of a step.
  void bin_particles();
  void particles_to_grid(Scatter what);
  void apply_contact(NodalVelocity which);
  void couple(GridStage stage);
  void update_grid(bool velocity, bool increment);
  void update_remapped_grid();
  void grid_to_particles(bool remap);
  void compute_velocity_gradient(NodalVelocity which);
  void update_stress();
  void move_particles();
  void remove_escaped_particles();
  void choose_time_step();
  // The energy ledger's work of the stresses on the grid, from the mid-step nodal velocities.
  void book_force_work();
  const double* failed_state() const;
  // A run spread over ranks (solver_ranks.cpp).
  void share_points();
  void count_points();  // collective: the points on every rank, for point_count()
  void migrate(const std::vector<int>& destination);
  void group_by_material();
  void writers_elsewhere(std::uint64_t block_key, std::vector<int>& others) const;
  std::vector<std::uint64_t> blocks_shared_with_others(const SparseGrid& grid) const;
  void find_shared_blocks(const SparseGrid& grid, SharedBlocks& shared);
  void combine_shared(SharedBlocks& shared, const SparseGrid& grid, int components,
                      const SharedBlocks::Target& target);
  double contact_work_over_ranks(NodalVelocity which) const;
  std::vector<std::vector<double>> exchange(std::vector<std::vector<double>> out);
  void gather_removal_events(std::vector<RemovalEvent>& events) const;
  GridRanks grid_ranks();
  // Collective where a rank may find a failure the others do not: with `failure` empty on every
  // rank, returns the largest of every rank's `x`; else throws on every rank the SolverError
  // (every_rank) of the rank whose `failure` is not empty and whose `score` is largest (the lowest
  // such rank on a tie). On one rank, throws `failure` when it is not empty, else returns x.
  double agree_on_failure(const std::string& failure, double score = 0.0, double x = 0.0) const;
  double max_over_ranks(double x) const { return distributed() ? comm_->max(x) : x; }
  enum class Command {
    stop,
    initialise,
    restore,
    step,
    energy,
    removal_events,
    gather,
    pressure,
    write,
    positions,
    measure,
    grow,
    coupled_state
  };
  void announce(Command command, double argument = 0.0) const;

  // f(bins, grid, node average or nullptr) for each velocity field: the solver's, then contact's.
  template <class F>
  void for_each_field(F&& f) {
    f(bins_, grid_, volumetric_.get());
    if (contact_) f(contact_->bins(), contact_->grid(), volumetric1_.get());
  }
  void sort_by_material_and_block();
  void compute_material_ranges();
  TransferContext transfer_context(const SparseGrid& grid) const;

  GridGeometry geometry_;
  SolverSettings settings_;
  std::vector<std::unique_ptr<Material>> materials_;
  std::vector<std::string> body_names_;
  std::vector<GridBoundary> boundaries_;
  std::vector<GridCoupling*> couplings_;

  Particles particles_;
  SparseGrid grid_;
  ParticleBins bins_;
  std::vector<ParticleRange> ranges_;
  std::vector<double>* half_width_ = nullptr;      // GIMP only
  std::unique_ptr<VolumetricAverage> volumetric_;  // Dilatation::node_average only
  // Contact only: field 1's grid and bins, and its node average.
  std::unique_ptr<BodyContact> contact_;
  std::unique_ptr<VolumetricAverage> volumetric1_;
  std::unique_ptr<EnergyLedger> ledger_;  // SolverSettings::energy_ledger only
  std::vector<double> mid_gradient_;      // the ledger's Lbar_p, 9 per point
  // GIMP on one velocity field: the points' stencils from the binning to the domains' stretch
  // (transfers.hpp). Invalidated by bin_particles() and move_particles() (cpGIMP's stretch).
  mutable StencilCache stencils_;

  SolverState state_;
  double dt_ = 0.0;  // of the step in progress
  double max_signal_speed_ = 0.0;
  std::vector<RemovalEvent> removal_events_;
  std::vector<std::uint32_t> escaped_;  // points move_particles() found outside the grid, ascending
  std::vector<MirrorPlane> mirrors_;    // the symmetry planes points are reflected at
  PhaseTimer timer_;
  // A run spread over ranks: the ranks, the partition of the groups among them, and the blocks of
  // nodes this rank shares with others this step (solver_ranks.cpp).
  Communicator* comm_ = nullptr;
  Partition partition_;
  mutable SharedBlocks shared_, shared1_;  // of the solver's grid and of contact's field 1
  Sharing sharing_;
  bool leading_ = false;
  std::size_t global_points_ = 0;
};

}  // namespace hvi::mpm
