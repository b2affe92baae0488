// The far field with deal.II: mesh, DoFs numbered node-major, matrix-free stiffness (and J2 or
// capped core stresses in plastic layers), lumped mass, the element bound of the stable time step, and VTU
// output.
#include "fem/far_field.hpp"

#include "fem/j2_plasticity.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <stdexcept>

#include <omp.h>

#include <deal.II/base/multithread_info.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/table.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/vector.h>
#include <deal.II/matrix_free/fe_evaluation.h>
#include <deal.II/matrix_free/matrix_free.h>
#include <deal.II/numerics/data_out.h>
#include <Eigen/Dense>

namespace hvi::fem {

namespace {

using namespace dealii;
constexpr int dim = 3;
using VA = VectorizedArray<double>;

// sigma = C eps in Voigt order (xx, yy, zz, yz, xz, xy; engineering shear strains), for any number
// type (double for the element matrices, VectorizedArray for the matrix-free kernel). C holds the
// nine entries of an orthotropic stiffness (orthotropic.hpp).
template <typename N>
Tensor<2, dim, N> orthotropic_stress(const std::array<N, 9>& C, const Tensor<2, dim, N>& grad_u) {
  const N exx = grad_u[0][0], eyy = grad_u[1][1], ezz = grad_u[2][2];
  const N gyz = grad_u[1][2] + grad_u[2][1], gxz = grad_u[0][2] + grad_u[2][0],
          gxy = grad_u[0][1] + grad_u[1][0];
  Tensor<2, dim, N> s;
  s[0][0] = C[0] * exx + C[3] * eyy + C[4] * ezz;
  s[1][1] = C[3] * exx + C[1] * eyy + C[5] * ezz;
  s[2][2] = C[4] * exx + C[5] * eyy + C[2] * ezz;
  s[1][2] = s[2][1] = C[6] * gyz;
  s[0][2] = s[2][0] = C[7] * gxz;
  s[0][1] = s[1][0] = C[8] * gxy;
  return s;
}

// Voigt slot k of a symmetric tensor: its (row, column).
constexpr int voigt[6][2] = {{0, 0}, {1, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}};

// Whether a cell centred at (x, y) lies inside the in-plane box (x0, y0, x1, y1): the mesh's hole
// and remove_cells take out the same cells.
bool centre_inside(double x, double y, const std::array<double, 4>& box) {
  return x > box[0] && x < box[2] && y > box[1] && y < box[3];
}

}  // namespace

std::vector<double> graded_steps(double a, double b, double fine_lower, double fine_upper,
                                 double fine, double ratio, double coarse, int keep) {
  if (!(a <= fine_lower && fine_lower <= fine_upper && fine_upper <= b) || !(fine > 0) ||
      !(ratio >= 1.0) || !(coarse >= fine))
    throw std::invalid_argument("graded_steps: need a <= fine_lower <= fine_upper <= b, fine > 0, "
                                "ratio >= 1, coarse >= fine");
  const double n_fine = (fine_upper - fine_lower) / fine;
  if (std::abs(n_fine - std::round(n_fine)) > 1e-9 * std::max(1.0, n_fine))
    throw std::invalid_argument("graded_steps: the fine region is not a whole number of fine steps");
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

struct FarField::Impl {
  LayeredMesh spec;
  Triangulation<dim> triangulation;
  std::unique_ptr<FESystem<dim>> fe;
  DoFHandler<dim> dof_handler;
  MappingQ1<dim> mapping;
  AffineConstraints<double> no_constraints;
  MatrixFree<dim, double> matrix_free;
  std::vector<std::array<double, 9>> layer_stiffness;
  std::vector<std::array<VA, 9>> batch_stiffness;  // per cell batch, lane by lane

  std::vector<double> positions;  // 3 per node
  std::vector<double> mass;       // per node
  std::vector<int> layer;         // per node
  std::vector<unsigned> fixed;    // per node
  mutable Vector<double> u, v, work_in, work_out;
  double dt_stable = 0.0;

  // Plasticity, kept only when a layer names it. lane_layer[W cell + lane] is the layer of each
  // lane of each cell batch (-1: an empty lane); a batch with a plastic lane has a slot in
  // `plastic` of n_q * W * state_size values: per quadrature point and lane eps_p (Voigt) and
  // alpha, with a failing core or facesheets an eighth, their damage D (0 in the other lanes), and
  // with a rate-dependent layer six more from `strain_slot` on, the strain E (Voigt) of the last
  // force evaluation, whose change over `rate_dt` is the point's strain rate.
  static constexpr unsigned W = VA::size();
  int state_size = 7;
  bool damage_slot = false;
  int strain_slot = -1;
  double rate_dt = 0.0;
  std::vector<int> lane_layer, plastic_slot;
  std::vector<double> plastic;
  mutable std::vector<double> batch_sum;  // per cell batch: its share of a sum, added in order
  // Finite strain only: per cell batch, the largest bound s >= |F|_2^2 at the last force
  // evaluation (Gershgorin's on F^T F).
  std::vector<double> batch_stretch;
  double plastic_work = 0.0;
  unsigned n_q = 0;
  // Cells taken out by remove_cells: per lane of each batch (W per batch), and per active cell.
  std::vector<std::uint8_t> lane_removed, cell_removed;
  std::size_t removed_cells = 0;
  // For sample(): the mesh lines along x, y, z; per brick (i, j, k), i slowest, its active cell
  // index (-1 in the hole); per active cell its iterator and (batch, lane).
  std::array<std::vector<double>, dim> lines;
  std::vector<int> brick_cell;
  std::vector<DoFHandler<dim>::active_cell_iterator> cell_iterator;
  std::vector<std::pair<unsigned, unsigned>> cell_lane;

  bool any_plastic() const { return !plastic.empty(); }
  bool lane_is_plastic(unsigned cell, unsigned lane) const {
    const int l = lane_layer[W * cell + lane];
    return l >= 0 && (spec.layers[l].plasticity || spec.layers[l].core_yield);
  }
  const Layer* lane_layer_spec(unsigned cell, unsigned lane) const {
    const int l = lane_layer[W * cell + lane];
    return l >= 0 ? &spec.layers[l] : nullptr;
  }
  double* state(unsigned cell, unsigned q, unsigned lane) {
    return &plastic[((static_cast<std::size_t>(plastic_slot[cell]) * n_q + q) * W + lane) * state_size];
  }
  const double* state(unsigned cell, unsigned q, unsigned lane) const {
    return &plastic[((static_cast<std::size_t>(plastic_slot[cell]) * n_q + q) * W + lane) * state_size];
  }

  // The strain of the displacement gradient H: (H + H^T)/2, plus H^T H / 2 (Green-Lagrange) with
  // finite strain.
  Tensor<2, dim, VA> total_strain(const Tensor<2, dim, VA>& H) const {
    Tensor<2, dim, VA> e;
    for (int i = 0; i < dim; ++i)
      for (int j = 0; j < dim; ++j) {
        e[i][j] = 0.5 * (H[i][j] + H[j][i]);
        if (spec.finite_strain)
          for (int k = 0; k < dim; ++k) e[i][j] += 0.5 * H[k][i] * H[k][j];
      }
    return e;
  }

  // The total strain less the committed plastic strain in plastic lanes.
  Tensor<2, dim, VA> elastic_strain(unsigned cell, unsigned q, Tensor<2, dim, VA> e) const {
    if (!any_plastic() || plastic_slot[cell] < 0) return e;
    for (unsigned lane = 0; lane < W; ++lane) {
      if (!lane_is_plastic(cell, lane)) continue;
      const double* ep = state(cell, q, lane);
      for (int k = 0; k < 6; ++k) {
        const auto [i, j] = voigt[k];
        e[i][j][lane] -= ep[k];
        if (i != j) e[j][i][lane] -= ep[k];
      }
    }
    return e;
  }

  // The stress C : (E - E_p) of a plastic batch's lanes returned to the yield surface, their state
  // and plastic work (into batch_sum) committed.
  void return_to_yield(unsigned cell, unsigned q, VA jxw, const Tensor<2, dim, VA>& E, Tensor<2, dim, VA>& sigma) {
    const auto& C = batch_stiffness[cell];
    for (unsigned lane = 0; lane < W; ++lane) {
      if (!lane_is_plastic(cell, lane)) continue;
      double* st = state(cell, q, lane);
      const Sym trial{sigma[0][0][lane], sigma[1][1][lane], sigma[2][2][lane],
                      sigma[1][2][lane], sigma[0][2][lane], sigma[0][1][lane]};
      const Layer& L = *lane_layer_spec(cell, lane);
      Sym stress, plastic_strain;
      double accumulated, work;
      if (L.core_yield) {
        std::array<double, 9> Cl;
        for (int k = 0; k < 9; ++k) Cl[k] = C[k][lane];
        Sym old;
        std::copy(st, st + 6, old.begin());
        const bool failing = L.core_yield->failure.has_value();
        const CoreYieldUpdate r = core_yield_return(trial, old, st[6], failing ? st[7] : 0.0, Cl, *L.core_yield);
        stress = r.stress, plastic_strain = r.plastic_strain, accumulated = r.accumulated, work = r.plastic_work;
        if (failing) st[7] = r.damage;
      } else {
        J2State old;
        std::copy(st, st + 6, old.plastic_strain.begin());
        old.alpha = st[6];
        // C[8] = C66 = mu of the isotropic layer, (C11 + 2 C12) / 3 its bulk modulus K.
        const double mu = C[8][lane];
        if (L.failure) old.damage = st[7];
        StrainRate rate;
        if (L.strain_rate) {
          double* last = st + strain_slot;
          Sym de;
          for (int k = 0; k < 6; ++k) {
            const double e = E[voigt[k][0]][voigt[k][1]][lane];
            de[k] = e - last[k];
            last[k] = e;
          }
          if (rate_dt > 0.0) rate = {equivalent_strain_rate(de, rate_dt), rate_dt};
        }
        const J2Update r = L.failure ? j2_return(trial, old, mu, (C[0][lane] + 2.0 * C[3][lane]) / 3.0,
                                                 *L.plasticity, *L.failure, rate)
                                     : j2_return(trial, old, mu, *L.plasticity, rate);
        stress = r.stress, plastic_strain = r.state.plastic_strain, accumulated = r.state.alpha, work = r.plastic_work;
        if (L.failure) st[7] = r.state.damage;
      }
      sigma[0][0][lane] = stress[0];
      sigma[1][1][lane] = stress[1];
      sigma[2][2][lane] = stress[2];
      sigma[1][2][lane] = sigma[2][1][lane] = stress[3];
      sigma[0][2][lane] = sigma[2][0][lane] = stress[4];
      sigma[0][1][lane] = sigma[1][0][lane] = stress[5];
      std::copy(plastic_strain.begin(), plastic_strain.end(), st);
      st[6] = accumulated;
      batch_sum[cell] += work * jxw[lane];
    }
  }

  // -dst = the internal force when it is not K u: with finite strain the first Piola-Kirchhoff
  // stress P = (I + H) S is integrated against grad N, and the stretch bound of the stable step
  // kept per batch; in plastic lanes S is returned to the yield surface first.
  template <int p>
  void nonlinear_force_kernel(const Vector<double>& src, Vector<double>& dst) {
    dst = 0.0;
    std::fill(batch_sum.begin(), batch_sum.end(), 0.0);
    gradient_loop<p>(src, [&](FEEvaluation<dim, p, p + 1, dim, double>& phi, unsigned cell) {
      const auto& C = batch_stiffness[cell];
      const bool plastic_batch = any_plastic() && plastic_slot[cell] >= 0;
      VA s_max = 1.0;
      for (unsigned int q = 0; q < phi.n_q_points; ++q) {
        const Tensor<2, dim, VA> H = phi.get_gradient(q), E = total_strain(H);
        Tensor<2, dim, VA> S = orthotropic_stress(C, elastic_strain(cell, q, E));
        if (plastic_batch) return_to_yield(cell, q, phi.JxW(q), E, S);
        if (!spec.finite_strain) {
          phi.submit_gradient(S, q);
          continue;
        }
        Tensor<2, dim, VA> P, F = H;
        for (int i = 0; i < dim; ++i) F[i][i] += 1.0;
        for (int i = 0; i < dim; ++i)
          for (int j = 0; j < dim; ++j)
            for (int k = 0; k < dim; ++k) P[i][j] += F[i][k] * S[k][j];
        // |F|_2^2 = the largest eigenvalue of F^T F = I + 2E, bounded by Gershgorin's row sums
        // (exact for a rotation, E = 0).
        for (int i = 0; i < dim; ++i) {
          VA row = 1.0 + 2.0 * E[i][i];
          for (int j = 0; j < dim; ++j)
            if (j != i) row += 2.0 * std::abs(E[i][j]);
          s_max = std::max(s_max, row);
        }
        phi.submit_gradient(P, q);
      }
      phi.integrate_scatter(EvaluationFlags::gradients, dst);
      if (spec.finite_strain) {
        double s = 1.0;
        for (unsigned lane = 0; lane < matrix_free.n_active_entries_per_cell_batch(cell); ++lane)
          if (!lane_removed[W * cell + lane]) s = std::max(s, s_max[lane]);
        batch_stretch[cell] = s;
      }
    });
    if (any_plastic()) plastic_work += batch_total();
  }

  // 1/2 int (E - E_p) : C (E - E_p) dV with the committed plastic strain.
  template <int p>
  double elastic_energy_kernel(const Vector<double>& src) const {
    std::fill(batch_sum.begin(), batch_sum.end(), 0.0);
    gradient_loop<p>(src, [&](FEEvaluation<dim, p, p + 1, dim, double>& phi, unsigned cell) {
      const auto& C = batch_stiffness[cell];
      for (unsigned int q = 0; q < phi.n_q_points; ++q) {
        const Tensor<2, dim, VA> e = elastic_strain(cell, q, total_strain(phi.get_gradient(q)));
        const VA w = 0.5 * scalar_product(orthotropic_stress(C, e), e) * phi.JxW(q);
        for (unsigned lane = 0; lane < matrix_free.n_active_entries_per_cell_batch(cell); ++lane)
          batch_sum[cell] += w[lane];
      }
    });
    return batch_total();
  }

  // Whether the force is other than K u.
  bool nonlinear() const { return spec.finite_strain || any_plastic(); }

  // The internal force's negative, K u when elastic with small strain.
  void internal(const Vector<double>& src, Vector<double>& dst) {
    if (!nonlinear()) return apply(src, dst);
    if (spec.degree == 1)
      nonlinear_force_kernel<1>(src, dst);
    else
      nonlinear_force_kernel<2>(src, dst);
  }

  // The cell batches in colours: no two batches of a colour share a node, so within a colour
  // they scatter into disjoint entries and run in parallel (OpenMP), while the colours run in
  // order. Every entry then receives its contributions in the same order for any thread count:
  // the far field is bitwise the same on 1 or N threads. A batch whose cells remove_cells has
  // all taken out adds nothing (no stiffness, no plastic state) and leaves its colour.
  std::vector<std::vector<unsigned>> colours;

  // body(phi, batch) for every cell batch, colour by colour, with one FEEvaluation per thread.
  template <int p, typename Body>
  void cell_loop(Body&& body) const {
    if (omp_get_max_threads() == 1 || omp_in_parallel()) {  // the same order, on this thread
      FEEvaluation<dim, p, p + 1, dim, double> phi(matrix_free, 0, 0);
      for (const auto& colour : colours)
        for (const unsigned cell : colour) body(phi, cell);
      return;
    }
#pragma omp parallel
    {
      FEEvaluation<dim, p, p + 1, dim, double> phi(matrix_free, 0, 0);
      for (const auto& colour : colours) {
#pragma omp for schedule(static)
        for (std::size_t i = 0; i < colour.size(); ++i) body(phi, colour[i]);
      }
    }
  }

  // body(phi, cell) with phi holding the gradients of src on the batch, for every cell batch.
  template <int p, typename Body>
  void gradient_loop(const Vector<double>& src, Body&& body) const {
    cell_loop<p>([&](FEEvaluation<dim, p, p + 1, dim, double>& phi, unsigned cell) {
      phi.reinit(cell);
      phi.gather_evaluate(src, EvaluationFlags::gradients);
      body(phi, cell);
    });
  }

  // The per-batch shares of a sum, added in batch order: the same for any thread count.
  double batch_total() const {
    double total = 0.0;
    for (const double x : batch_sum) total += x;
    return total;
  }

  template <int p>
  void stiffness_kernel(const Vector<double>& src, Vector<double>& dst) const {
    dst = 0.0;
    gradient_loop<p>(src, [&](FEEvaluation<dim, p, p + 1, dim, double>& phi, unsigned cell) {
      const auto& C = batch_stiffness[cell];
      for (unsigned int q = 0; q < phi.n_q_points; ++q)
        phi.submit_gradient(orthotropic_stress(C, phi.get_gradient(q)), q);
      phi.integrate_scatter(EvaluationFlags::gradients, dst);
    });
  }

  // M_a = sum_q rho N_a(x_q) JxW_q with Gauss-Lobatto points (quadrature 1): the row sums of the
  // nodal-quadrature mass, which is diagonal.
  template <int p>
  void lumped_mass_kernel(Vector<double>& dst) const {
    FEEvaluation<dim, p, p + 1, dim, double> phi(matrix_free, 0, 1);
    dst = 0.0;
    for (unsigned int cell = 0; cell < matrix_free.n_cell_batches(); ++cell) {
      phi.reinit(cell);
      VA rho = 0.0;
      for (unsigned int lane = 0; lane < matrix_free.n_active_entries_per_cell_batch(cell); ++lane)
        if (!lane_removed[W * cell + lane])
          rho[lane] = spec.layers[matrix_free.get_cell_iterator(cell, lane)->material_id()].density;
      Tensor<1, dim, VA> value;
      for (int d = 0; d < dim; ++d) value[d] = rho;
      for (unsigned int q = 0; q < phi.n_q_points; ++q) phi.submit_value(value, q);
      phi.integrate_scatter(EvaluationFlags::values, dst);
    }
  }

  void apply(const Vector<double>& src, Vector<double>& dst) const {
    if (spec.degree == 1)
      stiffness_kernel<1>(src, dst);
    else
      stiffness_kernel<2>(src, dst);
  }

  void build_mesh();
  void number_nodes();
  void setup_matrix_free();
  void setup_plasticity();
  void colour_batches();
  void lump_mass();
  void index_cells();
  double element_bound_time_step() const;
};

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
      throw std::invalid_argument("far field: layer '" + L.name + "' has no thickness, elements or density");
    if (l > 0 && std::abs(L.z_lower - spec.layers[l - 1].z_upper) > 1e-12)
      throw std::invalid_argument("far field: layer '" + L.name + "' does not start where the one below ends");
    for (int e = 0; e < L.elements; ++e) {
      z_steps.push_back((L.z_upper - L.z_lower) / L.elements);
      z_layer.push_back(static_cast<types::material_id>(l));
    }
    layer_stiffness.push_back(stiffness(L.elasticity));
    const auto& C = layer_stiffness.back();
    auto near = [&](double a, double b) { return std::abs(a - b) <= 1e-9 * C[0]; };
    const bool isotropic = near(C[0], C[1]) && near(C[0], C[2]) && near(C[3], C[4]) && near(C[3], C[5]) &&
                           near(C[6], C[8]) && near(C[7], C[8]) && near(2.0 * C[8], C[0] - C[3]);
    if (L.plasticity && !isotropic)
      throw std::invalid_argument("far field: layer '" + L.name + "' is plastic but not isotropic (J2 needs an isotropic layer)");
    if (L.plasticity && L.core_yield)
      throw std::invalid_argument("far field: layer '" + L.name + "' names both J2 plasticity and core yield");
    if (L.strain_rate && !L.plasticity)
      throw std::invalid_argument("far field: layer '" + L.name + "' takes the strain rate but has no J2 plasticity");
    if (L.failure && !L.plasticity)
      throw std::invalid_argument("far field: layer '" + L.name + "' names failure without J2 plasticity (its damage grows with eps_p)");
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
    const std::array<long long, 4> key{std::llround(extent[0] * 1e12), std::llround(extent[1] * 1e12),
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
    const double lambda =
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff();
    seen[key] = lambda;
    lambda_max = std::max(lambda_max, lambda);
  }
  return 2.0 / std::sqrt(lambda_max);
}

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

std::size_t FarField::node_count() const { return impl_->mass.size(); }
std::size_t FarField::cell_count() const { return impl_->triangulation.n_active_cells(); }
int FarField::degree() const { return impl_->spec.degree; }
std::span<const double> FarField::reference_positions() const { return impl_->positions; }
std::span<const double> FarField::lumped_mass() const { return impl_->mass; }
std::span<const int> FarField::node_layer() const { return impl_->layer; }
std::span<double> FarField::displacement() { return {impl_->u.begin(), impl_->u.size()}; }
std::span<const double> FarField::displacement() const { return {impl_->u.begin(), impl_->u.size()}; }
std::span<double> FarField::velocity() { return {impl_->v.begin(), impl_->v.size()}; }
std::span<const double> FarField::velocity() const { return {impl_->v.begin(), impl_->v.size()}; }

void FarField::fix(std::size_t node, unsigned components) {
  impl_->fixed.at(node) |= components & 7u;
  for (int d = 0; d < 3; ++d)
    if (components & (1u << d)) impl_->u[3 * node + d] = impl_->v[3 * node + d] = 0.0;
}
unsigned FarField::fixed(std::size_t node) const { return impl_->fixed.at(node); }

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
    e += 0.5 * impl_->mass[a] * (v[3 * a] * v[3 * a] + v[3 * a + 1] * v[3 * a + 1] + v[3 * a + 2] * v[3 * a + 2]);
  return e;
}
double FarField::kinetic_energy() const { return kinetic_energy(velocity()); }

