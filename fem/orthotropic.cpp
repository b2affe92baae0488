#include "fem/orthotropic.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Dense>

namespace hvi::fem {

Orthotropic isotropic(double E, double nu) {
  const double G = E / (2.0 * (1.0 + nu));
  return {E, E, E, nu, nu, nu, G, G, G};
}

double honeycomb_core_solidity(double D, double t, bool double_walls) {
  return (double_walls ? 8.0 * t / (3.0 * D) : 2.0 * t / D) * (1.0 - t / (2.0 * D));
}

Orthotropic honeycomb_core(double Es, double nus, double D, double t, bool double_walls) {
  if (!(D > 0.0) || !(t > 0.0) || t >= D)
    throw std::invalid_argument("honeycomb core: need 0 < wall thickness < cell diameter");
  const double Gs = Es / (2.0 * (1.0 + nus));
  const double l = D / std::sqrt(3.0);  // wall edge of the regular hexagon
  const double tl3 = std::pow(t / l, 3);
  Orthotropic c;
  c.E3 = Es * honeycomb_core_solidity(D, t, double_walls);
  c.E1 = c.E2 = 4.0 / std::sqrt(3.0) * Es * tl3;
  c.G12 = Es * tl3 / std::sqrt(3.0);
  c.G13 = c.G23 = Gs * t / D;
  if (double_walls) c.G23 = 19.0 / 12.0 * Gs * t / D;  // along the ribbon: Kelsey's bounds' mean
  c.nu12 = 0.99;
  // nu31 = nu_s; the symmetric compliance gives nu13 = nu31 E1 / E3.
  c.nu13 = c.nu23 = nus * c.E1 / c.E3;
  return c;
}

std::array<double, 9> stiffness(const Orthotropic& m) {
  // Compliance in Voigt order (normal part), inverted.
  Eigen::Matrix3d S;
  S << 1.0 / m.E1, -m.nu12 / m.E1, -m.nu13 / m.E1,  //
      -m.nu12 / m.E1, 1.0 / m.E2, -m.nu23 / m.E2,   //
      -m.nu13 / m.E1, -m.nu23 / m.E2, 1.0 / m.E3;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(S);
  if (!(m.E1 > 0 && m.E2 > 0 && m.E3 > 0 && m.G12 > 0 && m.G13 > 0 && m.G23 > 0) ||
      !(eig.eigenvalues().minCoeff() > 0.0))
    throw std::invalid_argument("orthotropic elasticity: the constants are not positive definite");
  const Eigen::Matrix3d C = S.inverse();
  return {C(0, 0), C(1, 1), C(2, 2), C(0, 1), C(0, 2), C(1, 2), m.G23, m.G13, m.G12};
}

double max_wave_speed(const Orthotropic& m, double density) {
  const auto C = stiffness(m);
  return std::sqrt(std::max({C[0], C[1], C[2]}) / density);
}

}  // namespace hvi::fem
