#pragma once
// Closed forms the far-field tests are checked against: the first bending frequency of a simply
// supported rectangular plate, homogeneous or sandwich, in first-order shear-deformation theory.
//
// For the mode w = W sin(pi x/a) sin(pi y/b) with k^2 = pi^2 (1/a^2 + 1/b^2), a plate with
// bending stiffness D0 carried through a shear stiffness S (Mindlin; for a sandwich Allen's
// "thick-face" theory, Allen 1969, ch. 2-3), face bending D_f acting on the deflection alone, mass
// m per area and rotary inertia I per area satisfies
//   (S k^2 + D_f k^4 - m w^2)(D0 k^2 + S - I w^2) - S^2 k^2 = 0,
// a quadratic in w^2 whose smaller root is the first bending frequency. With S -> infinity and
// I = 0 it is Kirchhoff's w = k^2 sqrt((D0 + D_f)/m).
#include <cmath>

namespace hvi::fem::test {

struct PlateStiffness {
  double D0, Df, S, m, I;
};

// The rotation amplitude Theta (per unit W) of the mode: the rotation field is Theta cos(kx x)...
inline double mode_rotation(const PlateStiffness& p, double k2, double omega2) {
  const double k = std::sqrt(k2);
  return (p.S * k2 + p.Df * k2 * k2 - p.m * omega2) / (p.S * k);
}

inline double first_bending_omega2(const PlateStiffness& p, double k2) {
  const double A = p.S * k2 + p.Df * k2 * k2, B = p.D0 * k2 + p.S;
  // (A - m x)(B - I x) - S^2 k^2 = 0  ->  m I x^2 - (A I + B m) x + (A B - S^2 k^2) = 0
  const double a = p.m * p.I, b = -(A * p.I + B * p.m), c = A * B - p.S * p.S * k2;
  if (a == 0.0) return c / -b;
  return (-b - std::sqrt(b * b - 4 * a * c)) / (2 * a);
}

// A sandwich with equal faces (E_f, nu_f, rho_f, thickness t) and an antiplane core (transverse
// shear modulus G_c, density rho_c, height c); d = c + t between the face centroids.
inline PlateStiffness sandwich(double Ef, double nuf, double rhof, double t, double Gc, double rhoc,
                               double c) {
  const double d = c + t, Dface = Ef / (1 - nuf * nuf);
  return {Dface * t * d * d / 2, 2 * Dface * t * t * t / 12, Gc * d * d / c,
          2 * rhof * t + rhoc * c, 2 * rhof * t * (d / 2) * (d / 2) + rhoc * c * c * c / 12};
}

// A homogeneous plate (Mindlin, shear correction 5/6).
inline PlateStiffness homogeneous(double E, double nu, double rho, double h) {
  const double G = E / (2 * (1 + nu));
  return {E * h * h * h / (12 * (1 - nu * nu)), 0.0, 5.0 / 6.0 * G * h, rho * h,
          rho * h * h * h / 12};
}

}  // namespace hvi::fem::test
