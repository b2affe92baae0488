// The MPM zone growing over the far field (coupling/zone_growth.hpp), on the bar of
// test_far_field_coupling.cpp (MPM left of x = 60 h, finite elements right of it, rollers on the
// long sides): the take-over of the elements in [60 h, 70 h] by material points
//  - keeps a rigid translation rigid: every particle and node moves on at V, to round-off;
//  - keeps a uniform strain uniform: the new points carry its stress and strain energy, so the
//    new interface at 70 h feels no force in the next step beyond the order of the displacement
//    over the cell size (the points sit at X + u, and keep X as their reference position);
//  - conserves momentum exactly and books the energy it does not carry over, which is zero to
//    round-off in both cases (the points hold the cells' mass, kinetic and strain energy);
//  - gives the points of a homogenised honeycomb core the stress of their walls, which averages
//    to the core's (to Voigt's versus Kelsey's bound, t/(2D));
// and grown_zone moves only the sides that damaged points of the panel reach, by its step, up to
// the limit (the panel's debris and ejecta, off its thickness, do not count, nor, by where they
// started, its fragments flown out along it).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "coupling/far_field_coupling.hpp"
#include "coupling/zone_growth.hpp"
#include "fem/orthotropic.hpp"
#include "geometry/lattice_sampler.hpp"
#include "tests/coupling/coupled_bar.hpp"

