#pragma once
// The finite-element far field of a panel: a layered mesh of hexahedra (each facesheet one or
// two elements through its thickness, the core a homogenised orthotropic solid), total
// Lagrangian (every quantity refers to the undeformed mesh), optionally J2 plasticity in the
// isotropic layers (fem/j2_plasticity.hpp), torn where their damage reaches 1 in failing ones, and
// capped out-of-plane stresses in a yielding core, dropped where its walls tear in a failing one
// (fem/core_yield.hpp), explicit central differences with a lumped mass, and matrix-free forces
// (deal.II MatrixFree / FEEvaluation). deal.II stays behind this header: callers see nodes as plain
// arrays.
//
// Kinematics, with H = grad_X u the displacement gradient on the undeformed mesh:
//   small strain   eps = (H + H^T)/2,            sigma = C : eps,   f_a = -int sigma . grad N_a dV
//   finite strain  E = (H + H^T + H^T H)/2,      S = C : E,         f_a = -int (I + H) S . grad N_a
//   dV
// The second is the orthotropic Saint Venant-Kirchhoff solid: S the second Piola-Kirchhoff stress,
// P = F S the first, so a rigid rotation of any size gives no force and no energy, and the strain
// energy 1/2 int E : C : E dV is exact (hyperelastic). With J2 it is the additive split
// E = E_e + E_p in the reference configuration, S = C : (E - E_p) returned to the yield surface:
// small elastic strains under rotations of any size, as in a panel's torn, bent edge.
//
// Elements are Lagrange Q2 by default: a thin facesheet one element thick bends without the
// shear locking of trilinear Q1 bricks (tests/fem shows both). The mass is lumped by
// Gauss-Lobatto quadrature on the element's own nodes, M_a = sum_q rho N_a(x_q) JxW_q, which for
// nodal points is diagonal and positive for Q1 and Q2.
//
// Nodes are numbered 0..n-1 and every nodal array holds 3 values per node (x, y, z), node-major.
//
// Spread over ranks (spread()), every rank holds the whole mesh and every node's displacement,
// velocity and mass, and steps them alike; the element work is split. Each node has one owner: the
// cell batches are cut into slabs along x of equal estimated cost (a plastic lane counts
// `plastic_cost` elastic ones) and a node belongs to the lowest rank whose slab touches it. A rank
// evaluates only the batches touching a node it owns, colour by colour as one rank does, so each
// of its nodes sums the same terms in the same order; then every rank gives its nodes' forces and
// its batches' shares of the sums (plastic work, stretch; each batch reported by the lowest rank
// evaluating it), and every rank takes them all, in node and batch order. Every rank's far field
// keeps the one-rank bits; a batch on a slab's edge is evaluated on both sides, alike. A cell's
// plastic state is current on the ranks evaluating it: gather_state_to_root() brings it all to
// rank 0, which alone writes it.
#include <array>
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "fem/core_yield.hpp"
#include "fem/orthotropic.hpp"
#include "materials/johnson_cook.hpp"
#include "materials/johnson_cook_damage.hpp"

