// Removing far-field cells (FarField::remove_cells, for an MPM zone that grows over them) leaves
// exactly the far field of a mesh built with that hole: the same lumped masses, internal forces,
// strain and kinetic energies and momentum at every node the two share, to round-off, in Q1 and
// Q2, elastic and with J2 facesheets and a failing core past yield. The nodes of removed cells
// only are detached: no mass, no force, at rest, and left out of the VTU output.
// FarField::sample, what the material points that take the cells over start from, reproduces
// fields the elements hold exactly (a linear displacement and velocity, Q1 and Q2), and past yield
// the J2 stress of uniaxial strain in closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include "block.hpp"
#include "fem/core_yield.hpp"
#include "fem/far_field.hpp"

namespace hvi::fem {
namespace {

constexpr double t = 0.5e-3, c = 4e-3;  // facesheet and core thickness

// A sandwich [0, 12 mm]^2 of uneven elements; J2 faces that fail and a failing core when
// `plastic` (Table 4's Al6061 faces from block.hpp, the walls' yield at its A).
LayeredMesh sandwich(int degree, bool plastic, std::optional<std::array<double, 4>> hole) {
  LayeredMesh m;
  m.lower = {0, 0};
  m.x_steps = {2e-3, 2e-3, 2e-3, 3e-3, 3e-3};
  m.y_steps = {2e-3, 2e-3, 2e-3, 2e-3, 4e-3};
  const Orthotropic face = isotropic(test::E, test::nu),
                    core = honeycomb_core(test::E, test::nu, 3e-3, 0.05e-3);
  Layer rear{"rear", 0, t, 1, face, test::rho, {}, {}, {}};
  Layer mid{"core", t,  t + c, 2, core, test::rho * honeycomb_core_solidity(3e-3, 0.05e-3),
            {},     {}, {}};
  Layer front{"front", t + c, 2 * t + c, 1, face, test::rho, {}, {}, {}};
  if (plastic) {
    rear.plasticity = front.plasticity = test::al6061();
    rear.failure = front.failure = test::al6061_damage();
    CoreYield caps = honeycomb_core_yield(core, test::E, test::nu, test::al6061().A);
    caps.failure = honeycomb_core_failure(test::al6061_damage());
    mid.core_yield = caps;
  }
  m.layers = {rear, mid, front};
  m.degree = degree;
  m.hole = hole;
  return m;
}

// A smooth displacement (a dent of up to 0.2 mm with in-plane stretch: past yield in the faces)
// and velocity at x.
std::array<double, 3> dent(const double* x) {
  const double r2 = (x[0] * x[0] + x[1] * x[1]) / 36e-6;
  const double w = -2e-4 * std::exp(-r2);
  return {3e-3 * x[0] + 1e-3 * x[2], -2e-3 * x[1], w * (1.0 + 50.0 * x[2])};
}
std::array<double, 3> velocity(const double* x) {
  return {10.0 * x[1] / 12e-3, -5.0, 30.0 * x[0] / 12e-3};
}

// The node of `b` at each node of `a` (their positions agree to 1e-12 m).
std::vector<std::size_t> match_nodes(const FarField& a, const FarField& b) {
  auto key = [](const double* x) {
    return std::array<long long, 3>{std::llround(x[0] * 1e12), std::llround(x[1] * 1e12),
                                    std::llround(x[2] * 1e12)};
  };
  std::map<std::array<long long, 3>, std::size_t> of_b;
  const auto xb = b.reference_positions();
  for (std::size_t n = 0; n < b.node_count(); ++n) of_b[key(&xb[3 * n])] = n;
  std::vector<std::size_t> m;
  const auto xa = a.reference_positions();
  for (std::size_t n = 0; n < a.node_count(); ++n) m.push_back(of_b.at(key(&xa[3 * n])));
  return m;
}

void set_state(FarField& f) {
  const auto x = f.reference_positions();
  auto u = f.displacement();
  auto v = f.velocity();
  for (std::size_t n = 0; n < f.node_count(); ++n) {
    const auto d = dent(&x[3 * n]);
    const auto w = velocity(&x[3 * n]);
    for (int k = 0; k < 3; ++k) u[3 * n + k] = d[k], v[3 * n + k] = w[k];
  }
}

std::size_t vtu_cells(const FarField& f) {
  const auto path = std::filesystem::temp_directory_path() / "hvi_remove_cells.vtu";
  f.write_vtu(path.string());
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  const std::string text = s.str();
  const auto at = text.find("NumberOfCells=\"");
  std::filesystem::remove(path);
  return std::stoul(text.substr(at + 15));
}

TEST(RemoveCells, LeavesTheFarFieldOfAMeshBuiltWithTheHole) {
  const std::array<double, 4> hole{0.0, 0.0, 6e-3, 4e-3};  // 3 x 2 elements in plane
  for (const int degree : {1, 2})
    for (const bool plastic : {false, true}) {
      SCOPED_TRACE(::testing::Message()
                   << "degree " << degree << (plastic ? ", plastic" : ", elastic"));
      FarField holed(sandwich(degree, plastic, hole)),
          whole(sandwich(degree, plastic, std::nullopt));
      const double mass_before = [&] {
        double m = 0;
        for (const double x : whole.lumped_mass()) m += x;
        return m;
      }();
      const std::size_t batches = whole.evaluated_batch_count();
      EXPECT_EQ(whole.remove_cells(hole), whole.cell_count() - holed.cell_count());
      EXPECT_EQ(whole.remove_cells(hole), 0u);  // already removed
      // The element loops skip the batches whose cells are all out (the forces below are the
      // holed mesh's all the same).
      EXPECT_LT(whole.evaluated_batch_count(), batches);
      EXPECT_EQ(whole.removed_cell_count(), whole.cell_count() - holed.cell_count());
      set_state(holed);
      set_state(whole);
      const auto of = match_nodes(holed, whole);
      std::vector<double> fh(3 * holed.node_count()), fw(3 * whole.node_count());
      // Twice: the second force starts from the plastic state the first committed.
      for (int pass = 0; pass < 2; ++pass) {
        holed.internal_force(fh);
        whole.internal_force(fw);
      }
      double fmax = 0;
      for (const double x : fh) fmax = std::max(fmax, std::abs(x));
      ASSERT_GT(fmax, 1.0);
      std::vector<char> shared(whole.node_count(), 0);
      for (std::size_t n = 0; n < holed.node_count(); ++n) {
        const std::size_t m = of[n];
        shared[m] = 1;
        EXPECT_NEAR(whole.lumped_mass()[m], holed.lumped_mass()[n], 1e-12 * holed.lumped_mass()[n]);
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(fw[3 * m + k], fh[3 * n + k], 1e-10 * fmax);
      }
      double detached_mass = 0, detached_force = 0;
      std::size_t detached = 0;
      for (std::size_t m = 0; m < whole.node_count(); ++m) {
        if (shared[m]) continue;
        ++detached;
        detached_mass += whole.lumped_mass()[m];
        for (int k = 0; k < 3; ++k)
          detached_force = std::max(detached_force, std::abs(fw[3 * m + k]));
      }
      EXPECT_GT(detached, 0u);
      EXPECT_EQ(detached_mass, 0.0);
      EXPECT_EQ(detached_force, 0.0);
      double mass_after = 0;
      for (const double x : whole.lumped_mass()) mass_after += x;
      EXPECT_LT(mass_after, mass_before);
      EXPECT_NEAR(whole.strain_energy(), holed.strain_energy(), 1e-12 * holed.strain_energy());
      EXPECT_NEAR(whole.kinetic_energy(), holed.kinetic_energy(), 1e-12 * holed.kinetic_energy());
      EXPECT_NEAR(whole.plastic_work(), holed.plastic_work(),
                  1e-12 * std::max(1.0, holed.plastic_work()));
      if (plastic) {
        EXPECT_GT(holed.max_equivalent_plastic_strain(), 0.0);
        EXPECT_NEAR(whole.max_equivalent_plastic_strain(), holed.max_equivalent_plastic_strain(),
                    1e-12);
        EXPECT_NEAR(whole.max_core_plastic_strain(), holed.max_core_plastic_strain(), 1e-12);
      }
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(whole.momentum()[k], holed.momentum()[k], 1e-12 * holed.kinetic_energy());
      EXPECT_EQ(vtu_cells(whole), vtu_cells(holed));

      // A step of each: the shared nodes move alike, the detached ones stay at rest.
      const double dt = 0.5 * holed.stable_time_step();
      holed.step(dt);
      whole.step(dt);
      for (std::size_t n = 0; n < holed.node_count(); ++n)
        for (int k = 0; k < 3; ++k)
          EXPECT_NEAR(whole.velocity()[3 * of[n] + k], holed.velocity()[3 * n + k], 1e-9);
      for (std::size_t m = 0; m < whole.node_count(); ++m) {
        if (shared[m]) continue;
        for (int k = 0; k < 3; ++k) EXPECT_EQ(whole.velocity()[3 * m + k], 0.0);
      }
    }
}

// A far field whose every cell a zone took over costs nothing: its element loops visit no batch,
// and it holds no mass, force or energy.
TEST(RemoveCells, AFarFieldTakenOverWhollyVisitsNoCell) {
  for (const bool plastic : {false, true}) {
    FarField f(sandwich(1, plastic, std::nullopt));
    set_state(f);
    EXPECT_GT(f.evaluated_batch_count(), 0u);
    EXPECT_EQ(f.remove_cells({-1.0, -1.0, 1.0, 1.0}), f.cell_count());
    EXPECT_EQ(f.evaluated_batch_count(), 0u);
    std::vector<double> force(3 * f.node_count(), 1.0);
    f.internal_force(force);
    for (const double x : force) EXPECT_EQ(x, 0.0);
    for (const double m : f.lumped_mass()) EXPECT_EQ(m, 0.0);
    EXPECT_EQ(f.strain_energy(), 0.0);
    EXPECT_EQ(f.kinetic_energy(), 0.0);
  }
}

// u = A X + c and v = B X + w: every element holds them exactly, so a sample anywhere gives them,
// the strain sym(A) and the stress C : sym(A) of the point's layer.
TEST(FarFieldSample, GivesTheFieldsTheElementsHold) {
  const std::array<std::array<double, 3>, 3> A{
      {{1e-3, 2e-4, -1e-4}, {3e-4, -5e-4, 2e-4}, {-2e-4, 1e-4, 4e-4}}};
  for (const int degree : {1, 2}) {
    SCOPED_TRACE(::testing::Message() << "degree " << degree);
    FarField f(sandwich(degree, false, std::array<double, 4>{0.0, 0.0, 2e-3, 2e-3}));
    test::deform(f, A, {1e-5, -2e-5, 3e-5});
    const auto x = f.reference_positions();
    auto v = f.velocity();
    for (std::size_t a = 0; a < f.node_count(); ++a)
      for (int i = 0; i < 3; ++i) v[3 * a + i] = 5.0 * i - 200.0 * x[3 * a + (i + 1) % 3];
    // In the rear sheet, the core, the front sheet; on a shared face; in the hole; outside.
    const std::vector<double> points{7.1e-3,  3.3e-3, 0.2e-3, 5.5e-3, 9.9e-3, 2.0e-3,
                                     11.0e-3, 1.0e-3, 4.9e-3, 4e-3,   6e-3,   t,
                                     1e-3,    1e-3,   2e-3,   13e-3,  1e-3,   2e-3};
    const auto r = f.sample(points);
    const std::array<int, 6> layers{0, 1, 2, 1, -1, -1};  // on a face: the cell above
    for (std::size_t s = 0; s < r.size(); ++s) {
      ASSERT_EQ(r[s].layer, layers[s]) << "point " << s;
      if (r[s].layer < 0) continue;
      const double* X = &points[3 * s];
      for (int i = 0; i < 3; ++i) {
        const double u = std::array<double, 3>{1e-5, -2e-5, 3e-5}[i] + A[i][0] * X[0] +
                         A[i][1] * X[1] + A[i][2] * X[2];
        EXPECT_NEAR(r[s].displacement[i], u, 1e-15);
        EXPECT_NEAR(r[s].velocity[i], 5.0 * i - 200.0 * X[(i + 1) % 3], 1e-12);
      }
      const Sym eps{A[0][0],
                    A[1][1],
                    A[2][2],
                    0.5 * (A[1][2] + A[2][1]),
                    0.5 * (A[0][2] + A[2][0]),
                    0.5 * (A[0][1] + A[1][0])};
      for (int k = 0; k < 6; ++k) EXPECT_NEAR(r[s].strain[k], eps[k], 1e-14);
      // sigma = C : eps with engineering shears, from fem::stiffness (orthotropic.hpp).
      // (The mesh held by name: a reference into the temporary's layers outlived it.)
      const LayeredMesh mesh = sandwich(degree, false, std::nullopt);
      const auto C = stiffness(mesh.layers[static_cast<std::size_t>(r[s].layer)].elasticity);
      const Sym sigma{C[0] * eps[0] + C[3] * eps[1] + C[4] * eps[2],
                      C[3] * eps[0] + C[1] * eps[1] + C[5] * eps[2],
                      C[4] * eps[0] + C[5] * eps[1] + C[2] * eps[2],
                      2 * C[6] * eps[3],
                      2 * C[7] * eps[4],
                      2 * C[8] * eps[5]};
      for (int k = 0; k < 6; ++k) EXPECT_NEAR(r[s].stress[k], sigma[k], 1e-9 * C[0] * 1e-3);
      EXPECT_EQ(r[s].plastic_strain, 0.0);
    }
    // A removed cell samples as outside.
    f.remove_cells({6e-3, 0.0, 9e-3, 2e-3});
    EXPECT_EQ(f.sample(std::vector<double>{7.1e-3, 1e-3, 0.2e-3})[0].layer, -1);
  }
}

// Uniaxial strain e = 1% along x in a J2 block: past yield the sample's stress is the closed
// form's (block.hpp), its alpha the consistency condition's, within the return's tolerance.
TEST(FarFieldSample, GivesTheJ2StressPastYield) {
  for (const int degree : {1, 2}) {
    FarField f(test::block(degree, true));
    const double e = 0.01;
    std::vector<double> force(3 * f.node_count());
    for (int k = 1; k <= 10; ++k) {  // loaded in steps, as a run would
      test::deform(f, {{{e * k / 10, 0, 0}, {0, 0, 0}, {0, 0, 0}}});
      f.internal_force(force);
    }
    const test::Uniaxial closed{test::mu, test::E / (3 * (1 - 2 * test::nu)), test::al6061()};
    const double alpha = closed.alpha_on_loading(e);
    ASSERT_GT(alpha, 0.0);
    const auto r = f.sample(std::vector<double>{0.3 * test::L, 0.7 * test::L, 0.45 * test::L});
    ASSERT_EQ(r[0].layer, 0);
    EXPECT_NEAR(r[0].plastic_strain, alpha, 1e-9 * alpha);
    EXPECT_NEAR(r[0].stress[0], closed.sxx(e, alpha), 1e-9 * closed.sxx(e, alpha));
    EXPECT_NEAR(r[0].stress[1], closed.syy(e, alpha), 1e-9 * closed.sxx(e, alpha));
    EXPECT_NEAR(r[0].stress[2], closed.syy(e, alpha), 1e-9 * closed.sxx(e, alpha));
  }
}

}  // namespace
}  // namespace hvi::fem