double FarField::strain_energy() const {
  const auto& I = *impl_;
  if (I.nonlinear()) return I.spec.degree == 1 ? I.elastic_energy_kernel<1>(I.u) : I.elastic_energy_kernel<2>(I.u);
  I.apply(I.u, I.work_out);
  return 0.5 * (I.u * I.work_out);
}

double FarField::plastic_work() const { return impl_->plastic_work; }

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
      for (int d = 0; d < dim; ++d) H[c][d] += g[d] / (I.lines[d][b[d] + 1] - I.lines[d][b[d]]) * I.u[dofs[i]];
    }
    for (int k = 0; k < 6; ++k) r.strain[k] = 0.5 * (H[voigt[k][0]][voigt[k][1]] + H[voigt[k][1]][voigt[k][0]]);
    Tensor<2, dim> eps;
    for (int k = 0; k < 6; ++k) eps[voigt[k][0]][voigt[k][1]] = eps[voigt[k][1]][voigt[k][0]] = r.strain[k];
    const auto [batch, lane] = I.cell_lane[index];
    if (I.any_plastic() && I.lane_is_plastic(batch, lane)) {
      // The nearest Gauss point: per axis the nearest of the n1 points, x running fastest.
      unsigned q = 0;
      for (int d = dim - 1; d >= 0; --d) {
        unsigned best = 0;
        for (unsigned k = 1; k < n1; ++k)
          if (std::abs(gauss.point(k)[0] - unit[d]) < std::abs(gauss.point(best)[0] - unit[d])) best = k;
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
  for (auto& colour : I.colours)
    std::erase_if(colour, [&](unsigned cell) {
      for (unsigned lane = 0; lane < I.matrix_free.n_active_entries_per_cell_batch(cell); ++lane)
        if (!I.lane_removed[Impl::W * cell + lane]) return false;
      if (!I.batch_stretch.empty()) I.batch_stretch[cell] = 1.0;  // what its kept cells would give: none
      return true;
    });
  I.lump_mass();
  for (std::size_t a = 0; a < I.mass.size(); ++a)
    if (I.mass[a] == 0.0)
      for (int d = 0; d < dim; ++d) I.v[3 * a + d] = 0.0;
  return newly;
}

std::size_t FarField::removed_cell_count() const { return impl_->removed_cells; }
std::size_t FarField::evaluated_batch_count() const {
  std::size_t n = 0;
  for (const auto& colour : impl_->colours) n += colour.size();
  return n;
}
bool FarField::plastic() const { return impl_->any_plastic(); }
bool FarField::finite_strain() const { return impl_->spec.finite_strain; }

namespace {
// The largest accumulated plastic strain (state slot 6) over the quadrature points of the plastic
// lanes whose layer `core` is or is not a yielding core.
template <class Impl>
double max_accumulated(const Impl& I, bool core) {
  double m = 0.0;
  if (!I.any_plastic()) return m;
  for (unsigned cell = 0; cell < I.matrix_free.n_cell_batches(); ++cell)
    for (unsigned lane = 0; lane < Impl::W; ++lane) {
      if (!I.lane_is_plastic(cell, lane) || I.lane_layer_spec(cell, lane)->core_yield.has_value() != core) continue;
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
      if (!I.lane_is_plastic(cell, lane) || I.lane_layer_spec(cell, lane)->core_yield.has_value() != core) continue;
      unsigned failed = 0;
      for (unsigned q = 0; q < I.n_q; ++q) failed += I.state(cell, q, lane)[7] >= 1.0;
      v += I.matrix_free.get_cell_iterator(cell, lane)->measure() * failed / I.n_q;
    }
  return v;
}
}  // namespace

double FarField::max_equivalent_plastic_strain() const { return max_accumulated(*impl_, false); }
double FarField::max_core_plastic_strain() const { return max_accumulated(*impl_, true); }
std::vector<double> FarField::damaged_cell_centres(double damage) const {
  const auto& I = *impl_;
  std::vector<double> centres;
  if (!I.damage_slot) return centres;  // no failing layer: no damage slot
  for (unsigned cell = 0; cell < I.matrix_free.n_cell_batches(); ++cell)
    for (unsigned lane = 0; lane < I.matrix_free.n_active_entries_per_cell_batch(cell); ++lane) {
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

double FarField::core_failed_volume() const { return failed_volume(*impl_, true); }
double FarField::facesheet_failed_volume() const { return failed_volume(*impl_, false); }

std::vector<std::pair<std::string, std::span<double>>> FarField::plastic_state() {
  if (!impl_->any_plastic()) return {};
  return {{"far_field_plastic_state", impl_->plastic}, {"far_field_plastic_work", {&impl_->plastic_work, 1}}};
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
         I.matrix_free.memory_consumption() +
         4 * I.u.memory_consumption() + I.positions.size() * sizeof(double) +
         I.mass.size() * (sizeof(double) + sizeof(int) + sizeof(unsigned)) +
         I.batch_stiffness.size() * sizeof(std::array<VA, 9>) +
         (I.plastic.size() + I.batch_stretch.size()) * sizeof(double) +
         (I.lane_layer.size() + I.plastic_slot.size()) * sizeof(int) +
         I.lane_removed.size() + I.cell_removed.size();
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
  out.add_data_vector(I.u, std::vector<std::string>(dim, "displacement"), DataOut<dim>::type_dof_data, vector);
  out.add_data_vector(I.v, std::vector<std::string>(dim, "velocity"), DataOut<dim>::type_dof_data, vector);
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

void FarField::write_pvd(const std::string& path, const std::vector<std::pair<double, std::string>>& entries) {
  // Written here rather than by DataOutBase::write_pvd_record, which stamps the date and time
  // into the file: the same run must give the same bytes.
  std::ofstream file(path);
  if (!file) throw std::runtime_error("cannot write " + path);
  file << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" ByteOrder=\"LittleEndian\">\n"
          "  <Collection>\n";
  char time[32];
  for (const auto& [t, name] : entries) {
    std::snprintf(time, sizeof time, "%.17g", t);
    file << "    <DataSet timestep=\"" << time << "\" group=\"\" part=\"0\" file=\"" << name << "\"/>\n";
  }
  file << "  </Collection>\n</VTKFile>\n";
}

}  // namespace hvi::fem