namespace hvi::fem {

// A layer of the panel, through the thickness.
struct Layer {
  std::string name;
  double z_lower = 0, z_upper = 0;  // m
  int elements = 1;                 // through the thickness
  Orthotropic elasticity;
  double density = 0;  // kg/m^3
  // J2 plasticity with this hardening curve (its A, B, n, and C with `strain_rate`; thermal factor
  // 1), for an isotropic layer only; none: the layer stays elastic and keeps no plastic state.
  std::optional<materials::JohnsonCookStrength> plasticity;
  // A honeycomb core's out-of-plane normal and transverse shear stresses capped where its walls
  // yield (fem/core_yield.hpp); none: elastic. A layer takes this or `plasticity`, not both.
  std::optional<CoreYield> core_yield;
  // With `plasticity`: the layer tears where this Johnson-Cook damage reaches 1
  // (fem/j2_plasticity.hpp); none: it yields without limit.
  std::optional<materials::JohnsonCookDamage> failure;
  // With `plasticity`: the yield stress takes eq. (1)'s rate factor at each quadrature point's
  // equivalent deviatoric strain rate, the change of its strain since the last force evaluation
  // over the step (fem/j2_plasticity.hpp; six more values of state per point); false: the
  // reference rate, factor 1.
  bool strain_rate = false;
};

struct LayeredMesh {
  std::array<double, 2> lower{};         // x, y of the mesh's lower corner
  std::vector<double> x_steps, y_steps;  // element widths along x and y (m), from `lower`
  std::vector<Layer> layers;             // bottom to top, each starting where the last ends
  // Elements whose centre lies inside this in-plane box (x0, y0, x1, y1) are left out: the
  // impact zone, where the material points are.
  std::optional<std::array<double, 4>> hole;
  int degree = 2;  // 1 (trilinear) or 2 (triquadratic)
  bool finite_strain =
      false;  // Green-Lagrange strain and P = F S; false: linearised (small strain)
};

// Element widths covering [a, b]: `fine` in [fine_lower, fine_upper] (which must be whole
// multiples of `fine` from each other), then growing by `ratio` per element away from it up to
// `coarse`, the first `keep` elements outside the fine region exactly `fine` and the others scaled
// so the steps add up to b - a exactly.
std::vector<double> graded_steps(double a, double b, double fine_lower, double fine_upper,
                                 double fine, double ratio, double coarse, int keep = 1);

// The ranks a far field's element work is split over. fem/ knows no MPI: the caller hands in two
// collectives on buffers of doubles, which every rank calls at the same point.
struct FarFieldRanks {
  int rank = 0, size = 1;
  // Every rank's `mine`, indexed by rank, on every rank.
  std::function<std::vector<std::vector<double>>(const std::vector<double>&)> all_gather;
  // Every rank's `mine`, indexed by rank, on rank 0 (what other ranks get back is unused).
  std::function<std::vector<std::vector<double>>(const std::vector<double>&)> gather_to_root;
  // The cost of a plastic lane (J2 or a yielding core, with its return to the yield surface) in
  // elastic lanes, for the slabs' balance.
  double plastic_cost = 3.0;
};

class FarField {
 public:
  // `threads`: the cap on deal.II's own (TBB) threads, which hvi does not use: the cell loops run
  // on OpenMP's threads, colour by colour, with the same result for any number of them.
  explicit FarField(const LayeredMesh& mesh, unsigned threads = 1);
  ~FarField();
  FarField(const FarField&) = delete;
  FarField& operator=(const FarField&) = delete;

  std::size_t node_count() const;
  std::size_t cell_count() const;
  int degree() const;
  // Undeformed node positions, 3 per node.
  std::span<const double> reference_positions() const;
  // Lumped mass of each node, kg (one value per node).
  std::span<const double> lumped_mass() const;
  // The layer of each node: the lowest-numbered layer of the cells around it.
  std::span<const int> node_layer() const;

  // State, 3 per node. Velocities live at half steps (central differences).
  std::span<double> displacement();
  std::span<const double> displacement() const;
  std::span<double> velocity();
  std::span<const double> velocity() const;

  // Essential conditions: components (bit d for axis d) of a node held at zero displacement.
  void fix(std::size_t node, unsigned components);
  unsigned fixed(std::size_t node) const;

  // f = -int P . grad N dV at the current displacement, 3 per node (N); `force` must hold
  // 3 * node_count(). Elastic with small strain: f = -K u. With plastic layers the stress is
  // returned to the yield surface and the plastic state committed: call it once per step, with
  // `dt` the step over which the displacement moved since the last call, the time a layer with
  // `strain_rate` divides its strain's change by (0: the reference rate, for static tests).
  void internal_force(std::span<double> force, double dt = 0.0);
  // The linearised elastic K (at u = 0) applied to any nodal vector (N): for tests and energy.
  void apply_stiffness(std::span<const double> u, std::span<double> Ku) const;

  // One central-difference step of the far field alone: v += dt M^-1 (f_int + f_ext), then
  // u += dt v, fixed components held at zero. `external` may be empty.
  void step(double dt, std::span<const double> external = {});

  // The stable time step 2 / omega_max, with omega_max^2 bounded from above by the largest
  // eigenvalue of M_e^-1 K_e over the elements (the element eigenvalue theorem: the assembled
  // system's is never larger). Computed once from the element matrices, never guessed.
  // With finite strain the tangent stiffens with the stretch: at a point with deformation gradient
  // F the tangent dP/dF = (.) S + F C : sym(F^T .) is bounded by |F|^2 C plus a tensile S of at
  // most C |E| <= C (|F|^2 - 1)/2, so the step is divided by sqrt(k), k = (3 s - 1)/2 with
  // s >= |F|_2^2 (Gershgorin's bound on the eigenvalues of F^T F, 1 for any rotation), the largest
  // at any quadrature point at the last force evaluation (k = 1 undeformed or in compression).
  double stable_time_step() const;

  // Energies (J): kinetic 1/2 sum m v^2 of the current velocities; elastic strain energy
  // 1/2 int (E - E_p) : C (E - E_p) dV (E the strain of the kinematics, E_p the committed plastic
  // strain; 1/2 u.K u when elastic with small strain); the plastic work done so far, sum over
  // steps and points of dgamma q JxW.
  double kinetic_energy() const;
  double strain_energy() const;
  double plastic_work() const;
  double kinetic_energy(std::span<const double> v) const;
  std::array<double, 3> momentum() const;

