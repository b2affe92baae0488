#pragma once
// Failure thresholds with scatter. A real metal's points do not fail at one strain: its flaws
// are spread, and a crack runs from the weakest. Each point's threshold (the Johnson-Cook failure
// strain, eq. 3, or the spall strength) is multiplied by its own factor k, drawn from a Weibull
// distribution of unit mean and modulus m (Weibull 1951):
//   k = (-ln U)^(1/m) / Gamma(1 + 1/m),   U uniform in (0, 1),
//   P(k' <= k) = 1 - exp(-(k Gamma(1 + 1/m))^m),
//   mean 1, variance Gamma(1 + 2/m) / Gamma(1 + 1/m)^2 - 1 (0.022 at m = 8, 0.0055 at m = 16).
// U is a hash of the point's id and a seed (SplitMix64: Steele, Lea & Flood 2014), so a point
// draws the same factor whichever thread or rank holds it, and a run is repeatable.
#include <cmath>
#include <cstdint>

namespace hvi::materials {

struct WeibullScatter {
  double modulus = 8.0;  // m
  std::uint64_t seed = 0;

  // U in (0, 1) for a point id: the top 53 bits of SplitMix64's output, offset by half a step.
  static double uniform(std::uint64_t id, std::uint64_t seed) {
    std::uint64_t z =
        id * 0x9E3779B97F4A7C15ull + seed * 0xD1B54A32D192ED03ull + 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return (static_cast<double>(z >> 11) + 0.5) * 0x1.0p-53;
  }
  double factor(std::int64_t id) const {
    const double u = uniform(static_cast<std::uint64_t>(id), seed);
    return std::pow(-std::log(u), 1.0 / modulus) / std::tgamma(1.0 + 1.0 / modulus);
  }
};

}  // namespace hvi::materials
