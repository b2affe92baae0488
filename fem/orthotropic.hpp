#pragma once
// Linear orthotropic elasticity in the panel frame (1 = x, 2 = y, 3 = z, the panel normal) and the
// homogenised honeycomb core of the far field. No deal.II here: plain numbers, testable alone.
#include <array>
#include <string>

namespace hvi::fem {

// Engineering constants. nu_ij is the contraction along j under a stress along i, so that
// nu_ij / E_i = nu_ji / E_j (the compliance is symmetric).
struct Orthotropic {
  double E1 = 0, E2 = 0, E3 = 0;
  double nu12 = 0, nu13 = 0, nu23 = 0;
  double G12 = 0, G13 = 0, G23 = 0;
};

Orthotropic isotropic(double youngs_modulus, double poisson_ratio);

// The honeycomb core as a homogeneous orthotropic solid, from its wall material (E_s, nu_s) and
// its cells (D_hc between wall mid-surfaces, wall thickness t_hc; regular hexagons, single walls).
// With the wall edge l = D/sqrt(3) and the solidity rho*/rho_s = (2t/D)(1 - t/(2D)) (the closed
// form geometry/ checks against the CGAL core) the closed forms of Gibson & Ashby, Cellular Solids
// (2nd ed.), ch. 4, for a regular hexagon (h = l, theta = 30 deg) are
//   out of plane  E3 = E_s rho*/rho_s,   nu31 = nu32 = nu_s
//   transverse shear (Kelsey's bounds coincide for the regular hexagon)
//                 G13 = G23 = G_s t/(sqrt(3) l) = G_s t/D
//   in plane (wall bending)
//                 E1 = E2 = E_s (t/l)^3 cos(theta) / ((h/l + sin(theta)) sin^2(theta))
//                         = (4/sqrt(3)) E_s (t/l)^3
//                 G12 = E_s (t/l)^3 (h/l + sin(theta)) / ((h/l)^2 (1 + 2h/l) cos(theta))
//                     = E_s (t/l)^3 / sqrt(3)
// The in-plane Poisson ratio of pure wall bending is 1, which makes a 3D compliance singular; we
// take nu12 = 0.99. The in-plane stiffness is 1e-4 of the facesheets' and does not matter to the
// panel's bending; it only has to be positive definite.
//
// Double walls (expanded honeycomb: the walls parallel to the ribbon direction, here y, are 2t
// thick, as geometry/ builds them). E3 = E_s rho*/rho_s with the solidity below. Transverse shear
// by Kelsey's two energy bounds per cell (area (3 sqrt(3)/2) l^2: one ribbon wall of length l,
// two inclined walls at 30 degrees to x):
//   across the ribbon (xz): the ribbon walls carry no shear flow in either bound, so
//                 G13 = G_s t/D, as for single walls;
//   along the ribbon (yz): unit displacement (upper) G_s (2t + t/2) / (3/2 sqrt(3) l) = 5/3 G_s
//   t/D,
//                 unit load (lower; the ribbon wall's flow splits in two at each joint)
//                 G_s (3/2 sqrt(3) l^2) / ((sqrt(3) l)^2 (l/2t + l/2t)) = 3/2 G_s t/D;
//                 we take their mean, G23 = 19/12 G_s t/D (each bound within 5.3% of it).
// The in-plane moduli keep the single-wall forms: the inclined walls bend as before, and the
// thicker ribbon walls only stiffen G12, which does not matter here.
Orthotropic honeycomb_core(double wall_youngs_modulus, double wall_poisson_ratio,
                           double cell_diameter, double wall_thickness, bool double_walls = false);
// rho*/rho_s of regular hexagons, single or double walls (the same closed form as geometry/'s):
// single (2t/D)(1 - t/(2D)), double (8t/(3D))(1 - t/(2D)) (1 minus the cell's interior, shrunk by
// half a wall, or a whole one on the two ribbon sides, over its (sqrt(3)/2) D^2).
double honeycomb_core_solidity(double cell_diameter, double wall_thickness,
                               bool double_walls = false);

// The stiffness C (sigma = C eps, Voigt order xx, yy, zz, yz, xz, xy with engineering shear
// strains) of an orthotropic solid in its axes: the nine independent entries
//   {C11, C22, C33, C12, C13, C23, C44 = G23, C55 = G13, C66 = G12}.
// Throws std::invalid_argument when the constants are not positive definite.
std::array<double, 9> stiffness(const Orthotropic& m);

// The largest longitudinal wave speed sqrt(max(C11, C22, C33) / rho), m/s.
double max_wave_speed(const Orthotropic& m, double density);

}  // namespace hvi::fem
