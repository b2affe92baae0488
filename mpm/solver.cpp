#include "mpm/solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <omp.h>

#include "mpm/exact_sum.hpp"
#include "mpm/grid_update.hpp"
#include "mpm/point_exchange.hpp"

namespace hvi::mpm {

Solver::Solver(GridGeometry grid, SolverSettings settings,
               std::vector<std::unique_ptr<Material>> materials,
               std::vector<std::string> body_names, std::vector<GridBoundary> boundaries)
    : geometry_(grid),
      settings_(settings),
      materials_(std::move(materials)),
      body_names_(std::move(body_names)),
      boundaries_(std::move(boundaries)),
      grid_(grid),
      mirrors_(mirror_planes(grid, boundaries_)) {
  const int bodies = static_cast<int>(body_names_.size());
  if (settings_.contact) {
    if (settings_.contact->impactor.size() != body_names_.size())
      throw std::invalid_argument("contact: one field entry per body is needed");
    contact_ = std::make_unique<BodyContact>(grid, *settings_.contact);
  }
  if (settings_.dilatation == Dilatation::node_average) {
    volumetric_ = std::make_unique<VolumetricAverage>(bodies);
    if (contact_) volumetric1_ = std::make_unique<VolumetricAverage>(bodies);
  }
  if (settings_.energy_ledger) ledger_ = std::make_unique<EnergyLedger>(body_names_.size());
}

TransferContext Solver::transfer_context(const SparseGrid& grid) const {
  TransferContext c{settings_.shape, half_width_, settings_.flip, dt_};
  if (settings_.stencil_cache && is_gimp(settings_.shape) && !contact_) c.stencils = &stencils_;
  if (distributed()) c.shared = contact_ && &grid == &contact_->grid() ? &shared1_ : &shared_;
  return c;
}

// ---------------------------------------------------------------------------------------------
// Set-up

void Solver::initialise() {
  announce(Command::initialise);
  for (const auto& m : materials_) m->declare_fields(particles_);
  if (is_gimp(settings_.shape)) {
    // A particle's domain: the half-widths its creator gave (the sampling spacing / 2 per axis),
    // else the cube of its initial volume, a = V0^(1/3) / 2 on every axis.
    half_width_ = &particles_.add_field(half_width_field, FieldKind::vector, "m", 0.0, false);
    auto& a = *half_width_;
    for (std::size_t p = 0; p < particles_.size(); ++p) {
      if (a[3 * p] == 0.0)
        a[3 * p] = a[3 * p + 1] = a[3 * p + 2] = 0.5 * std::cbrt(particles_.volume0[p]);
      for (int d = 0; d < 3; ++d)
        if (a[3 * p + d] > 0.5 * geometry_.cell_size * (1.0 + 1e-12))
          throw SolverError(
              fmt::format("GIMP needs particles no larger than a cell: particle {} (body '{}') has "
                          "size {:.4g} m "
                          "but the cell is {:.4g} m; use more particles per cell",
                          particles_.id[p], body_names_.at(particles_.body[p]), 2 * a[3 * p + d],
                          geometry_.cell_size));
    }
  }
  for (std::size_t p = 0; p < particles_.size(); ++p)
    if (!geometry_.contains(&particles_.position[3 * p]))
      throw SolverError(fmt::format(
          "particle {} of body '{}' at ({:.6g}, {:.6g}, {:.6g}) m lies "
          "outside the grid",
          particles_.id[p], body_names_.at(particles_.body[p]), particles_.position[3 * p],
          particles_.position[3 * p + 1], particles_.position[3 * p + 2]));
  bin_particles();
  sort_by_material_and_block();
  for (std::size_t m = 0; m < materials_.size(); ++m)
    materials_[m]->initialise(particles_, ranges_[m]);
  double signal = 0.0;
  for (std::size_t m = 0; m < materials_.size(); ++m)
    signal = std::max(signal, materials_[m]->max_signal_speed(particles_, ranges_[m]));
  max_signal_speed_ = max_over_ranks(signal);
  count_points();
  choose_time_step();
}

void Solver::adopt_particles(std::size_t first) {
  const std::size_t n = particles_.size();
  for (std::size_t p = first; p < n; ++p)
    if (!geometry_.contains(&particles_.position[3 * p]))
      fail(p, "an adopted particle lies outside the grid");
  if (half_width_) {
    auto& a = *half_width_;
    for (std::size_t p = first; p < n; ++p)
      if (a[3 * p] == 0.0)
        a[3 * p] = a[3 * p + 1] = a[3 * p + 2] = 0.5 * std::cbrt(particles_.volume0[p]);
  }
  // The new points in runs of one material, one call (one parallel loop) per run: a take-over
  // adopts thousands of points, and a loop per point cost more than the rest of it.
  double signal = max_signal_speed_;
  for (std::size_t begin = first, end = first; begin < n; begin = end) {
    const auto m = particles_.material[begin];
    while (end < n && particles_.material[end] == m) ++end;
    materials_[m]->initialise(particles_, {begin, end});
    signal = std::max(signal, materials_[m]->max_signal_speed(particles_, {begin, end}));
  }
  max_signal_speed_ = max_over_ranks(signal);
  bin_particles();
  sort_by_material_and_block();
  count_points();
  choose_time_step();
}

std::int64_t Solver::next_point_id() const {
  std::int64_t next = 0;
  for (const auto id : particles_.id) next = std::max(next, id + 1);
  return static_cast<std::int64_t>(max_over_ranks(static_cast<double>(next)));
}

void Solver::restore(const SolverState& state) {
  announce(Command::restore);
  for (const auto& m : materials_) m->declare_fields(particles_);
  if (is_gimp(settings_.shape)) half_width_ = &particles_.field(half_width_field);
  group_by_material();  // a checkpoint lists its points by id
  state_ = state;
  count_points();  // each rank read a share of them
}

void Solver::compute_material_ranges() {
  ranges_.assign(materials_.size(), {});
  std::vector<std::size_t> count(materials_.size(), 0);
  for (const auto m : particles_.material) ++count.at(m);
  std::size_t begin = 0;
  for (std::size_t m = 0; m < materials_.size(); ++m) {
    ranges_[m] = {begin, begin + count[m]};
    begin += count[m];
  }
  for (std::size_t p = 0; p < particles_.size(); ++p) {
    const auto& r = ranges_[particles_.material[p]];
    if (p < r.begin || p >= r.end) throw std::logic_error("particles are not grouped by material");
  }
}

// Reorders particle arrays by material (so each material is one contiguous group) and, inside a
// material, by owner block in the order the transfers visit them (so a block's particles, and a
// group's blocks', are close in memory). Uses the current bins.
void Solver::sort_by_material_and_block() {
  const std::size_t n = particles_.size();
  std::vector<std::size_t> start(materials_.size() + 1, 0);
  for (const auto m : particles_.material) ++start[m + 1];
  for (std::size_t m = 0; m < materials_.size(); ++m) start[m + 1] += start[m];
  std::vector<std::uint32_t> order(n);
  for_each_field([&](const ParticleBins& bins, const SparseGrid&, const VolumetricAverage*) {
    for (const std::uint32_t b : bins.group_owner)  // the order the transfers visit the blocks in
      for (std::uint32_t k = bins.offset[b]; k < bins.offset[b + 1]; ++k) {
        const std::uint32_t p = bins.order[k];
        order[start[particles_.material[p]]++] = p;
      }
  });
  particles_.reorder(order);
  compute_material_ranges();
  bin_particles();
}

// ---------------------------------------------------------------------------------------------
// The step

void Solver::step(double max_dt) {
  announce(Command::step, max_dt);
  dt_ = std::min(state_.next_dt, max_dt);
  if (distributed()) share_points();
  bin_particles();
  if (settings_.reorder_interval > 0 && state_.step % settings_.reorder_interval == 0 &&
      state_.step > 0) {
    auto t = timer_.scope("sort particles");
    sort_by_material_and_block();
  }
  if (distributed()) {
    find_shared_blocks(grid_, shared_);
    if (contact_) find_shared_blocks(contact_->grid(), shared1_);
  }
  switch (settings_.scheme) {
    case UpdateScheme::musl:
      particles_to_grid(Scatter::mass_momentum_force);
      couple(GridStage::mass_momentum);
      couple(GridStage::force);
      update_grid(true, true);
      grid_to_particles(true);  // and remap the updated velocities to the grid
      couple(GridStage::remapped);
      update_remapped_grid();
      compute_velocity_gradient(NodalVelocity::remapped);
      update_stress();
      break;
    case UpdateScheme::usl:
      particles_to_grid(Scatter::mass_momentum_force);
      couple(GridStage::mass_momentum);
      couple(GridStage::force);
      update_grid(true, true);
      grid_to_particles(false);
      compute_velocity_gradient(NodalVelocity::end);
      update_stress();
      break;
    case UpdateScheme::usf:
      particles_to_grid(Scatter::mass_momentum);
      couple(GridStage::mass_momentum);
      update_grid(true, false);
      compute_velocity_gradient(NodalVelocity::start);
      update_stress();
      particles_to_grid(Scatter::force);
      couple(GridStage::force);
      update_grid(false, true);
      grid_to_particles(false);
      break;
  }
  // After every transfer of the step: the bins (each point's owner block, the colours) hold for
  // the domains the step began with, and a domain grown mid-step can reach a node below its owner
  // block's, which a later scatter would write outside its colour's blocks (USF's force scatter
  // did, until the stretch ran here). The stress update reads L, not the domains.
  move_particles();
  state_.time += dt_;
  state_.step += 1;
  remove_escaped_particles();  // books every rank's removals in point_count() too
  choose_time_step();
  if (ledger_) ledger_->close_step(distributed() ? comm_ : nullptr, state_.ledger);
}

void Solver::bin_particles() {
  auto t = timer_.scope("bin particles");
  stencils_.invalidate();
  std::vector<std::uint64_t> extra;
  for (const auto* c : couplings_) c->request_blocks(extra);
  if (!contact_) {
    mpm::bin_particles(particles_, {settings_.shape, half_width_}, grid_, bins_, extra);
    return;
  }
  const std::uint8_t* field = contact_->assign_fields(particles_).data();
  const StencilSource stencil{settings_.shape, half_width_};
  SparseGrid& grid1 = contact_->grid();
  if (!distributed()) {
    mpm::bin_particles(particles_, stencil, grid_, bins_, extra, field, 0);
    mpm::bin_particles(particles_, stencil, grid1, contact_->bins(), {}, field, 1);
    return;
  }
  // Spread over ranks, each field's grid also holds the other field's blocks that other ranks'
  // groups may write: the fields meet there, and the points this rank holds of either field read
  // both fields' sums of those nodes (shared, so combined over the ranks). Field 1 (the impactor,
  // the fewer points) is binned twice, so that each field's grid knows the other's blocks.
  mpm::bin_particles(particles_, stencil, grid1, contact_->bins(), {}, field, 1);
  mpm::bin_particles(particles_, stencil, grid_, bins_, blocks_shared_with_others(grid1), field, 0);
  mpm::bin_particles(particles_, stencil, grid1, contact_->bins(), blocks_shared_with_others(grid_),
                     field, 1);
}

void Solver::particles_to_grid(Scatter what) {
  for_each_field([&](const ParticleBins& bins, SparseGrid& grid, VolumetricAverage* volumetric) {
    TransferContext context = transfer_context(grid);
    if (volumetric && what != Scatter::mass_momentum) {
      auto t = timer_.scope("mean stress: node average");
      context.mean_stress = &volumetric->mean_stress_sums(particles_, bins, grid, context);
    }
    auto t = timer_.scope("particles to grid");
    // The components the scatter adds (grid.hpp: mass, momentum, force).
    mpm::particles_to_grid(what, particles_, bins, grid, context);
  });
  if (contact_ && what != Scatter::force) {
    auto t = timer_.scope("contact: normals");
    contact_->compute_normals(particles_, bins_, grid_, transfer_context(grid_),
                              transfer_context(contact_->grid()));
  }
  if (contact_ && contact_->bond() && what != Scatter::force) {
    auto t = timer_.scope("bond");
    contact_->bond()->prepare(particles_, contact_->grid(), settings_.shape, half_width_,
                              distributed() ? comm_ : nullptr);
  }
}

void Solver::apply_contact(NodalVelocity which) {
  if (!contact_) return;
  auto t = timer_.scope("contact");
  const double work = contact_->apply(grid_, which, dt_);
  state_.contact_work += distributed() ? contact_work_over_ranks(which) : work;
  if (contact_->bond() && which == NodalVelocity::end)
    contact_->bond()->break_overloaded(particles_, contact_->grid(), settings_.shape, half_width_);
  apply_grid_conditions(contact_->grid(), boundaries_);
  apply_grid_conditions(grid_, boundaries_);
}

void Solver::couple(GridStage stage) {
  if (couplings_.empty()) return;
  auto t = timer_.scope("coupling");
  for (auto* c : couplings_) c->add_to_grid(grid_, stage, state_.time, dt_);
}

void Solver::update_grid(bool velocity, bool increment) {
  {
    auto t = timer_.scope("grid update");
    for_each_field([&](const ParticleBins&, SparseGrid& grid, const VolumetricAverage*) {
      update_nodes(grid, velocity, increment, dt_);
      apply_grid_conditions(grid, boundaries_);
    });
  }
  if (velocity) apply_contact(NodalVelocity::start);
  if (increment) apply_contact(NodalVelocity::end);
  if (increment && !couplings_.empty()) {
    auto t = timer_.scope("coupling");
    for (auto* c : couplings_) c->take_from_grid(grid_, state_.time, dt_);
  }
}

void Solver::update_remapped_grid() {
  {
    auto t = timer_.scope("grid update");
    for_each_field([&](const ParticleBins&, SparseGrid& grid, const VolumetricAverage*) {
      update_remapped(grid);
      apply_grid_conditions(grid, boundaries_);
    });
  }
  apply_contact(NodalVelocity::remapped);
}

void Solver::grid_to_particles(bool remap) {
  if (ledger_) {
    book_force_work();
    ledger_->start_transfer(particles_);
  }
  {
    auto t = timer_.scope("grid to particles");
    for_each_field([&](const ParticleBins& bins, SparseGrid& grid, const VolumetricAverage*) {
      mpm::grid_to_particles(particles_, bins, grid, transfer_context(grid), remap);
    });
  }
  if (ledger_) ledger_->end_transfer(particles_);
}

// Lbar_p from the mid-step nodal velocities into mid_gradient_ (the points' own velocity gradient
// is kept: USF's moves their domains), then W_b with the stress and volume the force scatter used.
void Solver::book_force_work() {
  auto t = timer_.scope("energy ledger");
  std::swap(particles_.velocity_gradient, mid_gradient_);
  particles_.velocity_gradient.resize(9 * particles_.size());
  for_each_field([&](const ParticleBins& bins, SparseGrid& grid, const VolumetricAverage*) {
    mpm::velocity_gradient(particles_, bins, grid, transfer_context(grid), NodalVelocity::mid);
  });
  std::swap(particles_.velocity_gradient, mid_gradient_);
  ledger_->add_force_work(particles_, mid_gradient_, dt_, failed_state());
}

const double* Solver::failed_state() const {
  // Declared by the materials that can fail or erode a point (0 intact).
  return particles_.has_field("failed") ? particles_.field("failed").data() : nullptr;
}

void Solver::compute_velocity_gradient(NodalVelocity which) {
  for_each_field([&](const ParticleBins& bins, SparseGrid& grid, VolumetricAverage* volumetric) {
    {  // with the node average, the same pass scatters tr L_p into its sums
      auto t = timer_.scope("velocity gradient");
      mpm::velocity_gradient(particles_, bins, grid, transfer_context(grid), which,
                             volumetric ? &volumetric->dilatation_sums(particles_) : nullptr,
                             volumetric ? volumetric->dilatation_values() : nullptr);
    }
    if (volumetric) {
      auto t = timer_.scope("dilatation: node average");
      volumetric->average_dilatation(particles_, bins, grid, transfer_context(grid));
    }
  });
}

void Solver::update_stress() {
  const StressContext context{dt_, state_.time, state_.step, &timer_};
  double signal = 0.0;
  std::string bad;  // the first failing point's, in material order
  if (ledger_) ledger_->start_stress(particles_);
  for (std::size_t m = 0; m < materials_.size() && bad.empty(); ++m) {
    if (ranges_[m].size() == 0) continue;
    const StressUpdate r = materials_[m]->update_stress(particles_, ranges_[m], context);
    if (r.bad_particle >= 0) bad = failure(static_cast<std::size_t>(r.bad_particle), r.problem);
    signal = std::max(signal, r.max_signal_speed);
  }
  if (ledger_) ledger_->end_stress(particles_, failed_state());
  max_signal_speed_ = agree_on_failure(bad, 0.0, signal);  // the largest over the ranks
}

// cpGIMP: the axis-aligned domain follows the stretch along each axis, a_d <- a_d (1 + dt L_dd),
// up to h / 2 (the three-node stencil's limit) and, in compression, down to h / 10 but never
// below where it started. Letting domains shrink further brings back linear-like cell-crossing
// noise: a 10 km/s impact then gained 59% energy (3.9% with the floor), and the floor also puts
// the Taylor-bar foot at 11.34 mm instead of 11.43 (benchmark 11.18-11.22).
//
// Per point, in one pass: the stretch of its domain (cpGIMP), x <- x + dt v_grid, the reflection
// at each symmetry plane it crossed, and whether it has left the grid (into escaped_).
void Solver::move_particles() {
  auto t = timer_.scope("move particles");
  const bool stretch = settings_.shape == ShapeFunction::cpgimp;
  if (stretch) stencils_.invalidate();
  double* a = stretch ? half_width_->data() : nullptr;
  const double* L = particles_.velocity_gradient.data();
  double* x = particles_.position.data();
  double* v = particles_.velocity.data();
  double* vg = particles_.grid_velocity.data();
  const double floor = 0.1 * geometry_.cell_size, ceiling = 0.5 * geometry_.cell_size, dt = dt_;
  const auto n = static_cast<std::int64_t>(particles_.size());
  std::vector<std::vector<std::uint32_t>> escaped(static_cast<std::size_t>(omp_get_max_threads()));
#pragma omp parallel
  {
    // Static ranges in thread order, so the lists join in ascending order.
    const std::int64_t threads = omp_get_num_threads(), id = omp_get_thread_num();
    auto& out = escaped[static_cast<std::size_t>(id)];
    for (std::int64_t p = n * id / threads; p < n * (id + 1) / threads; ++p) {
      if (stretch)
        for (int d = 0; d < 3; ++d) {
          double& ad = a[3 * p + d];
          ad = std::min(std::max(ad * (1.0 + dt * L[9 * p + 4 * d]), std::min(floor, ad)), ceiling);
        }
      for (int d = 0; d < 3; ++d) x[3 * p + d] += dt * vg[3 * p + d];
      for (const auto& m : mirrors_) reflect(m, &x[3 * p], &v[3 * p], &vg[3 * p]);
      if (!geometry_.contains(&x[3 * p])) out.push_back(static_cast<std::uint32_t>(p));
    }
  }
  escaped_.clear();
  for (const auto& e : escaped) escaped_.insert(escaped_.end(), e.begin(), e.end());
}

// The points that left the grid, booked as removed, then taken out: the last points of each
// material move into the gaps (Particles::erase).
void Solver::remove_escaped_particles() {
  if (escaped_.empty() && !distributed()) return;
  auto t = timer_.scope("remove escaped");
  std::string bad;
  for (const std::uint32_t p : escaped_) {
    const double* x = &particles_.position[3 * p];
    if (!std::isfinite(x[0] + x[1] + x[2])) {
      bad = failure(p, "non-finite position");
      break;
    }
  }
  if (!distributed()) agree_on_failure(bad);  // throws it; spread, the sums below carry it
  auto& r = state_.removed;
  const std::size_t first_event = removal_events_.size();
  // This step's removals summed exactly (the same in any order of the points), then booked.
  std::array<ExactSum, 8> step;  // mass, kinetic, internal, momentum, count, ranks that failed
  if (!bad.empty()) step[7] += 1.0;
  for (const std::uint32_t p : escaped_) {
    const double m = particles_.mass[p];
    const double* v = &particles_.velocity[3 * p];
    step[6] += 1.0;
    step[0] += m;
    step[1] += 0.5 * m * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    step[2] += m * particles_.internal_energy[p];
    for (int d = 0; d < 3; ++d) step[3 + d] += m * v[d];
    if (ledger_)
      ledger_->add_removed(
          static_cast<std::size_t>(particles_.body[p]),
          0.5 * m * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) + m * particles_.internal_energy[p]);
    removal_events_.push_back({particles_.id[p],
                               particles_.body[p],
                               particles_.material[p],
                               {particles_.position[3 * p], particles_.position[3 * p + 1],
                                particles_.position[3 * p + 2]},
                               {v[0], v[1], v[2]},
                               m,
                               state_.time,
                               state_.step});
  }
  // The step's events by id, as the points' order in the arrays may be any.
  std::sort(removal_events_.begin() + static_cast<std::ptrdiff_t>(first_event),
            removal_events_.end(),
            [](const RemovalEvent& a, const RemovalEvent& b) { return a.id < b.id; });
  if (distributed()) {
    add_over_ranks(*comm_, step);                      // every rank books every rank's removals
    if (step[7].value() > 0.0) agree_on_failure(bad);  // on every rank alike: it throws
  }
  r.particles += static_cast<std::int64_t>(step[6].value());
  global_points_ -= static_cast<std::size_t>(step[6].value());
  r.mass += step[0].value();
  r.kinetic += step[1].value();
  r.internal += step[2].value();
  for (int d = 0; d < 3; ++d) r.momentum[d] += step[3 + d].value();
  std::vector<std::size_t> sizes;
  for (const auto& range : ranges_) sizes.push_back(range.size());
  particles_.erase(escaped_, sizes);
  escaped_.clear();
  compute_material_ranges();
}

