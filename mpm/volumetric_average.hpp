#pragma once
// Node-averaged dilatation, for walls only a few cells thick (grid.dilatation = "node-average").
//
// Plastic flow keeps volume constant. A facesheet two cells thick, stretched and bent in its
// plane, must thin out to do so, and standard MPM gives every point the dilatation d_p = tr L_p of
// a velocity field two cells across, which cannot keep every point's volume: the points see
// expansion that varies from point to point, hydrostatic tension in a sheet that should be in
// plane stress (triaxiality sigma* <= 2/3). This is volumetric locking (with cell-crossing noise
// on top). Al6061's Johnson-Cook failure strain (eq. 3, Table 4) is zero above
// sigma* = 1.35, so the tension fails the sheet: at 0.4 mm cells the front hole's edge fails
// at sigma* 1.35-1.6 under 0.7-1.0 GPa of tension (docs/log/paper_cases.md).
//
// The remedy is that of B-bar and F-bar elements (Hughes 1980; for MPM Mast et al. 2012, Coombs et
// al. 2018): fewer volume constraints than points. Each intact point's dilatation is replaced by
// its average through the grid nodes, body by body:
//   d_I = sum_q N_I(x_q) V_q d_q / sum_q N_I(x_q) V_q   (q intact, of the body of p)
//   dbar_p = sum_I N_I(x_p) d_I,       L_p <- L_p + (dbar_p - d_p) / 3 1.
// The operator A (dbar = A d) satisfies V_p A_pq = V_q A_qp, so with the mean stress m = tr sigma /
// 3 averaged the same way, sum_p V_p m_p dbar_p = sum_p V_p mbar_p d_p. The internal force
// therefore uses mbar: f_I = -sum_p V_p (sigma_p + (mbar_p - m_p) 1) grad N_I(x_p), and the work
// the grid does on the points is exactly the work they book in their internal energy (tested).
// Failed points (no tension, no shear) are left out of both averages and keep their own d_p:
// the spray of a hole expanding away must not be averaged into the intact wall beside it. Bodies
// are averaged apart, so a projectile's shock is not spread into the sheet it strikes.
// Both averages are taken in the same step, from the same positions, volumes and failure flags
// (with USF the force's average follows the stress update, so points failing in that step have
// already left it).
#include <vector>

#include "mpm/grid.hpp"
#include "mpm/particle_bins.hpp"
#include "mpm/particles.hpp"
#include "mpm/transfers.hpp"

namespace hvi::mpm {

class VolumetricAverage {
 public:
  explicit VolumetricAverage(int bodies) : bodies_(bodies) {}

  // Before a scatter of the internal force: the node sums of the mean stress m_p = tr sigma_p / 3,
  // for TransferContext::mean_stress (the scatter gathers mbar_p - m_p from them).
  const NodeAverageSums& mean_stress_sums(const Particles& particles, const ParticleBins& bins,
                                          SparseGrid& grid, const TransferContext& context);

  // For velocity_gradient: where it puts d_p = tr L_p and the node sums of the dilatation.
  const NodeAverageSums& dilatation_sums(const Particles& particles);
  std::vector<double>* dilatation_values() { return &value_; }
  // After velocity_gradient with dilatation_sums(): L_p <- L_p + (dbar_p - d_p) / 3 1 on every
  // intact point.
  void average_dilatation(Particles& particles, const ParticleBins& bins, const SparseGrid& grid,
                          const TransferContext& context);

  std::size_t bytes() const {
    return (value_.capacity() + average_.capacity() + sums_.capacity()) * sizeof(double);
  }

 private:
  NodeAverageSums averaging(const Particles& particles);
  int bodies_;
  std::vector<double> value_, average_, sums_;
  NodeAverageSums current_;
};

}  // namespace hvi::mpm