namespace hvi::coupling {
namespace {

using namespace test;

constexpr int grown_cells = 10;

struct Bar {
  std::unique_ptr<mpm::Solver> solver;
  std::unique_ptr<fem::FarField> far;
  std::unique_ptr<FarFieldCoupling> coupling;
  explicit Bar(std::unique_ptr<fem::FarField> far_field = bar_far_field())
      : solver(bar_solver(mpm_cells)), far(std::move(far_field)) {
    coupling = std::make_unique<FarFieldCoupling>(
        *far, bar_grid(), InterfaceBand{{-4 * h, 0, mpm_cells * h, 2 * h}, h});
    solver->add_coupling(coupling.get());
  }
  // The points of [60 h, (60 + cells) h], sampled as the bar's were.
  NewPoints grown_points(int cells = grown_cells) const {
    const auto g = bar_grid();
    const auto s = geometry::sample_lattice(
        geometry::Box({mpm_cells * h, 0, 0}, {(mpm_cells + cells) * h, 2 * h, 2 * h}), h / 2,
        {g.origin[0], g.origin[1], g.origin[2]});
    NewPoints p;
    p.position = s.position;
    p.volume = s.volume;
    p.density.assign(s.size(), rho);
    p.body.assign(s.size(), 0);
    p.material.assign(s.size(), 0);
    return p;
  }
  TakeoverReport grow(const NewPoints& points, int cells, const LayerTakeover& layer) {
    return take_over(*coupling, *far, *solver, points,
                     InterfaceBand{{-4 * h, 0, (mpm_cells + cells) * h, 2 * h}, h}, {layer});
  }
  TakeoverReport grow() { return grow(grown_points(), grown_cells, LayerTakeover{}); }
  double mass() const {
    double m = 0;
    for (const double x : solver->particles().mass) m += x;
    for (const double x : far->lumped_mass()) m += x;
    return m;
  }
};

TEST(ZoneGrowth, TakeOverKeepsARigidTranslation) {
  mpm::test::Threads one(1);
  Bar B;
  const double V = 3.0;
  auto& P = B.solver->particles();
  for (std::size_t p = 0; p < P.size(); ++p) P.velocity[3 * p] = V;
  for (std::size_t a = 0; a < B.far->node_count(); ++a) B.far->velocity()[3 * a] = V;
  B.solver->initialise();
  for (int s = 0; s < 5; ++s) B.solver->step();
  const double mass = B.mass(), p0 = B.solver->energy().momentum[0],
               e0 = B.solver->energy().total();
  const std::size_t n0 = P.size();
  const TakeoverReport r = B.grow();
  EXPECT_EQ(r.points, 10u * 4u * 4u * 2u);  // 10 cells x 2 x 2, 8 points per cell
  EXPECT_EQ(P.size(), n0 + r.points);
  EXPECT_EQ(r.cells, 10u * 2u * 2u);
  EXPECT_EQ(B.coupling->tied_node_count(), 18u);  // the nodes at 70 h and 71 h
  EXPECT_NEAR(B.mass(), mass, 1e-12 * mass);
  EXPECT_NEAR(B.solver->energy().momentum[0], p0, 1e-12 * std::abs(p0));
  EXPECT_LT(r.momentum_correction, 1e-12 * V);
  EXPECT_NEAR(r.point_energy, r.far_field_energy, 1e-12 * r.far_field_energy);
  EXPECT_NEAR(B.solver->energy().total(), e0, 1e-12 * e0);
  for (int s = 0; s < 20; ++s) B.solver->step();
  double worst = 0;
  for (std::size_t p = 0; p < P.size(); ++p)
    worst = std::max(worst, std::abs(P.velocity[3 * p] - V));
  for (std::size_t a = 0; a < B.far->node_count(); ++a)
    if (B.far->lumped_mass()[a] > 0)
      worst = std::max(worst, std::abs(B.far->velocity()[3 * a] - V));
  EXPECT_LT(worst, 1e-12 * V);
  EXPECT_NEAR(B.solver->energy().momentum[0], p0, 1e-12 * std::abs(p0));
}

TEST(ZoneGrowth, TakeOverKeepsAUniformStrain) {
  mpm::test::Threads one(1);
  Bar B;
  const double eps = 1e-4;
  auto& P = B.solver->particles();
  strain_uniformly(P, *B.far, eps);
  B.solver->initialise();
  P.add_field(reference_position_field, mpm::FieldKind::vector, "m");
  const double e0 = B.solver->energy().total();
  const std::size_t n0 = P.size();
  const NewPoints points = B.grown_points();
  const TakeoverReport r = B.grow(points, grown_cells, LayerTakeover{});
  // The new points: stress M eps, lambda eps; strain energy 1/2 M eps^2 per volume, as the cells;
  // their undeformed positions X kept exactly, and x - X the far field's displacement eps X.
  const auto& X = P.field(reference_position_field);
  std::size_t found = 0;
  for (std::size_t p = 0; p < P.size(); ++p) {  // the adoption sorts the arrays: found by id
    if (P.id[p] < r.first_id) continue;
    ++found;
    const auto k =
        static_cast<std::size_t>(P.id[p] - r.first_id);  // new point k has id first_id + k
    for (int d = 0; d < 3; ++d) EXPECT_EQ(X[3 * p + d], points.position[3 * k + d]);
    EXPECT_NEAR(P.position[3 * p] - X[3 * p], eps * X[3 * p], 1e-12 * h);
    EXPECT_NEAR(P.stress[6 * p + mpm::sym::xx], M * eps, 1e-9 * M * eps);
    EXPECT_NEAR(P.stress[6 * p + mpm::sym::yy], lambda * eps, 1e-9 * M * eps);
    EXPECT_NEAR(P.volume[p], P.volume0[p] * (1 + eps), 1e-12 * P.volume0[p]);
  }
  EXPECT_EQ(found, P.size() - n0);
  const double cells = 0.5 * M * eps * eps * grown_cells * h * 4 * h * h;
  EXPECT_NEAR(r.far_field_energy, cells, 1e-9 * cells);
  EXPECT_NEAR(r.point_energy, cells, 1e-9 * cells);
  EXPECT_NEAR(B.solver->energy().total(), e0, 1e-9 * e0);
  // One step: only the free far end moves; the new interface at 70 h feels nothing.
  B.solver->step();
  const auto [far_end, interface] = patch_speeds(P, *B.far, (mpm_cells + grown_cells) * h);
  EXPECT_GT(far_end, 1e-3);
  // The new points sit where the far field has moved their material, X + eps X (0.006-0.007 h
  // from X), while the bar's first points were left at X with their stress set; so the patch
  // holds to the order of that offset, u / h, not to round-off as with no take-over.
  EXPECT_LT(interface, eps * (mpm_cells + grown_cells) * far_end);
}

// The bar's far field as a homogenised honeycomb core (the study panel's cells, D = 3 mm,
// t = 0.05 mm, of the bar's material) sheared transversely and stretched through its thickness,
// u = (gamma z, 0, eps z): its points take the stress of their walls (coupling/zone_growth.hpp),
// a third of them in each of the three wall directions.
//  - Each point: sigma_zz = E eps, tau = G gamma t_x along its wall, so sigma_xz = G gamma t_x^2,
//    sigma_yz = G gamma t_x t_y; its volume V0 (1 + (1 - 2 nu) eps).
//  - Averaged over the core (the points hold the walls' volume, rho*/rho_s of the cells'), the
//    walls give the core's sigma_zz = E3 eps exactly and its sigma_xz = G13 gamma (1 - t/(2D)):
//    Voigt's average of the walls against Kelsey's G13 = G_s t/D (fem/orthotropic.hpp).
//  - The energy carried over is the walls', V rho*/rho_s 1/2 (E eps^2 + G gamma^2 / 2), against
//    the cells' V 1/2 (C33 eps^2 + G13 gamma^2), 2.5% more; the points started unstressed
//    before, carrying none of it. Without the walls' directions the take-over refuses, before it
//    changes anything.
TEST(ZoneGrowth, TakeOverGivesTheCoresPointsTheirWallsStress) {
  mpm::test::Threads one(1);
  const double D = 3e-3, t = 0.05e-3;
  const fem::Orthotropic core = fem::honeycomb_core(E, nu, D, t);
  const double solidity = fem::honeycomb_core_solidity(D, t), C33 = fem::stiffness(core)[2];
  fem::LayeredMesh m;
  m.lower = {mpm_cells * h, 0};
  m.x_steps.assign(fe_cells, h);
  m.y_steps.assign(2, h);
  m.layers = {{"core", 0, 2 * h, 2, core, rho * solidity, {}, {}, {}}};
  m.degree = 1;
  Bar B(std::make_unique<fem::FarField>(m));
  const double gamma = 1e-4, eps = -5e-5;
  const auto X = B.far->reference_positions();
  for (std::size_t a = 0; a < B.far->node_count(); ++a) {
    B.far->displacement()[3 * a] = gamma * X[3 * a + 2];
    B.far->displacement()[3 * a + 2] = eps * X[3 * a + 2];
  }
  B.solver->initialise();
  const int cells = 12;  // 384 points, 128 per wall direction
  NewPoints points = B.grown_points(cells);
  const std::size_t n = points.size();
  ASSERT_EQ(n % 3, 0u);
  for (double& v : points.volume) v *= solidity;
  const LayerTakeover walls{LayerTakeover::Kind::walls, E, nu};
  // No directions: refused, nothing taken.
  auto& P = B.solver->particles();
  const std::size_t n0 = P.size();
  EXPECT_THROW(B.grow(points, cells, walls), std::invalid_argument);
  EXPECT_EQ(P.size(), n0);
  EXPECT_EQ(B.far->removed_cell_count(), 0u);
  // The walls' directions, at 90, 150 and 210 degrees (normals at 0, 60, 120).
  for (std::size_t k = 0; k < n; ++k) {
    const double angle = std::numbers::pi / 2 + std::numbers::pi / 3 * static_cast<double>(k % 3);
    points.wall_direction.insert(points.wall_direction.end(), {std::cos(angle), std::sin(angle)});
  }
  const double e0 = B.solver->energy().total();
  const TakeoverReport r = B.grow(points, cells, walls);
  ASSERT_EQ(P.size(), n0 + n);
  const double G = mu;
  double volume = 0, sum_zz = 0, sum_xz = 0, sum_yz = 0;
  for (std::size_t p = 0; p < P.size(); ++p) {
    if (P.id[p] < r.first_id) continue;
    const auto k = static_cast<std::size_t>(P.id[p] - r.first_id);  // the solver may reorder points
    const double tx = points.wall_direction[2 * k], ty = points.wall_direction[2 * k + 1];
    const double* sigma = &P.stress[6 * p];
    EXPECT_NEAR(sigma[mpm::sym::zz], E * eps, 1e-9 * E * std::abs(eps));
    EXPECT_NEAR(sigma[mpm::sym::xz], G * gamma * tx * tx, 1e-9 * G * gamma);
    EXPECT_NEAR(sigma[mpm::sym::yz], G * gamma * tx * ty, 1e-9 * G * gamma);
    for (const int c : {mpm::sym::xx, mpm::sym::yy, mpm::sym::xy}) EXPECT_EQ(sigma[c], 0.0);
    EXPECT_NEAR(P.volume[p], P.volume0[p] * (1 + (1 - 2 * nu) * eps), 1e-12 * P.volume0[p]);
    volume += P.volume0[p] / solidity;
    sum_zz += sigma[mpm::sym::zz] * P.volume0[p];
    sum_xz += sigma[mpm::sym::xz] * P.volume0[p];
    sum_yz += sigma[mpm::sym::yz] * P.volume0[p];
  }
  const double cells_volume = cells * h * 4 * h * h;
  EXPECT_NEAR(volume, cells_volume, 1e-12 * cells_volume);
  EXPECT_NEAR(sum_zz / volume, core.E3 * eps, 1e-9 * core.E3 * std::abs(eps));
  EXPECT_NEAR(sum_xz / volume, core.G13 * gamma * (1 - t / (2 * D)), 1e-9 * core.G13 * gamma);
  EXPECT_NEAR(sum_yz / volume, 0.0, 1e-9 * core.G13 * gamma);
  EXPECT_NEAR(r.far_field_energy, cells_volume * 0.5 * (C33 * eps * eps + core.G13 * gamma * gamma),
              1e-9 * r.far_field_energy);
  const double walls_energy =
      cells_volume * solidity * 0.5 * (E * eps * eps + G * gamma * gamma / 2);
  EXPECT_NEAR(r.point_energy, walls_energy, 1e-9 * walls_energy);
  // What is not carried over, booked so that the total stays: the shear's t/(2D) = 0.8% of its
  // energy, and C33's excess over E3 (the core's in-plane Poisson coupling, nu12 = 0.99 with
  // nu31 = nu_s: 3.8% here, which a wall in uniaxial stress does not feel); 2.5% in all.
  EXPECT_NEAR(C33 / core.E3, 1.038, 0.001);
  EXPECT_LT(std::abs(r.far_field_energy - r.point_energy), 0.03 * r.far_field_energy);
  EXPECT_NEAR(B.solver->energy().total(), e0, 1e-9 * std::abs(e0) + 1e-12 * r.far_field_energy);
}

// The growth of the tests below: 2 mm steps, a 1 mm margin, the panel z in [-2, 0] mm, x0 and
// y0 on symmetry planes.
ZoneGrowth test_growth(const std::array<double, 4>& limit) {
  ZoneGrowth g;
  g.limit = limit;
  g.step = 2e-3;
  g.margin = 1e-3;
  g.z_lower = -2e-3;
  g.z_upper = 0.0;
  g.movable = {false, false, true, true};
  return g;
}

TEST(ZoneGrowth, GrowsTheSidesDamageReaches) {
  mpm::Particles P;
  P.add_field("damage", mpm::FieldKind::scalar, "1");
  // Reaches x1; too little damage; interior; far outside; debris 2.5 mm below the panel's rear
  // face, within y1's margin; ejecta 1.5 mm above its front face, within y1's margin.
  const double pts[][3] = {{9.5e-3, 2e-3, -1e-3}, {3e-3, 9.9e-3, -1e-3},   {1e-3, 1e-3, -1e-3},
                           {30e-3, 3e-3, -1e-3},  {5e-3, 9.5e-3, -4.5e-3}, {6e-3, 9.5e-3, 1.5e-3}};
  const double D[] = {1.0, 0.5, 1.0, 1.0, 1.0, 1.0};
  for (int k = 0; k < 6; ++k) {
    const std::size_t p = P.append(pts[k], 1e-9, 1e-6, 1, 0);
    P.field("damage")[p] = D[k];
  }
  ZoneGrowth g = test_growth({0, 0, 12e-3, 20e-3});
  const std::array<double, 4> zone{0, 0, 10e-3, 10e-3};
  const std::vector<std::int64_t> panel{1};
  EXPECT_EQ(grown_zone(P, panel, zone, g), (std::array<double, 4>{0, 0, 12e-3, 10e-3}));
  // The debris and the ejecta count once the panel's window holds them.
  ZoneGrowth deep = g;
  deep.z_lower = -4e-3;
  EXPECT_EQ(grown_zone(P, panel, zone, deep), (std::array<double, 4>{0, 0, 12e-3, 12e-3}));
  ZoneGrowth high = g;
  high.z_upper = 1e-3;
  EXPECT_EQ(grown_zone(P, panel, zone, high), (std::array<double, 4>{0, 0, 12e-3, 12e-3}));
  g.damage = 0.5;  // now the second point reaches y1 too
  EXPECT_EQ(grown_zone(P, panel, zone, g), (std::array<double, 4>{0, 0, 12e-3, 12e-3}));
  // At the limit the side stays; other bodies' damage does not count.
  EXPECT_EQ(grown_zone(P, panel, {0, 0, 12e-3, 10e-3}, g),
            (std::array<double, 4>{0, 0, 12e-3, 12e-3}));
  EXPECT_EQ(grown_zone(P, std::vector<std::int64_t>{2}, zone, g), zone);
  // The interior point reaches x0 and y0, which lie on symmetry planes and stay.
  EXPECT_EQ(grown_zone(P, panel, zone, g)[0], 0.0);
}

// With undeformed positions (a growing zone's points carry them) a damaged point counts where it
// started: a fragment torn off near the axis that flew out along the panel's rear face, within
// the z window, reaches no side; the panel's own material failed at a side does.
TEST(ZoneGrowth, AFragmentFlownOutFromTheAxisMovesNoSide) {
  mpm::Particles P;
  P.add_field("damage", mpm::FieldKind::scalar, "1");
  P.add_field(reference_position_field, mpm::FieldKind::vector, "m");
  // A core fragment from 2.1 mm off the axis, now at x1's edge 0.5 mm below the rear face; a point
  // of the panel that started at y1's edge and failed there, moved 0.3 mm outward.
  const double now[][3] = {{9.5e-3, 2e-3, -2.5e-3}, {4e-3, 10.2e-3, -1e-3}};
  const double start[][3] = {{1.5e-3, 1.5e-3, -1e-3}, {4e-3, 9.9e-3, -1e-3}};
  for (int k = 0; k < 2; ++k) {
    const std::size_t p = P.append(now[k], 1e-9, 1e-6, 1, 0);
    P.field("damage")[p] = 1.0;
    for (int d = 0; d < 3; ++d) P.field(reference_position_field)[3 * p + d] = start[k][d];
  }
  ZoneGrowth g = test_growth({0, 0, 20e-3, 20e-3});
  const std::array<double, 4> zone{0, 0, 10e-3, 10e-3};
  const std::vector<std::int64_t> panel{1};
  EXPECT_EQ(sides_reached(P, panel, zone, g), (std::array<bool, 4>{false, false, false, true}));
  EXPECT_EQ(grown_zone(P, panel, zone, g), (std::array<double, 4>{0, 0, 10e-3, 12e-3}));
  // Without X the fragment is tested where it is, and would move x1.
  mpm::Particles Q;
  Q.add_field("damage", mpm::FieldKind::scalar, "1");
  for (int k = 0; k < 2; ++k) Q.field("damage")[Q.append(now[k], 1e-9, 1e-6, 1, 0)] = 1.0;
  EXPECT_EQ(grown_zone(Q, panel, zone, g), (std::array<double, 4>{0, 0, 12e-3, 12e-3}));
}

// The far field's own torn cells reach a side from outside: a centre within the margin beyond x1
// and across the zone moves x1; one beyond the margin, one inside the zone (a cell the zone has
// not removed yet cannot be there, but it must not count) and one past the zone's corner by more
// than the margin move none.
TEST(ZoneGrowth, TheFarFieldsTornCellsJustBeyondASideReachIt) {
  const ZoneGrowth g = test_growth({0, 0, 20e-3, 20e-3});
  const std::array<double, 4> zone{0, 0, 10e-3, 10e-3};
  const std::vector<double> beyond_x1{10.25e-3, 4e-3}, too_far{11.25e-3, 4e-3},
      inside{9.75e-3, 4e-3}, past_corner{10.5e-3, 11.5e-3}, at_corner{10.5e-3, 10.5e-3};
  EXPECT_EQ(sides_reached_from_outside(beyond_x1, zone, g),
            (std::array<bool, 4>{false, false, true, false}));
  for (const auto* none : {&too_far, &inside, &past_corner})
    EXPECT_EQ(sides_reached_from_outside(*none, zone, g), (std::array<bool, 4>{}))
        << (*none)[0] << ", " << (*none)[1];
  EXPECT_EQ(sides_reached_from_outside(at_corner, zone, g),
            (std::array<bool, 4>{false, false, true, true}));
  const std::array<bool, 4> reached = sides_reached_from_outside(beyond_x1, zone, g);
  EXPECT_EQ(grown_zone(reached, zone, g), (std::array<double, 4>{0, 0, 12e-3, 10e-3}));
}

// A side at its limit that the damage reaches is held there, and reported; a side on a symmetry
// plane (which never moves) or below its limit is not, and the zone grows as before.
TEST(ZoneGrowth, ASideAtItsLimitThatDamageReachesIsHeld) {
  mpm::Particles P;
  P.add_field("damage", mpm::FieldKind::scalar, "1");
  // Reaches x1 (at its limit), y1 (below its limit) and x0 (a symmetry plane).
  const double pts[][3] = {{11.5e-3, 2e-3, -1e-3}, {5e-3, 9.5e-3, -1e-3}, {0.5e-3, 5e-3, -1e-3}};
  for (const auto& x : pts) P.field("damage")[P.append(x, 1e-9, 1e-6, 1, 0)] = 1.0;
  ZoneGrowth g = test_growth({0, 0, 12e-3, 20e-3});
  const std::array<double, 4> zone{0, 0, 12e-3, 10e-3};
  const std::vector<std::int64_t> panel{1};
  const std::array<bool, 4> reached = sides_reached(P, panel, zone, g);
  EXPECT_EQ(reached, (std::array<bool, 4>{true, false, true, true}));
  EXPECT_EQ(sides_held_at_limit(reached, zone, g),
            (std::array<bool, 4>{false, false, true, false}));
  EXPECT_EQ(grown_zone(reached, zone, g), (std::array<double, 4>{0, 0, 12e-3, 12e-3}));
  // Below its limit the same side grows and is not held.
  const std::array<double, 4> smaller{0, 0, 10e-3, 10e-3};
  P.position[0] = 9.5e-3;
  const std::array<bool, 4> below = sides_reached(P, panel, smaller, g);
  EXPECT_EQ(sides_held_at_limit(below, smaller, g), (std::array<bool, 4>{}));
  EXPECT_EQ(grown_zone(below, smaller, g), (std::array<double, 4>{0, 0, 12e-3, 12e-3}));
}

// The ring a grown zone adds tiles it: no overlap, nothing missing, no box where a side stays.
TEST(ZoneGrowth, TheRingsBoxesTileIt) {
  const std::array<double, 4> zone{0, 0, 3e-3, 3e-3}, grown{-1e-3, 0, 5e-3, 4e-3};
  const auto boxes = ring(zone, grown);
  double area = 0;
  for (const auto& r : boxes) area += (r[2] - r[0]) * (r[3] - r[1]);
  EXPECT_NEAR(area, 6e-3 * 4e-3 - 9e-6, 1e-18);
  EXPECT_EQ(boxes.size(), 3u);  // above, left, right: nothing below (y0 stays)
  EXPECT_TRUE(ring(zone, zone).empty());
}

}  // namespace
}  // namespace hvi::coupling