void Solver::choose_time_step() {
  double dt = settings_.max_time_step;
  if (max_signal_speed_ > 0.0)
    dt = std::min(dt, settings_.cfl * geometry_.cell_size / max_signal_speed_);
  for (const auto* c : couplings_) dt = std::min(dt, c->stable_time_step());
  // dt is the same on every rank (the signal speed is their largest), so every rank fails here.
  if (!std::isfinite(dt) || dt <= 0.0)
    throw SolverError(
        fmt::format("step {}, t = {:.6g} s: no finite time step (max signal speed {:.6g} m/s)",
                    state_.step, state_.time, max_signal_speed_),
        distributed());
  if (state_.first_dt == 0.0) state_.first_dt = dt;
  if (dt < settings_.min_time_step_fraction * state_.first_dt && point_count() > 0) {
    std::string fastest;  // this rank's fastest point, if it holds any; the fastest rank's wins
    double v = -1.0;
    if (particles_.size() > 0) {
      const std::size_t p = fastest_particle();
      v = speed(particles_, p);
      fastest =
          failure(p, fmt::format("the time step collapsed to {:.3g} s ({:.2g} of the first, "
                                 "{:.3g} s; signal speed {:.4g} m/s): the run is unstable; "
                                 "this particle moves fastest, at {:.4g} m/s",
                                 dt, dt / state_.first_dt, state_.first_dt, max_signal_speed_, v));
    }
    agree_on_failure(fastest, v == v ? v : std::numeric_limits<double>::infinity());
  }
  state_.next_dt = dt;
}

