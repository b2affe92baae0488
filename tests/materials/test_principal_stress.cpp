// The largest principal stress against Eigen's eigen-solver, and the bounded test of whether it
// reaches a limit against the eigenvalue itself.
#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <Eigen/Eigenvalues>

#include "materials/principal_stress.hpp"
#include "materials/tensor.hpp"

namespace hvi::materials {
namespace {

TEST(PrincipalStress, LargestEigenvalueMatchesEigen) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1e9, 1e9);
  for (int k = 0; k < 1000; ++k) {
    double s[6];
    for (double& c : s) c = u(rng);
    if (k % 10 == 0) s[sym::xy] = s[sym::xz] = s[sym::yz] = 0.0;  // already diagonal
    Eigen::Matrix3d M;
    M << s[0], s[1], s[2], s[1], s[3], s[4], s[2], s[4], s[5];
    const double expected =
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(M).eigenvalues().maxCoeff();
    // The trigonometric solution loses a few digits near repeated roots: 1e-9 of the scale.
    EXPECT_NEAR(max_principal(s), expected, 1e-9 * 3e9);
  }
}

// The failure test skips the eigenvalue where Gershgorin's bound already rules failure out; it
// must answer as max_principal(s) >= limit does, also for limits at the largest principal value
// itself and a few ulps either side, and for diagonal tensors (where the bound is exact).
TEST(PrincipalStress, BoundedTestAnswersAsTheEigenvalue) {
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(-1e9, 1e9);
  int reached = 0;
  for (int k = 0; k < 20000; ++k) {
    double s[6];
    for (double& c : s) c = u(rng);
    if (k % 10 == 0) s[sym::xy] = s[sym::xz] = s[sym::yz] = 0.0;
    const double sigma_1 = max_principal(s);
    for (const double limit : {u(rng), sigma_1, std::nextafter(sigma_1, 1e10),
                               std::nextafter(sigma_1, -1e10), sigma_1 * (1 + 1e-12), 5e8}) {
      ASSERT_EQ(principal_reaches(s, limit), sigma_1 >= limit) << k;
      reached += sigma_1 >= limit;
    }
  }
  EXPECT_GT(reached, 20000);  // both answers are tried
}

}  // namespace
}  // namespace hvi::materials
