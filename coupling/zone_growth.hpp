#pragma once
// A hybrid's MPM zone that grows over the far field where the damage reaches its edge, as
// hydrocodes turn eroding elements into particles: the far field cannot tear, perforate or spray
// debris, so the zone must hold wherever the panel does.
//
// When (grown_zone): a side of the zone grows by `step` when a point of the panel's bodies that
// started within `margin` of it (in plane, inside the zone: its undeformed position X, which a
// growing zone's points carry) and is within `margin` of the panel's undeformed thickness (along z)
// has Johnson-Cook damage D >= `damage` (or has failed), up to the side's `limit`. A side on a
// symmetry plane, or already at its limit, stays. The z window leaves out the failed points of the
// panel that fly off it, the front sheet's ejecta and the debris cloud behind the rear sheet,
// which spread radially faster than the panel fails and are not damage the far field would have
// to hold; testing X in plane leaves out the fragments torn off near the axis that fly out along
// the panel's faces, within the window (on the 300 mm panel at 4.5 km/s, core points from 2-5 mm
// off the axis 46-62 mm out, just below the rear face, at 30 us). Points without X (a scene
// whose zone does not grow) are tested where they are. A side also grows when the far field's
// own failing layers have torn a cell within `margin` beyond it (sides_reached_from_outside): the
// far field tears where it must but cannot perforate or throw debris (on the same panel with a
// 40 mm limit, the zone stopped by the points alone at 37.6 x 34.4 mm while the far field's core
// tore in the element row beyond y = 34.4 mm).
//
// How (take_over), between two steps, for the cells of the grown zone:
//  1. The far field is sampled (fem::FarField::sample) at the new points' undeformed positions X,
//     and they start from it: x = X + u(X), v = v(X). A point of a layer that carries its stress
//     (the facesheets) takes the stress C : (eps - eps_p), its alpha and damage, and the volume
//     V0 (1 + tr eps), so that its equation of state gives back the far field's pressure. A
//     point of the homogenised core is a point of a wall, of in-plane direction t (NewPoints'
//     wall_direction), and takes the stress the core's elastic strain e gives that wall, by the
//     kinematics the core's moduli follow from (fem/orthotropic.hpp: the walls stretch with the
//     core along z and shear with it in their own plane, and carry no in-plane load):
//       sigma_zz = E_s e_zz,   tau = G_s gamma_tz,   gamma_tz = 2 (e_xz t_x + e_yz t_y),
//       sigma = sigma_zz e_z e_z + tau (t e_z + e_z t),   V = V0 (1 + (1 - 2 nu_s) e_zz)
//     (uniaxial stress along z: the volume gives back the pressure -sigma_zz / 3). Over walls of
//     all three directions, a fraction rho*/rho_s of the core, this averages to the core's
//     sigma_zz = E3 e_zz and, as <t_x^2> = 1/2, sigma_xz = G_s (rho*/rho_s / 2) gamma_xz, Voigt's
//     bound, which Kelsey's G13 = G_s t/D exceeds by the factor 1 / (1 - t/(2D)) (0.8% for the
//     paper's core). A torn core point (damage 1) starts unstressed, as the far field's torn
//     walls carry nothing. Each point keeps alpha and damage; its specific internal energy is
//     the elastic 1/2 sigma : (eps - eps_p) / rho of its own stress.
//  2. The cells are removed (fem::FarField::remove_cells) and the band is tied anew
//     (FarFieldCoupling::retie).
//  3. Momentum is conserved exactly: the far field's loss of momentum, less the new points', is
//     shared out over the new points as one velocity, dv = (P_lost - sum m v) / sum m.
//  4. Energy is accounted for exactly: what the far field loses (its kinetic and strain energy)
//     less what the new points hold (1/2 m v^2 + m e) is booked in the coupling's internal
//     energy as converted (FarFieldCoupling::book_conversion), so the total stays continuous; its
//     size is reported as the take-over's mismatch.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "coupling/far_field_coupling.hpp"
#include "fem/far_field.hpp"
#include "mpm/solver.hpp"

