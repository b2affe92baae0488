// A far field spread over ranks (FarField::spread) steps bitwise as on one rank: a sandwich of
// failing J2 facesheets on a failing yielding core, with finite strain, Q1 and Q2, struck at its
// centre and stepped past yield, with cells removed halfway as a growing zone does. The ranks
// here are threads of this test with in-process collectives. On every rank the displacement,
// velocity, plastic work, strain energy and stable step are the one-rank bits, and rank 0's
// plastic state after gather_state_to_root is the one-rank state; the damaged cells the ranks
// report add up to the one-rank set. Each rank evaluates a part of the batches, the nodes each
// owned once.
#include <gtest/gtest.h>

#include <barrier>
#include <cmath>
#include <set>
#include <thread>
#include <utility>
#include <vector>

#include <omp.h>

#include "block.hpp"
#include "fem/core_yield.hpp"
#include "fem/far_field.hpp"

namespace hvi::fem {
namespace {

// Ranks as threads: each collective waits for all of them.
class ThreadRanks {
 public:
  explicit ThreadRanks(int size) : size_(size), sync_(size), slots_(size) {}
  FarFieldRanks of(int rank) {
    FarFieldRanks r{rank, size_, {}, {}};
    r.all_gather = [this, rank](const std::vector<double>& mine) { return gather(rank, mine); };
    r.gather_to_root = r.all_gather;
    return r;
  }

