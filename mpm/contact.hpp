#pragma once
// Contact between an impactor and the bodies it strikes, with two velocity fields on the grid
// (Bardenhagen, Brackbill and Sulsky 2000; Bardenhagen et al. 2001; for hypervelocity impact
// Huang, Zhang, Ma and Wang 2011). Standard MPM has one velocity per node: wherever two bodies'
// points share a node they stick, and a projectile's material jetting sideways at the rim of the
// crater drags the facesheet outward with it (docs/log/paper_cases.md). Here the bodies
// named in the scene's [contact] table (field 1) scatter to a grid of their own; every other body
// (field 0) to the solver's grid. Each field runs the whole step on its own nodes. Where a node
// carries mass of both fields, the fields meet:
//   each field's outward normal at node I:           g_k = sum_p m_p grad N_I(x_p)   (p of field k;
//                                                    ~ -int N_I grad rho, so away from its
//                                                    material)
//   the normal, pointing from field 1 into field 0:  n = (g1 - g0) / |g1 - g0|
//   the centre-of-mass velocity:                      v_cm = (m0 v0 + m1 v1) / (m0 + m1)
//   approaching when                                  (v1 - v0) . n > 0,
// and then the normal relative velocity is removed and, with Coulomb friction mu, as much of the
// tangential one as mu times the normal change allows. In the relative velocity w = v1 - v0
// (well conditioned when one field's mass at a node is a GIMP tail many orders below the other's):
//   wn = w . n,  w_t = w - wn n,  dw = -wn n - min(mu wn, |w_t|) w_t / |w_t|,
//   dv1 = (m0 / M) dw,  dv0 = -(m1 / M) dw,  M = m0 + m1   (momentum is conserved node by node).
// Separating fields move freely. The correction is applied to the start velocity (where the
// particles' positions and USF's strain rate start from), to the end velocity through its
// increment (which the particles' FLIP update takes) and, at the nodes so corrected, to the MUSL
// remapped velocity whatever its sign (its strain rate must see the bodies held together as their
// motion did). Applying it to all three makes a symmetric collision exactly the one-field one
// until the bodies pull apart (tested: touching bars part, a frictionless oblique impact keeps the
// tangential velocity and the energy to 4e-5). Frictionless contact does no work in the continuum,
// so nothing is booked for it (where the fields are crushed together the discrete corrections do
// lose some: the thin-wall hard case's balance is -2.7% with contact, +1.3% without); friction
// heat, the friction impulse times the slip it leaves, is booked so the balance closes.
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "mpm/bond.hpp"
#include "mpm/grid.hpp"
#include "mpm/particle_bins.hpp"
#include "mpm/particles.hpp"
#include "mpm/transfers.hpp"

namespace hvi::mpm {

struct ContactSettings {
  std::vector<std::uint8_t> impactor;  // per body: 1 if it belongs to field 1
  double friction = 0.0;               // Coulomb coefficient mu
  // Field 1 is a core bonded to field 0's facesheets (bond.hpp): tied where still bonded.
  std::optional<BondSettings> bond;
};

class BodyContact {
 public:
  BodyContact(const GridGeometry& geometry, ContactSettings settings);

  // Per particle: its field (0 or 1), from its body. Recomputed when particles change.
  const std::vector<std::uint8_t>& assign_fields(const Particles& particles);
  const std::vector<std::uint8_t>& fields() const { return field_; }

  SparseGrid& grid() { return grid_; }  // field 1's nodes
  const SparseGrid& grid() const { return grid_; }
  ParticleBins& bins() { return bins_; }
  const ParticleBins& bins() const { return bins_; }

  // Each field's outward normals g_k this step (after both are binned), each with its grid's
  // context (a run spread over ranks shares each grid's blocks apart).
  void compute_normals(const Particles& particles, const ParticleBins& bins0, SparseGrid& grid0,
                       const TransferContext& context0, const TransferContext& context1);

  // Corrects the nodal velocity `which` (start: p, end: p + f via f, remapped: q) of both fields
  // at every node where they approach; the remapped velocity at every node where the end
  // velocity was corrected. With a bond, ties them where bonded whatever their motion (the end
  // correction's force over the step `dt` kept for the bond's tractions). Returns the friction
  // heat of an end correction (J; 0 otherwise).
  double apply(SparseGrid& grid0, NodalVelocity which, double dt);
  // With a bond (else nullptr): the interface, prepared once the step's grids are binned.
  BondInterface* bond() { return bond_.get(); }
  // The friction heat of the last correction per field-1 block (0 but for an end correction).
  const std::vector<double>& block_work() const { return block_work_; }
  bool has_friction() const { return settings_.friction > 0.0; }

  std::size_t bytes() const;

 private:
  ContactSettings settings_;
  SparseGrid grid_;
  ParticleBins bins_;
  std::vector<std::uint8_t> field_;
  std::vector<double> normal0_, normal1_;  // g_k per node, in each grid's node storage order
  std::vector<double> block_work_;
  std::vector<std::uint8_t> in_contact_;  // per field-1 node: corrected at the end stage this step
  std::vector<std::uint8_t> tied_;        // per field-1 node: tied by the bond at the end stage
  std::vector<std::uint8_t> meeting0_, meeting1_;  // per owner block of each field: near the other
  std::unique_ptr<BondInterface> bond_;
};

}  // namespace hvi::mpm
