#pragma once
// The far-field mesh of a honeycomb panel, from the same description the MPM zone is sampled from
// (geometry::HoneycombPanel): its three layers at the panel's own z ranges, the core homogenised
// (fem/orthotropic.hpp) from its cells and wall material, and the MPM zone cut out. Near the zone
// the elements are trilinear bricks one grid cell wide whose nodes sit on the grid's nodes in
// plane (the interface band, where the MPM grid's linear shape functions and the bricks' agree, so
// a uniform stress gives no interface force); beyond `band_elements` they grow by `ratio` per
// element up to `max_element`, which defaults to 6 facesheet thicknesses: Q1 faces lock in their
// own bending as (length / thickness)^2 (tests/fem: 1.4% in frequency at 6.25 t_f).
#include <array>
#include <optional>

#include "coupling/far_field_coupling.hpp"
#include "fem/far_field.hpp"
#include "geometry/honeycomb.hpp"
#include "mpm/grid.hpp"

namespace hvi::coupling {

struct SolidMaterial {
  double youngs_modulus = 0, poisson_ratio = 0, density = 0;
  // J2 plasticity (facesheets), or for the core's walls the yield stress of a yielding core (its
  // A); none: elastic.
  std::optional<materials::JohnsonCookStrength> hardening;
  // For failing facesheets (with `hardening`; fem::FarField refuses them without) or a failing
  // core's walls: their Johnson-Cook damage (eqs. 2-3); none otherwise.
  std::optional<materials::JohnsonCookDamage> damage;
};

struct PanelFarFieldSpec {
  SolidMaterial front, core_wall, rear;
  std::array<double, 4> zone{};  // the MPM zone in plane: x0, y0, x1, y1 on grid planes (m)
  // A zone that grows (coupling/zone_growth.hpp) up to this box (holding `zone`, on grid planes):
  // the elements are one grid cell wide over it and its band, so that every band it may grow to
  // ties nodes that sit on grid nodes. None: a fixed zone.
  std::optional<std::array<double, 4>> growth_limit;
  int band_elements = 2;       // grid-cell-wide elements beyond the zone
  double ratio = 1.25;         // growth of the element length beyond them
  double max_element = 0;      // m; 0: 6 times the thinner facesheet
  int core_elements = 8;       // through the core height
  int face_elements = 1;       // through each facesheet
  bool finite_strain = false;  // Green-Lagrange kinematics (fem/far_field.hpp); false: small strain
  // J2 facesheets (with `hardening`) whose yield stress takes the rate factor of their strain rate
  // (fem::Layer::strain_rate); false: the reference rate.
  bool strain_rate = false;
  // The core's out-of-plane stresses capped where its walls yield (fem/core_yield.hpp, sigma_ys
  // = core_wall.hardening's A); false: the core stays elastic.
  bool yielding_core = false;
  // A yielding core whose walls also fail, where their Johnson-Cook damage (core_wall.damage)
  // reaches 1 (fem/core_yield.hpp); false: the caps hold.
  bool failing_core = false;
};

// Throws std::invalid_argument when the zone (or the growth limit) is not on grid planes or not
// inside the panel, the growth limit does not hold the zone, a
// yielding core's walls have no hardening (yield stress), a failing core's no damage, or the
// panel has double walls and its cell pattern is not turned by a multiple of 90 degrees (the
// core's orthotropic axes must be the panel's).
fem::LayeredMesh panel_far_field_mesh(const geometry::HoneycombPanel& panel,
                                      const PanelFarFieldSpec& spec, const mpm::GridGeometry& grid);

// The band the coupling ties: the zone and the band elements beyond it.
InterfaceBand panel_interface_band(const PanelFarFieldSpec& spec, const mpm::GridGeometry& grid);

}  // namespace hvi::coupling