 private:
  std::vector<std::vector<double>> gather(int rank, const std::vector<double>& mine) {
    slots_[rank] = mine;
    sync_.arrive_and_wait();
    auto all = slots_;
    sync_.arrive_and_wait();  // nobody writes a slot before every rank has read them
    return all;
  }
  int size_;
  std::barrier<> sync_;
  std::vector<std::vector<double>> slots_;
};

// 12 x 6 mm of uneven elements: J2 facesheets that fail on a failing yielding core.
LayeredMesh sandwich(int degree) {
  constexpr double t = 0.5e-3, c = 3e-3;
  LayeredMesh m;
  m.lower = {0, 0};
  m.x_steps = {1e-3, 1e-3, 1e-3, 1e-3, 1e-3, 1e-3, 1e-3, 1.5e-3, 1.5e-3, 2e-3};
  m.y_steps = {1e-3, 1e-3, 2e-3, 2e-3};
  const Orthotropic face = isotropic(test::E, test::nu),
                    core = honeycomb_core(test::E, test::nu, 3e-3, 0.05e-3);
  CoreYield caps = honeycomb_core_yield(core, test::E, test::nu, test::al6061().A);
  caps.failure = honeycomb_core_failure(test::al6061_damage());
  Layer rear{"rear", 0, t, 1, face, test::rho, test::al6061(), {}, test::al6061_damage()};
  Layer mid{"core", t,    t + c, 2, core, test::rho * honeycomb_core_solidity(3e-3, 0.05e-3),
            {},     caps, {}};
  Layer front{
      "front", t + c, 2 * t + c, 1, face, test::rho, test::al6061(), {}, test::al6061_damage()};
  rear.strain_rate = front.strain_rate = true;
  m.layers = {rear, mid, front};
  m.degree = degree;
  m.finite_strain = true;
  return m;
}

// What a test compares: the state and sums after the steps.
struct Outcome {
  std::vector<double> u, v, plastic_state, damaged;
  double plastic_work = 0, strain_energy = 0, stable_step = 0;
  std::size_t owned = 0, evaluated = 0;
};

// The sandwich struck at its centre (front facesheet nodes within 2 mm, 400 m/s down), its
// x = 0 edge clamped, 40 steps; the cells of [3, 6] x [0, 2] mm removed after 20.
Outcome strike(FarField& f, const FarFieldRanks* ranks) {
  if (ranks) f.spread(*ranks);
  const auto x = f.reference_positions();
  for (std::size_t a = 0; a < f.node_count(); ++a) {
    if (x[3 * a] < 1e-12) f.fix(a, 7u);
    const double dx = x[3 * a] - 5e-3, dy = x[3 * a + 1] - 3e-3;
    if (x[3 * a + 2] > 3.9e-3 && dx * dx + dy * dy < 4e-6) f.velocity()[3 * a + 2] = -400.0;
  }
  const double dt = 0.5 * f.stable_time_step();
  Outcome o;
  for (int step = 0; step < 40; ++step) {
    if (step == 20) f.remove_cells({3e-3, 0.0, 6e-3, 2e-3});
    f.step(dt);
  }
  o.u.assign(f.displacement().begin(), f.displacement().end());
  o.v.assign(f.velocity().begin(), f.velocity().end());
  o.plastic_work = f.plastic_work();
  o.strain_energy = f.strain_energy();
  o.stable_step = f.stable_time_step();
  o.damaged = f.damaged_cell_centres(0.2);
  o.owned = f.owned_node_count();
  o.evaluated = f.evaluated_batch_count();
  f.gather_state_to_root();
  for (const auto& [name, values] : f.plastic_state())
    o.plastic_state.insert(o.plastic_state.end(), values.begin(), values.end());
  return o;
}

// The damaged cells' centres as a set of (x, y) pairs.
std::set<std::pair<double, double>> centres(const std::vector<double>& xy) {
  std::set<std::pair<double, double>> s;
  for (std::size_t k = 0; k + 1 < xy.size(); k += 2) s.insert({xy[k], xy[k + 1]});
  return s;
}

TEST(SpreadFarField, StepsBitwiseAsOneRankOnTwoAndThreeRanks) {
  omp_set_num_threads(1);
  for (const int degree : {1, 2}) {
    FarField one(sandwich(degree));
    const Outcome reference = strike(one, nullptr);
    ASSERT_GT(one.max_equivalent_plastic_strain(), 0.0) << "the strike must yield the faces";
    ASSERT_FALSE(reference.damaged.empty()) << "and damage them";
    const std::size_t batches = reference.evaluated;
    for (const int size : {2, 3}) {
      SCOPED_TRACE(::testing::Message() << "Q" << degree << ", " << size << " ranks");
      std::vector<std::unique_ptr<FarField>> fields;
      for (int r = 0; r < size; ++r) fields.push_back(std::make_unique<FarField>(sandwich(degree)));
      ThreadRanks ranks(size);
      std::vector<Outcome> out(size);
      std::vector<std::thread> threads;
      for (int r = 0; r < size; ++r)
        threads.emplace_back([&, r] {
          omp_set_num_threads(1);
          const FarFieldRanks mine = ranks.of(r);
          out[r] = strike(*fields[r], &mine);
        });
      for (auto& t : threads) t.join();
      std::size_t owned = 0, evaluated = 0;
      std::set<std::pair<double, double>> damaged;
      for (int r = 0; r < size; ++r) {
        SCOPED_TRACE(::testing::Message() << "rank " << r);
        EXPECT_EQ(out[r].u, reference.u);
        EXPECT_EQ(out[r].v, reference.v);
        EXPECT_EQ(out[r].plastic_work, reference.plastic_work);
        EXPECT_EQ(out[r].strain_energy, reference.strain_energy);
        EXPECT_EQ(out[r].stable_step, reference.stable_step);
        EXPECT_LT(out[r].evaluated, batches);  // a part of the work
        owned += out[r].owned;
        evaluated += out[r].evaluated;
        const auto mine = centres(out[r].damaged);
        damaged.insert(mine.begin(), mine.end());
      }
      EXPECT_EQ(out[0].plastic_state, reference.plastic_state);
      EXPECT_EQ(damaged, centres(reference.damaged));
      EXPECT_EQ(owned, one.node_count());
      // Only batches on a slab's edge are evaluated twice: here a third of them at most.
      EXPECT_LE(evaluated, batches + batches / 3);
    }
  }
}

}  // namespace
}  // namespace hvi::fem