std::size_t Solver::fastest_particle() const {
  std::size_t best = 0;
  double v_best = -1.0;
  for (std::size_t p = 0; p < particles_.size(); ++p) {
    const double v = speed(particles_, p);
    if (v > v_best || !(v == v)) {  // a NaN speed is the worst of all
      v_best = v == v ? v : std::numeric_limits<double>::infinity();
      best = p;
    }
  }
  return best;
}

std::vector<RemovalEvent> Solver::take_removal_events() {
  announce(Command::removal_events);
  std::vector<RemovalEvent> events;
  events.swap(removal_events_);
  if (distributed()) gather_removal_events(events);
  return events;
}

void Solver::fail(std::size_t p, const std::string& problem) const {
  throw SolverError(failure(p, problem));
}

std::string Solver::failure(std::size_t p, const std::string& problem) const {
  const double* x = &particles_.position[3 * p];
  return fmt::format(
      "step {}, t = {:.6g} s: particle {} (body '{}', material '{}') at ({:.6g}, {:.6g}, {:.6g}) "
      "m: {}",
      state_.step, state_.time, particles_.id[p], body_names_.at(particles_.body[p]),
      materials_.at(particles_.material[p])->name(), x[0], x[1], x[2], problem);
}

// ---------------------------------------------------------------------------------------------
// Diagnostics

