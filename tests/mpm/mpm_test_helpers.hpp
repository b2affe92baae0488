#pragma once
// Shared set-up for the MPM core tests: a solver built by hand from lattice-sampled solids (the
// way a scene does it), per-run diagnostics, and bitwise comparison of particle arrays.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <functional>
#include <memory>
#include <numeric>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <omp.h>
#include <unistd.h>

#include "geometry/lattice_sampler.hpp"
#include "geometry/primitives.hpp"
#include "mpm/elastic.hpp"
#include "mpm/solver.hpp"

namespace hvi::mpm::test {

// Sets the OpenMP thread count for a scope and restores it after. The physics tests run on one
// thread: their scenes are small, and on a loaded machine every parallel region of a 2-thread run
// waits for a time slice (measured 50-100x slower during a parallel build). That results do not
// depend on the thread count, bit for bit, is test_determinism.cpp's job.
class Threads {
 public:
  explicit Threads(int n) : saved_(omp_get_max_threads()) { omp_set_num_threads(n); }
  ~Threads() { omp_set_num_threads(saved_); }
  Threads(const Threads&) = delete;
  Threads& operator=(const Threads&) = delete;

 private:
  int saved_;
};

using VelocityField = std::function<Vec3(const double* x)>;

inline VelocityField uniform(Vec3 v) {
  return [v](const double*) { return v; };
}

// A grid of `cells` cells of edge h whose node (0, 0, 0) sits at `origin`.
inline GridGeometry grid(Vec3 origin, double h, std::array<int, 3> cells) {
  GridGeometry g;
  g.origin = origin;
  g.cell_size = h;
  g.cells = cells;
  return g;
}

// Appends the lattice sample of `solid` (spacing = h / ppc, anchored at the grid origin so every
// cell holds the same points) as body `body` of material `material`; ids continue from the
// current particle count. Returns the number of particles added.
inline std::size_t add_body(Solver& solver, const geometry::Solid& solid, int ppc,
                            std::int64_t body, std::int64_t material,
                            const VelocityField& velocity) {
  const GridGeometry& g = solver.grid().geometry();
  const double density = solver.materials().at(material)->reference_density();
  const auto points =
      geometry::sample_lattice(solid, g.cell_size / ppc, {g.origin[0], g.origin[1], g.origin[2]});
  Particles& P = solver.particles();
  const std::size_t first = P.size();
  P.resize(first + points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    const std::size_t p = first + k;
    for (int d = 0; d < 3; ++d) P.position[3 * p + d] = points.position[3 * k + d];
    const Vec3 v = velocity(&points.position[3 * k]);
    for (int d = 0; d < 3; ++d) P.velocity[3 * p + d] = v[d];
    P.volume0[p] = P.volume[p] = points.volume[k];
    P.mass[p] = density * points.volume[k];
    P.id[p] = static_cast<std::int64_t>(p);
    P.body[p] = body;
    P.material[p] = material;
  }
  return points.size();
}

inline std::vector<std::unique_ptr<Material>> one_material(std::unique_ptr<Material> m) {
  std::vector<std::unique_ptr<Material>> v;
  v.push_back(std::move(m));
  return v;
}

// Sum of m v over the particles plus what left the domain.
inline Vec3 total_momentum(const Solver& s) {
  const EnergyReport e = s.energy();
  return {e.momentum[0] + e.removed_momentum[0], e.momentum[1] + e.removed_momentum[1],
          e.momentum[2] + e.removed_momentum[2]};
}

// Byte-wise equality of two arrays (distinguishes -0.0 from 0.0 and compares NaNs by bits).
template <class T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// Every particle field of `a` (core, extra and scratch, real and integer) has a field of the same
// name in `b` with bitwise the same contents, and `b` has no field that `a` lacks.
inline ::testing::AssertionResult identical_particles(const Particles& a, const Particles& b) {
  if (a.size() != b.size())
    return ::testing::AssertionFailure()
           << "particle counts differ: " << a.size() << " vs " << b.size();
  if (a.real_fields().size() != b.real_fields().size())
    return ::testing::AssertionFailure() << "field counts differ";
  for (const auto& f : a.real_fields()) {
    if (!b.has_field(f.name)) return ::testing::AssertionFailure() << "no field " << f.name;
    const auto& x = *f.data;
    const auto& y = b.field(f.name);
    if (!same_bytes(x, y)) {
      std::size_t k = 0;
      while (k < std::min(x.size(), y.size()) && std::memcmp(&x[k], &y[k], sizeof(double)) == 0)
        ++k;
      return ::testing::AssertionFailure()
             << "field " << f.name << " differs (sizes " << x.size() << ", " << y.size()
             << "; first difference at value " << k << ")";
    }
  }
  for (std::size_t i = 0; i < a.int_fields().size(); ++i) {
    const auto& f = a.int_fields()[i];
    if (b.int_fields()[i].name != f.name || !same_bytes(*f.data, *b.int_fields()[i].data))
      return ::testing::AssertionFailure() << "integer field " << f.name << " differs";
  }
  return ::testing::AssertionSuccess();
}

// Exact equality of the restartable state.
// Every field of every point that outlives a step, point by point (matched by id), bitwise. The
// scratch fields (the velocity gradient, the grid velocity) hold the step's intermediate values,
// which a point that changed rank after its last step does not carry.
inline ::testing::AssertionResult identical_by_id(const Particles& a, const Particles& b) {
  if (a.size() != b.size())
    return ::testing::AssertionFailure() << "counts differ: " << a.size() << " vs " << b.size();
  std::vector<std::size_t> ia(a.size()), ib(b.size());
  std::iota(ia.begin(), ia.end(), 0);
  std::iota(ib.begin(), ib.end(), 0);
  std::sort(ia.begin(), ia.end(), [&](auto x, auto y) { return a.id[x] < a.id[y]; });
  std::sort(ib.begin(), ib.end(), [&](auto x, auto y) { return b.id[x] < b.id[y]; });
  for (std::size_t k = 0; k < a.size(); ++k)
    if (a.id[ia[k]] != b.id[ib[k]]) return ::testing::AssertionFailure() << "ids differ";
  for (const auto& f : a.real_fields()) {
    if (f.scratch) continue;
    const auto& x = *f.data;
    const auto& y = b.field(f.name);
    const std::size_t nc = x.size() / a.size();
    for (std::size_t k = 0; k < a.size(); ++k)
      for (std::size_t c = 0; c < nc; ++c)
        if (std::memcmp(&x[ia[k] * nc + c], &y[ib[k] * nc + c], sizeof(double)) != 0)
          return ::testing::AssertionFailure()
                 << "field " << f.name << " of point " << a.id[ia[k]]
                 << " differs: " << x[ia[k] * nc + c] << " vs " << y[ib[k] * nc + c];
  }
  return ::testing::AssertionSuccess();
}

// The same removal events, in the same order, bitwise.
inline bool same_events(const std::vector<RemovalEvent>& a, const std::vector<RemovalEvent>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k) {
    const auto &x = a[k], &y = b[k];
    if (x.id != y.id || x.body != y.body || x.material != y.material || x.position != y.position ||
        x.velocity != y.velocity || x.mass != y.mass || x.time != y.time || x.step != y.step)
      return false;
  }
  return true;
}