  // The far field at points of the undeformed mesh, 3 coordinates per point: what material points
  // that take over its cells start from. In the cell holding the point (on a face between two, the
  // one above it): the displacement u and velocity v interpolated by the shape functions, the small
  // strain eps = (H + H^T)/2 of their gradient, and the stress C : (eps - eps_p) with the plastic
  // strain eps_p, alpha and damage of the cell's quadrature point nearest to it (none in elastic
  // layers). The stress is the small-strain one (with finite strain, E's linear part: a sample is
  // taken where the far field is still small-strained). `layer` is -1 for a point outside the mesh,
  // in its hole or in a removed cell.
  struct PointSample {
    int layer = -1;
    std::array<double, 3> displacement{}, velocity{};
    Sym strain{}, elastic_strain{}, stress{};  // Voigt xx, yy, zz, yz, xz, xy; tensor shears
    double plastic_strain = 0.0, damage = 0.0;
  };
  std::vector<PointSample> sample(std::span<const double> points) const;

  // Removes the cells whose centre lies inside the in-plane box (x0, y0, x1, y1), as the mesh's
  // `hole` leaves them out, for an MPM zone that grows over them: from now on they carry no mass,
  // stiffness, stress or plastic state, and leave the energies and the VTU output. A node of
  // removed cells only is detached: its lumped mass is 0, and it neither moves nor counts. The
  // nodes the removed cells share with the rest lose their share of the mass. Returns the number
  // of cells newly removed. Their kinetic and strain energy leave the far field's: the caller
  // books them (the difference of kinetic_energy() and strain_energy() across the call).
  std::size_t remove_cells(const std::array<double, 4>& box);
  std::size_t removed_cell_count() const;
  // The cell batches (of VectorizedArray's width) the element loops visit: those with a cell
  // not removed. A zone grown over the far field's cells takes their cost with them. Spread: those
  // this rank evaluates.
  std::size_t evaluated_batch_count() const;

  // Splits the element work over ranks (see the top of this file); call it once, on every rank,
  // before the first step. From then on internal_force(), step(), apply_stiffness() and
  // strain_energy() are collective: every rank calls them at the same point.
  void spread(FarFieldRanks ranks);
  // The nodes this rank owns (every node on one rank).
  std::size_t owned_node_count() const;
  // Collective when spread (nothing otherwise): rank 0 takes every cell's plastic state, before
  // it reads it: write_vtu(), plastic_state(), sample(), the largest plastic strains and the
  // failed volumes. On other ranks those read what this rank evaluates only.
  void gather_state_to_root();

  // Whether the kinematics are finite (Green-Lagrange) rather than small strain.
  bool finite_strain() const;
  // Whether any layer is plastic (J2 or a yielding core); the largest equivalent plastic strain
  // at any quadrature point of the J2 layers; the largest accumulated plastic strain of a
  // yielding core's (sum of |d eps_p,zz| + |d gamma_p,xz| + |d gamma_p,yz|), 0 without one.
  bool plastic() const;
  double max_equivalent_plastic_strain() const;
  double max_core_plastic_strain() const;
  // The volume of a failing core whose walls are torn (damage D >= 1), and of failing
  // facesheets torn: each such cell's volume times the fraction of its quadrature points failed,
  // in m^3; 0 without a failing core (facesheets).
  double core_failed_volume() const;
  double facesheet_failed_volume() const;
  // The undeformed in-plane centres (x, y: 2 per cell) of the cells not removed whose largest
  // damage over their quadrature points, in a failing core or failing facesheets, is at least
  // `damage`; in the mesh's cell order, so the same for any thread count. Empty without failing
  // layers. Spread, only the cells of the batches this rank reports: their union over the ranks is
  // the one-rank set.
  std::vector<double> damaged_cell_centres(double damage) const;
  // The plastic state (per quadrature point of the plastic layers' cells: eps_p and alpha, the
  // accumulated plastic strain in a yielding core, and a failing layer's damage) and the plastic
  // work, for checkpoints; empty when no layer is plastic.
  std::vector<std::pair<std::string, std::span<double>>> plastic_state();

  std::size_t bytes() const;
  // The mesh and the current displacement and velocity as a VTU file for ParaView (with plastic
  // layers also each cell's largest equivalent plastic strain, or in a yielding core its
  // accumulated plastic strain; each cell's largest damage, `core_damage` with a failing core and
  // `facesheet_damage` with failing facesheets).
  void write_vtu(const std::string& path) const;
  // A ParaView collection (.pvd) of VTU files: (time, file relative to the .pvd) per entry.
  static void write_pvd(const std::string& path,
                        const std::vector<std::pair<double, std::string>>& entries);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hvi::fem
