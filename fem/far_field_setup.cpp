// Building the far field: the layered mesh with its hole, DoFs numbered node-major, the
// matrix-free data, the lumped mass, the colouring of cell batches, the plastic layers' state and
// the element bound of the stable time step; and the graded steps the meshes are made of.
#include "fem/far_field_impl.hpp"

namespace hvi::fem {

std::vector<double> graded_steps(double a, double b, double fine_lower, double fine_upper,
                                 double fine, double ratio, double coarse, int keep) {
  if (!(a <= fine_lower && fine_lower <= fine_upper && fine_upper <= b) || !(fine > 0) ||
      !(ratio >= 1.0) || !(coarse >= fine))
    throw std::invalid_argument(
        "graded_steps: need a <= fine_lower <= fine_upper <= b, fine > 0, "
        "ratio >= 1, coarse >= fine");
  const double n_fine = (fine_upper - fine_lower) / fine;
  if (std::abs(n_fine - std::round(n_fine)) > 1e-9 * std::max(1.0, n_fine))
    throw std::invalid_argument(
        "graded_steps: the fine region is not a whole number of fine steps");
  // Steps from the fine region outwards over a length L.
  // Steps from the fine region outwards over a length L: grow until they pass L, then shrink the
  // ones beyond the kept steps (or the last step, if all are kept) so they end exactly at L and
  // none exceeds `coarse`.
  auto outward = [&](double L) {
    std::vector<double> s;
    if (L <= 1e-12 * fine) return s;
    double sum = 0.0, next = fine;
    while (sum < L * (1 - 1e-12)) {
      s.push_back(next);
      sum += next;
      if (static_cast<int>(s.size()) >= keep) next = std::min(next * ratio, coarse);
    }
    if (static_cast<int>(s.size()) > keep) {
      double kept = 0.0, tail = 0.0;
      for (std::size_t i = 0; i < s.size(); ++i) (static_cast<int>(i) < keep ? kept : tail) += s[i];
      const double scale = (L - kept) / tail;
      for (std::size_t i = keep; i < s.size(); ++i) s[i] *= scale;
    } else {
      s.back() -= sum - L;
    }
    return s;
  };
  std::vector<double> left = outward(fine_lower - a), right = outward(b - fine_upper);
  std::vector<double> steps(left.rbegin(), left.rend());
  for (long i = 0; i < std::lround(n_fine); ++i) steps.push_back(fine);
  steps.insert(steps.end(), right.begin(), right.end());
  return steps;
}

void FarField::Impl::build_mesh() {
  if (spec.degree != 1 && spec.degree != 2)
    throw std::invalid_argument("far field: element degree must be 1 or 2");
  if (spec.layers.empty() || spec.x_steps.empty() || spec.y_steps.empty())
    throw std::invalid_argument("far field: the mesh needs layers and in-plane steps");
  std::vector<double> z_steps;
  std::vector<types::material_id> z_layer;
  for (std::size_t l = 0; l < spec.layers.size(); ++l) {
    const Layer& L = spec.layers[l];
    if (!(L.z_upper > L.z_lower) || L.elements < 1 || !(L.density > 0))
      throw std::invalid_argument("far field: layer '" + L.name +
                                  "' has no thickness, elements or density");
    if (l > 0 && std::abs(L.z_lower - spec.layers[l - 1].z_upper) > 1e-12)
      throw std::invalid_argument("far field: layer '" + L.name +
                                  "' does not start where the one below ends");
    for (int e = 0; e < L.elements; ++e) {
      z_steps.push_back((L.z_upper - L.z_lower) / L.elements);
      z_layer.push_back(static_cast<types::material_id>(l));
    }
    layer_stiffness.push_back(stiffness(L.elasticity));
    const auto& C = layer_stiffness.back();
    auto near = [&](double a, double b) { return std::abs(a - b) <= 1e-9 * C[0]; };
    const bool isotropic = near(C[0], C[1]) && near(C[0], C[2]) && near(C[3], C[4]) &&
                           near(C[3], C[5]) && near(C[6], C[8]) && near(C[7], C[8]) &&
                           near(2.0 * C[8], C[0] - C[3]);
    if (L.plasticity && !isotropic)
      throw std::invalid_argument("far field: layer '" + L.name +
                                  "' is plastic but not isotropic (J2 needs an isotropic layer)");
    if (L.plasticity && L.core_yield)
      throw std::invalid_argument("far field: layer '" + L.name +
                                  "' names both J2 plasticity and core yield");
    if (L.strain_rate && !L.plasticity)
      throw std::invalid_argument("far field: layer '" + L.name +
                                  "' takes the strain rate but has no J2 plasticity");
    if (L.failure && !L.plasticity)
      throw std::invalid_argument(
          "far field: layer '" + L.name +
          "' names failure without J2 plasticity (its damage grows with eps_p)");
  }
  Table<dim, types::material_id> ids(spec.x_steps.size(), spec.y_steps.size(), z_steps.size());
  double x = spec.lower[0];
  std::size_t kept = 0;
  for (std::size_t i = 0; i < spec.x_steps.size(); ++i) {
    const double xc = x + 0.5 * spec.x_steps[i];
    double y = spec.lower[1];
    for (std::size_t j = 0; j < spec.y_steps.size(); ++j) {
      const double yc = y + 0.5 * spec.y_steps[j];
      const bool in_hole = spec.hole && centre_inside(xc, yc, *spec.hole);
      for (std::size_t k = 0; k < z_steps.size(); ++k) {
        ids[i][j][k] = in_hole ? numbers::invalid_material_id : z_layer[k];
        kept += !in_hole;
      }
      y += spec.y_steps[j];
    }
    x += spec.x_steps[i];
  }
  if (kept == 0) throw std::invalid_argument("far field: the hole removes every element");
  const std::array<const std::vector<double>*, dim> steps{&spec.x_steps, &spec.y_steps, &z_steps};
  const std::array<double, dim> origin{spec.lower[0], spec.lower[1], spec.layers.front().z_lower};
  for (int d = 0; d < dim; ++d) {
    lines[d] = {origin[d]};
    for (const double h : *steps[d]) lines[d].push_back(lines[d].back() + h);
  }
  GridGenerator::subdivided_hyper_rectangle(
      triangulation, {spec.x_steps, spec.y_steps, z_steps},
      Point<dim>(spec.lower[0], spec.lower[1], spec.layers.front().z_lower), ids);
}

// DoFs renumbered node-major: the three components of node a are DoFs 3a, 3a + 1, 3a + 2, nodes
// in the order the cells first reach them.
void FarField::Impl::number_nodes() {
  fe = std::make_unique<FESystem<dim>>(FE_Q<dim>(spec.degree), dim);
  dof_handler.reinit(triangulation);
  dof_handler.distribute_dofs(*fe);
  const auto n_dofs = dof_handler.n_dofs();
  std::vector<types::global_dof_index> new_number(n_dofs, numbers::invalid_dof_index);
  std::vector<types::global_dof_index> local(fe->n_dofs_per_cell());
  types::global_dof_index nodes = 0;
  for (const auto& cell : dof_handler.active_cell_iterators()) {
    cell->get_dof_indices(local);
    // Scalar support point k carries components 0..2; number the node at its x DoF.
    std::vector<types::global_dof_index> node_of_point(fe->base_element(0).n_dofs_per_cell(),
                                                       numbers::invalid_dof_index);
    for (unsigned i = 0; i < local.size(); ++i) {
      const auto [comp, k] = fe->system_to_component_index(i);
      if (comp != 0) continue;
      if (new_number[local[i]] == numbers::invalid_dof_index) new_number[local[i]] = 3 * nodes++;
      node_of_point[k] = new_number[local[i]] / 3;
    }
    for (unsigned i = 0; i < local.size(); ++i) {
      const auto [comp, k] = fe->system_to_component_index(i);
      if (comp != 0) new_number[local[i]] = 3 * node_of_point[k] + comp;
    }
  }
  dof_handler.renumber_dofs(new_number);

  std::vector<Point<dim>> points(n_dofs);
  DoFTools::map_dofs_to_support_points(mapping, dof_handler, points);
  positions.resize(n_dofs);
  for (types::global_dof_index a = 0; a < nodes; ++a)
    for (int d = 0; d < dim; ++d) positions[3 * a + d] = points[3 * a][d];
  layer.assign(nodes, static_cast<int>(spec.layers.size()));
  for (const auto& cell : dof_handler.active_cell_iterators()) {
    cell->get_dof_indices(local);
    for (const auto dof : local)
      layer[dof / 3] = std::min<int>(layer[dof / 3], cell->material_id());
  }
  fixed.assign(nodes, 0u);
}

void FarField::Impl::setup_matrix_free() {
  no_constraints.close();
  typename MatrixFree<dim, double>::AdditionalData data;
  data.tasks_parallel_scheme = MatrixFree<dim, double>::AdditionalData::none;
  data.mapping_update_flags = update_gradients | update_JxW_values | update_values;
  const std::vector<Quadrature<1>> quadratures{QGauss<1>(spec.degree + 1),
                                               QGaussLobatto<1>(spec.degree + 1)};
  matrix_free.reinit(mapping, std::vector<const DoFHandler<dim>*>{&dof_handler},
                     std::vector<const AffineConstraints<double>*>{&no_constraints}, quadratures,
                     data);
  batch_stiffness.resize(matrix_free.n_cell_batches());
  for (unsigned int cell = 0; cell < matrix_free.n_cell_batches(); ++cell) {
    auto& C = batch_stiffness[cell];
    for (auto& c : C) c = 0.0;
    for (unsigned int lane = 0; lane < matrix_free.n_active_entries_per_cell_batch(cell); ++lane) {
      const auto& L = layer_stiffness[matrix_free.get_cell_iterator(cell, lane)->material_id()];
      for (int k = 0; k < 9; ++k) C[k][lane] = L[k];
    }
  }
  const auto n = dof_handler.n_dofs();
  u.reinit(n);
  v.reinit(n);
  work_in.reinit(n);
  work_out.reinit(n);
  lane_removed.assign(static_cast<std::size_t>(W) * matrix_free.n_cell_batches(), 0);
  cell_removed.assign(triangulation.n_active_cells(), 0);
  index_cells();
  lump_mass();
  for (const double m : mass)
    if (!(m > 0.0)) throw std::logic_error("far field: a node has no positive lumped mass");
}

void FarField::Impl::index_cells() {
  const std::size_t nx = lines[0].size() - 1, ny = lines[1].size() - 1, nz = lines[2].size() - 1;
  brick_cell.assign(nx * ny * nz, -1);
  cell_iterator.resize(triangulation.n_active_cells());
  cell_lane.resize(triangulation.n_active_cells());
  for (unsigned cell = 0; cell < matrix_free.n_cell_batches(); ++cell)
    for (unsigned lane = 0; lane < matrix_free.n_active_entries_per_cell_batch(cell); ++lane) {
      const auto it = matrix_free.get_cell_iterator(cell, lane);
      const auto index = it->active_cell_index();
      const Point<dim> c = it->center();
      std::array<std::size_t, dim> b{};
      for (int d = 0; d < dim; ++d)
        b[d] = std::upper_bound(lines[d].begin(), lines[d].end(), c[d]) - lines[d].begin() - 1;
      brick_cell[(b[0] * ny + b[1]) * nz + b[2]] = static_cast<int>(index);
      cell_iterator[index] = it;
      cell_lane[index] = {cell, lane};
    }
}

void FarField::Impl::lump_mass() {
  Vector<double> m(dof_handler.n_dofs());
  if (spec.degree == 1)
    lumped_mass_kernel<1>(m);
  else
    lumped_mass_kernel<2>(m);
  mass.resize(m.size() / 3);
  for (std::size_t a = 0; a < mass.size(); ++a) mass[a] = m[3 * a];
}

// Greedy colouring: each batch takes the lowest colour none of its nodes has yet.
void FarField::Impl::colour_batches() {
  std::vector<std::uint64_t> used(mass.size(), 0);  // per node: the colours of batches touching it
  std::vector<types::global_dof_index> dofs(fe->n_dofs_per_cell());
  colours.clear();
  for (unsigned cell = 0; cell < matrix_free.n_cell_batches(); ++cell) {
    std::uint64_t taken = 0;
    std::vector<std::size_t> nodes;
    for (unsigned lane = 0; lane < matrix_free.n_active_entries_per_cell_batch(cell); ++lane) {
      matrix_free.get_cell_iterator(cell, lane)->get_dof_indices(dofs);
      for (const auto d : dofs)
        if (d % 3 == 0) nodes.push_back(d / 3);
    }
    for (const auto a : nodes) taken |= used[a];
    if (~taken == 0) throw std::logic_error("far field: more than 64 colours of cell batches");
    const int c = std::countr_one(taken);
    for (const auto a : nodes) used[a] |= std::uint64_t{1} << c;
    if (static_cast<int>(colours.size()) <= c) colours.resize(c + 1);
    colours[c].push_back(cell);
  }
  all_colours = colours;
  batch_sum.assign(matrix_free.n_cell_batches(), 0.0);
  if (spec.finite_strain) batch_stretch.assign(matrix_free.n_cell_batches(), 1.0);
}

void FarField::Impl::setup_plasticity() {
  const unsigned batches = matrix_free.n_cell_batches();
  lane_layer.assign(static_cast<std::size_t>(W) * batches, -1);
  plastic_slot.assign(batches, -1);
  n_q = static_cast<unsigned>(std::pow(spec.degree + 1, dim));
  int slots = 0;
  for (unsigned cell = 0; cell < batches; ++cell) {
    for (unsigned lane = 0; lane < matrix_free.n_active_entries_per_cell_batch(cell); ++lane)
      lane_layer[W * cell + lane] = matrix_free.get_cell_iterator(cell, lane)->material_id();
    for (unsigned lane = 0; lane < W; ++lane)
      if (lane_is_plastic(cell, lane)) {
        plastic_slot[cell] = slots++;
        break;
      }
  }
  state_size = 7;
  damage_slot = false;
  strain_slot = -1;
  for (const Layer& L : spec.layers)
    if ((L.core_yield && L.core_yield->failure) || L.failure) damage_slot = true;
  if (damage_slot) state_size = 8;
  for (const Layer& L : spec.layers)
    if (L.plasticity && L.strain_rate) strain_slot = state_size;
  if (strain_slot >= 0) state_size += 6;
  plastic.assign(static_cast<std::size_t>(slots) * n_q * W * state_size, 0.0);
  if (slots == 0) {  // nothing plastic: keep no per-batch tables either
    lane_layer = {};
    plastic_slot = {};
  }
}

// The largest eigenvalue of M_e^-1 K_e over the elements, each distinct (extent, layer) once.
double FarField::Impl::element_bound_time_step() const {
  const QGauss<dim> gauss(spec.degree + 1);
  const QGaussLobatto<dim> lobatto(spec.degree + 1);
  FEValues<dim> stiff(mapping, *fe, gauss, update_gradients | update_JxW_values);
  FEValues<dim> lump(mapping, *fe, lobatto, update_values | update_JxW_values);
  const unsigned nd = fe->n_dofs_per_cell();
  std::map<std::array<long long, 4>, double> seen;
  double lambda_max = 0.0;
  for (const auto& cell : dof_handler.active_cell_iterators()) {
    const Tensor<1, dim> extent = cell->vertex(7) - cell->vertex(0);
    const std::array<long long, 4> key{std::llround(extent[0] * 1e12),
                                       std::llround(extent[1] * 1e12),
                                       std::llround(extent[2] * 1e12), cell->material_id()};
    if (seen.count(key)) continue;
    const auto& C = layer_stiffness[cell->material_id()];
    const double rho = spec.layers[cell->material_id()].density;
    stiff.reinit(cell);
    lump.reinit(cell);
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(nd, nd);
    Eigen::VectorXd M = Eigen::VectorXd::Zero(nd);
    for (unsigned q = 0; q < gauss.size(); ++q) {
      std::vector<Tensor<2, dim>> grad(nd), stress(nd);
      for (unsigned i = 0; i < nd; ++i) {
        const unsigned ci = fe->system_to_component_index(i).first;
        grad[i] = 0;
        grad[i][ci] = stiff.shape_grad_component(i, q, ci);
        stress[i] = orthotropic_stress(C, grad[i]);
      }
      for (unsigned i = 0; i < nd; ++i)
        for (unsigned j = 0; j < nd; ++j)
          K(i, j) += scalar_product(stress[i], grad[j]) * stiff.JxW(q);
    }
    for (unsigned q = 0; q < lobatto.size(); ++q)
      for (unsigned i = 0; i < nd; ++i)
        M(i) += rho * lump.shape_value_component(i, q, fe->system_to_component_index(i).first) *
                lump.JxW(q);
    const Eigen::VectorXd s = M.cwiseSqrt().cwiseInverse();
    const Eigen::MatrixXd A = s.asDiagonal() * K * s.asDiagonal();
    const double lambda = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A, Eigen::EigenvaluesOnly)
                              .eigenvalues()
                              .maxCoeff();
    seen[key] = lambda;
    lambda_max = std::max(lambda_max, lambda);
  }
  return 2.0 / std::sqrt(lambda_max);
}

}  // namespace hvi::fem