inline ::testing::AssertionResult identical_state(const Solver& a, const Solver& b) {
  const SolverState &x = a.state(), &y = b.state();
  if (x.time != y.time || x.step != y.step || x.next_dt != y.next_dt)
    return ::testing::AssertionFailure() << "time, step or next_dt differ";
  const RemovedMaterial &r = x.removed, &s = y.removed;
  if (r.particles != s.particles || r.mass != s.mass || r.kinetic != s.kinetic ||
      r.internal != s.internal || r.momentum != s.momentum)
    return ::testing::AssertionFailure() << "removed-material ledgers differ";
  if (x.contact_work != y.contact_work)
    return ::testing::AssertionFailure() << "contact work differs";
  if (!same_bytes(x.ledger, y.ledger))
    return ::testing::AssertionFailure() << "energy ledgers differ";
  return ::testing::AssertionSuccess();
}

// A scratch directory unique to this process and test, removed on destruction.
class TempDir {
 public:
  explicit TempDir(const std::string& name)
      : path_(std::filesystem::temp_directory_path() /
              ("hvi_mpm_test_" + name + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// The solver of small_scene below, without particles: what a restart builds before reading the
// checkpoint.
inline std::unique_ptr<Solver> small_scene_solver(SolverSettings settings) {
  const double h = 1e-3;
  std::vector<std::unique_ptr<Material>> materials;
  materials.push_back(std::make_unique<LinearElastic>("aluminium", 2700.0, 70e9, 0.33));
  materials.push_back(std::make_unique<LinearElastic>("steel", 7850.0, 200e9, 0.29));
  return std::make_unique<Solver>(
      grid({-12 * h, -6 * h, -6 * h}, h, {24, 12, 12}), settings, std::move(materials),
      std::vector<std::string>{"left", "right", "cube"}, std::vector<GridBoundary>{});
}

// Adds the particles of small_scene (not initialised).
inline void add_small_scene_bodies(Solver& solver, double sphere_speed = 300.0) {
  const double h = 1e-3;
  // Bodies are appended in an order that mixes materials, so the initial sort has work to do.
  add_body(solver, geometry::Box({8 * h, 4 * h, 4 * h}, {10 * h, 6 * h, 6 * h}), 2, 2, 1,
           uniform({2000.0, 0.0, 0.0}));
  add_body(solver, geometry::Sphere({-3.6 * h, 0.3 * h, 0.0}, 3 * h), 2, 0, 0,
           [=](const double* x) {  // with a little shear
             return Vec3{sphere_speed, sphere_speed / 300.0 * 2e4 * x[2], 0.0};
           });
  add_body(solver, geometry::Sphere({3.6 * h, -0.3 * h, 0.0}, 3 * h), 2, 1, 0,
           uniform({-sphere_speed, 0.0, 0.0}));
}

// The small two-material scene of the reproducibility tests: two elastic aluminium spheres
// (radius 3 cells) closing at 2 x 300 m/s, and a small steel cube (2 cells, in a corner away from
// the spheres' nodes) flying at 2 km/s toward the +x face, about 0.13 cell per step, so that its
// particles leave the domain between steps ~17 and ~30, during the runs. 1 mm cells, 2 particles
// per cell per direction (~1900 particles). `sphere_speed` scales the spheres' velocities (USL
// with linear shape functions needs a gentler collision, see test_determinism.cpp).
inline std::unique_ptr<Solver> small_scene(SolverSettings settings, double sphere_speed = 300.0) {
  auto solver = small_scene_solver(settings);
  add_small_scene_bodies(*solver, sphere_speed);
  solver->initialise();
  return solver;
}

}  // namespace hvi::mpm::test
