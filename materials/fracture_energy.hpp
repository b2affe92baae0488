#pragma once
// Damage evolution over a fracture energy (the crack band model: Hillerborg, Modeer & Petersson
// 1976; Bazant & Oh 1983). Once damage has initiated (Johnson-Cook D = 1, eqs. 2-3), a point does
// not fail at once: it softens, its flow stress and its tension scaled by (1 - omega), until it has
// dissipated G_f per unit area of a band of width L. The work it does from initiation on, per unit
// area of the band, is g = rho_0 L w (w per unit mass: plastic, and of its tension on its opening),
// and omega follows from g as for linear softening, stress = (1 - u / u_f) sigma_0 over an opening
// u, whose work is g = G_f (2 omega - omega^2):
//   omega = 1 - sqrt(1 - g / G_f),
// which reaches 1, and the point fails, at g = G_f after a finite opening u_f = 2 G_f / sigma_0. A
// crack then costs its measured energy on any grid, instead of the energy of one row of points up
// to initiation, which falls with the cell. In MPM a strain localises in no less than one grid cell
// (the velocity is interpolated from the nodes), so L is the cell size.
#include <algorithm>
#include <cmath>

namespace hvi::materials {

struct FractureEnergy {
  double energy = 0.0;  // G_f, J/m^2
  double band = 0.0;    // L, m

  // The share of G_f a work w (J/kg) of a point of reference density rho_0 dissipates: g / G_f.
  double share(double rho_0, double work) const { return rho_0 * band * work / energy; }
  // 1 - omega, the fraction of its strength a point keeps once it has spent `spent` of G_f.
  static double intact(double spent) { return std::sqrt(std::max(1.0 - spent, 0.0)); }
};

}  // namespace hvi::materials
