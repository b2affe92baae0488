#pragma once
// The far field's state behind FarField (far_field.hpp): the deal.II mesh, DoF handler and
// matrix-free data, the lumped mass, the plastic layers' state, and the element kernels. Internal
// to fem/: far_field.cpp (the public interface and output) and far_field_setup.cpp (building it).
#include "fem/far_field.hpp"

#include "fem/j2_plasticity.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <map>
#include <optional>
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

namespace detail {

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
inline constexpr int voigt[6][2] = {{0, 0}, {1, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}};

// Whether a cell centred at (x, y) lies inside the in-plane box (x0, y0, x1, y1): the mesh's hole
// and remove_cells take out the same cells.
inline bool centre_inside(double x, double y, const std::array<double, 4>& box) {
  return x > box[0] && x < box[2] && y > box[1] && y < box[3];
}

}  // namespace detail

using namespace detail;

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
    return &plastic[((static_cast<std::size_t>(plastic_slot[cell]) * n_q + q) * W + lane) *
                    state_size];
  }
  const double* state(unsigned cell, unsigned q, unsigned lane) const {
    return &plastic[((static_cast<std::size_t>(plastic_slot[cell]) * n_q + q) * W + lane) *
                    state_size];
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
  void return_to_yield(unsigned cell, unsigned q, VA jxw, const Tensor<2, dim, VA>& E,
                       Tensor<2, dim, VA>& sigma) {
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
        const CoreYieldUpdate r =
            core_yield_return(trial, old, st[6], failing ? st[7] : 0.0, Cl, *L.core_yield);
        stress = r.stress, plastic_strain = r.plastic_strain, accumulated = r.accumulated,
        work = r.plastic_work;
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
        const J2Update r = L.failure
                               ? j2_return(trial, old, mu, (C[0][lane] + 2.0 * C[3][lane]) / 3.0,
                                           *L.plasticity, *L.failure, rate)
                               : j2_return(trial, old, mu, *L.plasticity, rate);
        stress = r.stress, plastic_strain = r.state.plastic_strain, accumulated = r.state.alpha,
        work = r.plastic_work;
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
    if (ranks) merge(nullptr, batch_sum.data(), nullptr);
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
    if (ranks)
      merge(&dst, any_plastic() ? batch_sum.data() : nullptr,
            spec.finite_strain ? batch_stretch.data() : nullptr);
    if (any_plastic()) plastic_work += batch_total();
  }

  // The cell batches in colours: no two batches of a colour share a node, so within a colour
  // they scatter into disjoint entries and run in parallel (OpenMP), while the colours run in
  // order. Every entry then receives its contributions in the same order for any thread count:
  // the far field is bitwise the same on 1 or N threads. A batch whose cells remove_cells has
  // all taken out adds nothing (no stiffness, no plastic state) and leaves its colour. Spread,
  // `colours` keeps the batches this rank evaluates, `all_colours` every rank's.
  std::vector<std::vector<unsigned>> colours, all_colours;

  // Spread over ranks (FarField::spread): per node its owner, per batch the rank reporting its
  // shares of sums (the lowest owner of its nodes, which evaluates it).
  std::optional<FarFieldRanks> ranks;
  std::vector<int> node_owner, batch_reporter;

  // Every rank gives what it holds current and takes the others': the force (3 per node) in
  // `nodal` from the nodes' owners, and per batch `sums` and `stretch` from its reporter; a null
  // pointer is not exchanged.
  void merge(Vector<double>* nodal, double* sums, double* stretch) const {
    const int me = ranks->rank;
    std::vector<double> mine;
    if (nodal)
      for (std::size_t a = 0; a < node_owner.size(); ++a)
        if (node_owner[a] == me)
          mine.insert(mine.end(), nodal->begin() + 3 * a, nodal->begin() + 3 * a + 3);
    for (double* per_batch : {sums, stretch})
      if (per_batch)
        for (std::size_t b = 0; b < batch_reporter.size(); ++b)
          if (batch_reporter[b] == me) mine.push_back(per_batch[b]);
    const auto all = ranks->all_gather(mine);
    std::vector<std::size_t> at(all.size(), 0);
    if (nodal)
      for (std::size_t a = 0; a < node_owner.size(); ++a) {
        const auto r = static_cast<std::size_t>(node_owner[a]);
        std::copy_n(&all[r][at[r]], 3, nodal->begin() + 3 * a);
        at[r] += 3;
      }
    for (double* per_batch : {sums, stretch})
      if (per_batch)
        for (std::size_t b = 0; b < batch_reporter.size(); ++b) {
          const auto r = static_cast<std::size_t>(batch_reporter[b]);
          per_batch[b] = all[r][at[r]++];
        }
  }
  void partition();

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
    if (ranks) merge(&dst, nullptr, nullptr);
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

}  // namespace hvi::fem