EnergyReport Solver::energy() const {
  announce(Command::energy);
  // Exact sums over fixed chunks, merged exactly: the same bits for any thread count and any order
  // of the points.
  constexpr std::int64_t chunk = 4096;
  const auto n = static_cast<std::int64_t>(particles_.size());
  const std::int64_t chunks = (n + chunk - 1) / chunk;
  std::vector<std::array<ExactSum, 7>> partial(static_cast<std::size_t>(chunks));
#pragma omp parallel for schedule(static)
  for (std::int64_t c = 0; c < chunks; ++c) {
    auto& s = partial[static_cast<std::size_t>(c)];
    for (std::int64_t p = c * chunk; p < std::min(n, (c + 1) * chunk); ++p) {
      const double m = particles_.mass[p];
      const double* v = &particles_.velocity[3 * p];
      s[0] += 0.5 * m * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      s[1] += m * particles_.internal_energy[p];
      for (int d = 0; d < 3; ++d) s[2 + d] += m * v[d];
      s[5] += m;
    }
  }
  std::array<ExactSum, 7> total;  // the six above and the dissipated energy
  for (const auto& s : partial)
    for (std::size_t k = 0; k < 6; ++k) total[k] += s[k];
  for (std::size_t m = 0; m < materials_.size(); ++m)
    materials_[m]->add_dissipated_energy(particles_, ranges_[m], total[6]);
  if (distributed()) add_over_ranks(*comm_, total);
  std::array<double, 7> sum{};
  for (std::size_t k = 0; k < 7; ++k) sum[k] = total[k].value();
  EnergyReport e;
  e.kinetic = sum[0];
  e.dissipated = sum[6];
  e.internal = sum[1] - e.dissipated;
  e.momentum = {sum[2], sum[3], sum[4]};
  e.mass = sum[5];
  const auto& r = state_.removed;
  e.removed = r.kinetic + r.internal;
  e.removed_momentum = r.momentum;
  e.removed_mass = r.mass;
  e.contact = state_.contact_work;
  if (ledger_) {
    e.ledger.assign(body_names_.size(), {});
    for (std::size_t k = 0; k < state_.ledger.size(); ++k)
      e.ledger[k / ledger::columns][k % ledger::columns] = state_.ledger[k];
  }
  for (const auto* c : couplings_) {
    const CoupledEnergy ce = c->energy();
    e.coupled_kinetic += ce.kinetic;
    e.coupled_strain += ce.strain;
    for (int d = 0; d < 3; ++d) e.momentum[d] += ce.momentum[d];
  }
  return e;
}

double Solver::peak_pressure() const {
  announce(Command::pressure);
  double peak = -std::numeric_limits<double>::infinity();
  const auto n = static_cast<std::int64_t>(particles_.size());
#pragma omp parallel for reduction(max : peak) schedule(static)
  for (std::int64_t p = 0; p < n; ++p)
    peak = std::max(peak, -trace_sym(&particles_.stress[6 * p]) / 3.0);
  return max_over_ranks(peak);
}

std::size_t Solver::bytes() const {
  return particles_.bytes() + grid_.bytes() + bins_.bytes() + stencils_.bytes() +
         (volumetric_ ? volumetric_->bytes() : 0) + (contact_ ? contact_->bytes() : 0) +
         (volumetric1_ ? volumetric1_->bytes() : 0);
}

}  // namespace hvi::mpm
