// The far field with deal.II: mesh, DoFs numbered node-major, matrix-free stiffness (and J2 or
// capped core stresses in plastic layers), lumped mass, the element bound of the stable time step,
// and VTU output.
#include "fem/far_field_impl.hpp"

namespace hvi::fem {

FarField::FarField(const LayeredMesh& mesh, unsigned threads) : impl_(std::make_unique<Impl>()) {
  MultithreadInfo::set_thread_limit(std::max(1u, threads));
  impl_->spec = mesh;
  impl_->build_mesh();
  impl_->number_nodes();
  impl_->setup_matrix_free();
  impl_->colour_batches();
  impl_->setup_plasticity();
  impl_->dt_stable = impl_->element_bound_time_step();
}

FarField::~FarField() = default;

std::size_t FarField::node_count() const {
  return impl_->mass.size();
}
std::size_t FarField::cell_count() const {
  return impl_->triangulation.n_active_cells();
}
int FarField::degree() const {
  return impl_->spec.degree;
}
std::span<const double> FarField::reference_positions() const {
  return impl_->positions;
}
std::span<const double> FarField::lumped_mass() const {
  return impl_->mass;
}
std::span<const int> FarField::node_layer() const {
  return impl_->layer;
}
std::span<double> FarField::displacement() {
  return {impl_->u.begin(), impl_->u.size()};
}
std::span<const double> FarField::displacement() const {
  return {impl_->u.begin(), impl_->u.size()};
}
std::span<double> FarField::velocity() {
  return {impl_->v.begin(), impl_->v.size()};
}
std::span<const double> FarField::velocity() const {
  return {impl_->v.begin(), impl_->v.size()};
}

void FarField::fix(std::size_t node, unsigned components) {
  impl_->fixed.at(node) |= components & 7u;
  for (int d = 0; d < 3; ++d)
    if (components & (1u << d)) impl_->u[3 * node + d] = impl_->v[3 * node + d] = 0.0;
}
unsigned FarField::fixed(std::size_t node) const {
  return impl_->fixed.at(node);
}

void FarField::apply_stiffness(std::span<const double> u, std::span<double> Ku) const {
  const auto n = impl_->u.size();
  if (u.size() != n || Ku.size() != n) throw std::invalid_argument("far field: vector size");
  std::copy(u.begin(), u.end(), impl_->work_in.begin());
  impl_->apply(impl_->work_in, impl_->work_out);
  std::copy(impl_->work_out.begin(), impl_->work_out.end(), Ku.begin());
}

void FarField::internal_force(std::span<double> force, double dt) {
  if (force.size() != impl_->u.size()) throw std::invalid_argument("far field: force size");
  impl_->rate_dt = dt;
  impl_->internal(impl_->u, impl_->work_out);
  for (std::size_t i = 0; i < force.size(); ++i) force[i] = -impl_->work_out[i];
}

void FarField::step(double dt, std::span<const double> external) {
  auto& I = *impl_;
  I.rate_dt = dt;
  I.internal(I.u, I.work_out);  // K u when elastic
  const std::size_t nodes = I.mass.size();
  for (std::size_t a = 0; a < nodes; ++a)
    for (int d = 0; d < 3; ++d) {
      const std::size_t i = 3 * a + d;
      if ((I.fixed[a] & (1u << d)) || I.mass[a] == 0.0) {  // held, or detached by remove_cells
        I.v[i] = 0.0;
        continue;
      }
      const double f = -I.work_out[i] + (external.empty() ? 0.0 : external[i]);
      I.v[i] += dt * f / I.mass[a];
      I.u[i] += dt * I.v[i];
    }
}

double FarField::stable_time_step() const {
  double s = 1.0;
  for (const double b : impl_->batch_stretch) s = std::max(s, b);
  return impl_->dt_stable / std::sqrt(0.5 * (3.0 * s - 1.0));
}

double FarField::kinetic_energy(std::span<const double> v) const {
  double e = 0.0;
  for (std::size_t a = 0; a < impl_->mass.size(); ++a)
    e += 0.5 * impl_->mass[a] *
         (v[3 * a] * v[3 * a] + v[3 * a + 1] * v[3 * a + 1] + v[3 * a + 2] * v[3 * a + 2]);
  return e;
}
double FarField::kinetic_energy() const {
  return kinetic_energy(velocity());
}

double FarField::strain_energy() const {
  const auto& I = *impl_;
  if (I.nonlinear())
    return I.spec.degree == 1 ? I.elastic_energy_kernel<1>(I.u) : I.elastic_energy_kernel<2>(I.u);
  I.apply(I.u, I.work_out);
  return 0.5 * (I.u * I.work_out);
}

double FarField::plastic_work() const {
  return impl_->plastic_work;
}

std::vector<FarField::PointSample> FarField::sample(std::span<const double> points) const {
  const auto& I = *impl_;
  const unsigned p = I.spec.degree, n1 = p + 1;
  const QGauss<1> gauss(n1);
  const std::size_t ny = I.lines[1].size() - 1, nz = I.lines[2].size() - 1;
  std::vector<types::global_dof_index> dofs(I.fe->n_dofs_per_cell());
  std::vector<PointSample> out(points.size() / 3);
  for (std::size_t s = 0; s < out.size(); ++s) {
    const double* x = &points[3 * s];
    // The brick holding x, and x in its unit cube.
    std::array<std::size_t, dim> b{};
    Point<dim> unit;
    bool inside = true;
    for (int d = 0; d < dim && inside; ++d) {
      const auto& L = I.lines[d];
      const double tol = 1e-9 * (L.back() - L.front());
      if (x[d] < L.front() - tol || x[d] > L.back() + tol) {
        inside = false;
        break;
      }
      auto it = std::upper_bound(L.begin(), L.end(), x[d]);
      b[d] = std::min<std::size_t>(std::max<std::ptrdiff_t>(it - L.begin() - 1, 0), L.size() - 2);
      unit[d] = std::clamp((x[d] - L[b[d]]) / (L[b[d] + 1] - L[b[d]]), 0.0, 1.0);
    }
    if (!inside) continue;
    const int index = I.brick_cell[(b[0] * ny + b[1]) * nz + b[2]];
    if (index < 0 || I.cell_removed[index]) continue;
    const auto& cell = I.cell_iterator[index];
    cell->get_dof_indices(dofs);
    PointSample& r = out[s];
    r.layer = cell->material_id();
    Tensor<2, dim> H;
    for (unsigned i = 0; i < dofs.size(); ++i) {
      const unsigned c = I.fe->system_to_component_index(i).first;
      const double N = I.fe->shape_value_component(i, unit, c);
      const Tensor<1, dim> g = I.fe->shape_grad_component(i, unit, c);
      r.displacement[c] += N * I.u[dofs[i]];
      r.velocity[c] += N * I.v[dofs[i]];
      for (int d = 0; d < dim; ++d)
        H[c][d] += g[d] / (I.lines[d][b[d] + 1] - I.lines[d][b[d]]) * I.u[dofs[i]];
    }
    for (int k = 0; k < 6; ++k)
      r.strain[k] = 0.5 * (H[voigt[k][0]][voigt[k][1]] + H[voigt[k][1]][voigt[k][0]]);
    Tensor<2, dim> eps;
    for (int k = 0; k < 6; ++k)
      eps[voigt[k][0]][voigt[k][1]] = eps[voigt[k][1]][voigt[k][0]] = r.strain[k];
    const auto [batch, lane] = I.cell_lane[index];
    if (I.any_plastic() && I.lane_is_plastic(batch, lane)) {
      // The nearest Gauss point: per axis the nearest of the n1 points, x running fastest.
      unsigned q = 0;
      for (int d = dim - 1; d >= 0; --d) {
        unsigned best = 0;
        for (unsigned k = 1; k < n1; ++k)
          if (std::abs(gauss.point(k)[0] - unit[d]) < std::abs(gauss.point(best)[0] - unit[d]))
            best = k;
        q = q * n1 + best;
      }
      const double* st = I.state(batch, q, lane);
      for (int k = 0; k < 6; ++k) {
        eps[voigt[k][0]][voigt[k][1]] -= st[k];
        if (voigt[k][0] != voigt[k][1]) eps[voigt[k][1]][voigt[k][0]] -= st[k];
      }
      r.plastic_strain = st[6];
      r.damage = I.damage_slot ? st[7] : 0.0;
    }
    const Tensor<2, dim> sigma = orthotropic_stress(I.layer_stiffness[r.layer], eps);
    for (int k = 0; k < 6; ++k) {
      r.stress[k] = sigma[voigt[k][0]][voigt[k][1]];
      r.elastic_strain[k] = eps[voigt[k][0]][voigt[k][1]];
    }
  }
  return out;
}

std::size_t FarField::remove_cells(const std::array<double, 4>& box) {
  auto& I = *impl_;
  std::size_t newly = 0;
  for (unsigned cell = 0; cell < I.matrix_free.n_cell_batches(); ++cell)
    for (unsigned lane = 0; lane < I.matrix_free.n_active_entries_per_cell_batch(cell); ++lane) {
      const auto it = I.matrix_free.get_cell_iterator(cell, lane);
      const Point<dim> c = it->center();
      const std::size_t l = Impl::W * cell + lane;
      if (I.lane_removed[l] || !centre_inside(c[0], c[1], box)) continue;
      // No stiffness (so no stress, force or strain energy), no plastic state, no mass.
      I.lane_removed[l] = 1;
      I.cell_removed[it->active_cell_index()] = 1;
      for (auto& C : I.batch_stiffness[cell]) C[lane] = 0.0;
      if (!I.lane_layer.empty()) I.lane_layer[l] = -1;
      ++newly;
    }
  if (newly == 0) return 0;
  I.removed_cells += newly;
  const auto all_removed = [&](unsigned cell) {
    for (unsigned lane = 0; lane < I.matrix_free.n_active_entries_per_cell_batch(cell); ++lane)
      if (!I.lane_removed[Impl::W * cell + lane]) return false;
    if (!I.batch_stretch.empty())
      I.batch_stretch[cell] = 1.0;  // what its kept cells would give: none
    return true;
  };
  for (auto* list : {&I.colours, &I.all_colours})
    for (auto& colour : *list) std::erase_if(colour, all_removed);
  I.lump_mass();
  for (std::size_t a = 0; a < I.mass.size(); ++a)
    if (I.mass[a] == 0.0)
      for (int d = 0; d < dim; ++d) I.v[3 * a + d] = 0.0;
  return newly;
}

std::size_t FarField::removed_cell_count() const {
  return impl_->removed_cells;
}
std::size_t FarField::evaluated_batch_count() const {
  std::size_t n = 0;
  for (const auto& colour : impl_->colours) n += colour.size();
  return n;
}
bool FarField::plastic() const {
  return impl_->any_plastic();
}
bool FarField::finite_strain() const {
  return impl_->spec.finite_strain;
}

namespace {
// The largest accumulated plastic strain (state slot 6) over the quadrature points of the plastic
// lanes whose layer `core` is or is not a yielding core.
template <class Impl>
double max_accumulated(const Impl& I, bool core) {
  double m = 0.0;
  if (!I.any_plastic()) return m;
  for (unsigned cell = 0; cell < I.matrix_free.n_cell_batches(); ++cell)
    for (unsigned lane = 0; lane < Impl::W; ++lane) {
      if (!I.lane_is_plastic(cell, lane) ||
          I.lane_layer_spec(cell, lane)->core_yield.has_value() != core)
        continue;
      for (unsigned q = 0; q < I.n_q; ++q) m = std::max(m, I.state(cell, q, lane)[6]);
    }
  return m;
}

// The volume of the failing core's (`core`) or facesheets' torn quadrature points (damage, state
// slot 7, >= 1): each cell's volume times the fraction of its points torn.
template <class Impl>
double failed_volume(const Impl& I, bool core) {
  if (!I.damage_slot) return 0.0;
  double v = 0.0;
  for (unsigned cell = 0; cell < I.matrix_free.n_cell_batches(); ++cell)
    for (unsigned lane = 0; lane < Impl::W; ++lane) {
      if (!I.lane_is_plastic(cell, lane) ||
          I.lane_layer_spec(cell, lane)->core_yield.has_value() != core)
        continue;
      unsigned failed = 0;
      for (unsigned q = 0; q < I.n_q; ++q) failed += I.state(cell, q, lane)[7] >= 1.0;
      v += I.matrix_free.get_cell_iterator(cell, lane)->measure() * failed / I.n_q;
    }
  return v;
}
}  // namespace

double FarField::max_equivalent_plastic_strain() const {
  return max_accumulated(*impl_, false);
}
double FarField::max_core_plastic_strain() const {
  return max_accumulated(*impl_, true);
}
std::vector<double> FarField::damaged_cell_centres(double damage) const {
  const auto& I = *impl_;
  std::vector<double> centres;
  if (!I.damage_slot) return centres;  // no failing layer: no damage slot
  for (unsigned cell = 0; cell < I.matrix_free.n_cell_batches(); ++cell)
    for (unsigned lane = 0; lane < I.matrix_free.n_active_entries_per_cell_batch(cell); ++lane) {
      if (I.ranks && I.batch_reporter[cell] != I.ranks->rank) continue;  // another rank's
      if (!I.lane_is_plastic(cell, lane)) continue;  // elastic, or removed (its layer is -1)
      double d = 0.0;
      for (unsigned q = 0; q < I.n_q; ++q) d = std::max(d, I.state(cell, q, lane)[7]);
      if (d < damage) continue;
      const Point<dim> c = I.matrix_free.get_cell_iterator(cell, lane)->center();
      centres.push_back(c[0]);
      centres.push_back(c[1]);
    }
  return centres;
}

double FarField::core_failed_volume() const {
  return failed_volume(*impl_, true);
}
double FarField::facesheet_failed_volume() const {
  return failed_volume(*impl_, false);
}

std::vector<std::pair<std::string, std::span<double>>> FarField::plastic_state() {
  if (!impl_->any_plastic()) return {};
  return {{"far_field_plastic_state", impl_->plastic},
          {"far_field_plastic_work", {&impl_->plastic_work, 1}}};
}

std::array<double, 3> FarField::momentum() const {
  std::array<double, 3> p{};
  for (std::size_t a = 0; a < impl_->mass.size(); ++a)
    for (int d = 0; d < 3; ++d) p[d] += impl_->mass[a] * impl_->v[3 * a + d];
  return p;
}

std::size_t FarField::bytes() const {
  const auto& I = *impl_;
  return I.triangulation.memory_consumption() + I.dof_handler.memory_consumption() +
         I.matrix_free.memory_consumption() + 4 * I.u.memory_consumption() +
         I.positions.size() * sizeof(double) +
         I.mass.size() * (sizeof(double) + sizeof(int) + sizeof(unsigned)) +
         I.batch_stiffness.size() * sizeof(std::array<VA, 9>) +
         (I.plastic.size() + I.batch_stretch.size()) * sizeof(double) +
         (I.lane_layer.size() + I.plastic_slot.size()) * sizeof(int) + I.lane_removed.size() +
         I.cell_removed.size();
}

void FarField::write_vtu(const std::string& path) const {
  const auto& I = *impl_;
  DataOut<dim> out;
  out.attach_dof_handler(I.dof_handler);
  if (I.removed_cells > 0)
    out.set_cell_selection([&](const Triangulation<dim>::cell_iterator& cell) {
      return cell->is_active() && !I.cell_removed[cell->active_cell_index()];
    });
  const std::vector<DataComponentInterpretation::DataComponentInterpretation> vector(
      dim, DataComponentInterpretation::component_is_part_of_vector);
  out.add_data_vector(I.u, std::vector<std::string>(dim, "displacement"),
                      DataOut<dim>::type_dof_data, vector);
  out.add_data_vector(I.v, std::vector<std::string>(dim, "velocity"), DataOut<dim>::type_dof_data,
                      vector);
  // Per cell the largest value of state slot `k` at its quadrature points (0 in elastic cells;
  // with `core`, only the cells that are (true) or are not (false) a yielding core's).
  auto cell_max = [&](int k, std::optional<bool> core = std::nullopt) {
    Vector<double> m(I.triangulation.n_active_cells());
    for (unsigned cell = 0; cell < I.matrix_free.n_cell_batches(); ++cell)
      for (unsigned lane = 0; lane < Impl::W; ++lane) {
        if (!I.lane_is_plastic(cell, lane)) continue;
        if (core && I.lane_layer_spec(cell, lane)->core_yield.has_value() != *core) continue;
        double& v = m[I.matrix_free.get_cell_iterator(cell, lane)->active_cell_index()];
        for (unsigned q = 0; q < I.n_q; ++q) v = std::max(v, I.state(cell, q, lane)[k]);
      }
    return m;
  };
  // DataOut keeps references: the vectors live to the end of the function.
  Vector<double> alpha, core_damage, facesheet_damage;
  if (I.any_plastic()) {
    alpha = cell_max(6);  // alpha, or a yielding core's accumulated strain
    out.add_data_vector(alpha, "equivalent_plastic_strain", DataOut<dim>::type_cell_data);
  }
  bool failing_core = false, failing_faces = false;
  for (const Layer& L : I.spec.layers) {
    failing_core = failing_core || (L.core_yield && L.core_yield->failure);
    failing_faces = failing_faces || L.failure;
  }
  if (failing_core) {
    core_damage = cell_max(7, true);  // a failing core's damage D
    out.add_data_vector(core_damage, "core_damage", DataOut<dim>::type_cell_data);
  }
  if (failing_faces) {
    facesheet_damage = cell_max(7, false);
    out.add_data_vector(facesheet_damage, "facesheet_damage", DataOut<dim>::type_cell_data);
  }
  out.build_patches(I.mapping, I.spec.degree);
  DataOutBase::VtkFlags flags;
  flags.print_date_and_time = false;  // the same state gives the same bytes
  out.set_flags(flags);
  std::ofstream file(path);
  if (!file) throw std::runtime_error("cannot write " + path);
  out.write_vtu(file);
}

void FarField::write_pvd(const std::string& path,
                         const std::vector<std::pair<double, std::string>>& entries) {
  // Written here rather than by DataOutBase::write_pvd_record, which stamps the date and time
  // into the file: the same run must give the same bytes.
  std::ofstream file(path);
  if (!file) throw std::runtime_error("cannot write " + path);
  file << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" "
          "ByteOrder=\"LittleEndian\">\n"
          "  <Collection>\n";
  char time[32];
  for (const auto& [t, name] : entries) {
    std::snprintf(time, sizeof time, "%.17g", t);
    file << "    <DataSet timestep=\"" << time << "\" group=\"\" part=\"0\" file=\"" << name
         << "\"/>\n";
  }
  file << "  </Collection>\n</VTKFile>\n";
}

}  // namespace hvi::fem