namespace hvi::coupling {

// With a zone that grows, every point carries its undeformed position X (3 per point, m), written
// to the snapshots: the points of the start their position at t = 0, the points a take-over adds
// the far field's undeformed point they take over. So position - X is the displacement of any
// point, also of one born after the first snapshot (a probe read after the run, ParaView).
inline constexpr const char* reference_position_field = "reference_position";

struct ZoneGrowth {
  std::array<double, 4> limit{};  // the largest zone: x0, y0, x1, y1 (m, on grid planes)
  double step = 0.0;              // m, a whole number of grid cells
  double margin = 0.0;            // m
  double damage = 1.0;            // D that counts as reaching the edge
  double z_lower = 0.0,
         z_upper = 0.0;  // the panel's undeformed thickness, rear face to front face (m)
  // Per side (x0, y0, x1, y1): whether it may move (false on a symmetry plane).
  std::array<bool, 4> movable{true, true, true, true};
};

// Per side of `zone` (x0, y0, x1, y1): whether a damaged point of `bodies` (indices into the
// scene's bodies) reaches it, as above (by its `reference_position_field` where the particles
// have one), whether or not the side may move.
std::array<bool, 4> sides_reached(const mpm::Particles& particles,
                                  std::span<const std::int64_t> bodies,
                                  const std::array<double, 4>& zone, const ZoneGrowth& growth);

// Per side of `zone`: whether the far field's own damage reaches it from outside, a damaged cell's
// in-plane centre (x, y pairs, fem::FarField::damaged_cell_centres) lying within `margin` beyond
// the side and across the zone's extent widened by `margin`. The far field tears only as its
// failing layers let it and throws no debris, so damage there is a reason for the zone to grow,
// as damage of the points at the side is.
std::array<bool, 4> sides_reached_from_outside(std::span<const double> centres,
                                               const std::array<double, 4>& zone,
                                               const ZoneGrowth& growth);

// The zone grown by `step` on the movable sides `reached` names, each up to its limit; `zone`
// itself when no side needs to move.
std::array<double, 4> grown_zone(const std::array<bool, 4>& reached,
                                 const std::array<double, 4>& zone, const ZoneGrowth& growth);
std::array<double, 4> grown_zone(const mpm::Particles& particles,
                                 std::span<const std::int64_t> bodies,
                                 const std::array<double, 4>& zone, const ZoneGrowth& growth);

// The sides `reached` names that would move but are at their limit: there the damage reaches
// the far field, which cannot hold it (it tears only as its failing layers let it, and sprays no
// debris), so the limit, not the damage, bounds the zone.
std::array<bool, 4> sides_held_at_limit(const std::array<bool, 4>& reached,
                                        const std::array<double, 4>& zone,
                                        const ZoneGrowth& growth);

// The ring `grown` adds to `zone` (grown holds zone), as up to four in-plane boxes x0, y0, x1, y1
// that do not overlap: below and above the zone along y over the grown zone's width, and left and
// right of it along x over the zone's height.
std::vector<std::array<double, 4>> ring(const std::array<double, 4>& zone,
                                        const std::array<double, 4>& grown);

// Material points, undeformed, that take over far-field cells.
struct NewPoints {
  std::vector<double> position;  // X, 3 per point (m)
  // The in-plane unit direction t of a wall point's wall (2 per point; zeros for a point not in
  // a honeycomb wall), or empty when there is no core among the points.
  std::vector<double> wall_direction;
  std::vector<double> volume;      // V0 (m^3)
  std::vector<double> half_width;  // 3 per point (m), or empty
  std::vector<double> density;     // reference density (kg/m^3)
  std::vector<std::int64_t> body, material;
  std::size_t size() const { return volume.size(); }
};

struct TakeoverReport {
  std::size_t points = 0, cells = 0;
  std::int64_t first_id = 0;         // the new points' ids: first_id + k for NewPoints' point k
  double far_field_energy = 0.0;     // the far field's loss, J
  double point_energy = 0.0;         // what the new points hold, J
  double far_field_kinetic = 0.0;    // the kinetic part of far_field_energy, J
  double point_kinetic = 0.0;        // the kinetic part of point_energy, J
  double momentum_correction = 0.0;  // |dv| of step 3, m/s
};

// What the points of a far-field layer take from it (step 1 above): a solid's stress (the
// facesheets), or, for the homogenised core, the stress of its walls, whose elastic constants
// are given.
struct LayerTakeover {
  enum class Kind { solid, walls } kind = Kind::solid;
  double wall_youngs_modulus = 0.0, wall_poisson_ratio = 0.0;  // Pa, -; for walls
};

// `layers[l]`: how points of far-field layer l start. Throws std::invalid_argument when a point of
// a walls layer has no wall direction, fem's and the coupling's errors, or mpm::SolverError for
// a point that falls outside the far field or the grid. Collective in a run spread over ranks:
// every rank takes the cells out of its far field, and the points are rank 0's (none elsewhere).
TakeoverReport take_over(FarFieldCoupling& coupling, fem::FarField& far_field, mpm::Solver& solver,
                         const NewPoints& points, const InterfaceBand& band,
                         const std::vector<LayerTakeover>& layers);

}  // namespace hvi::coupling
