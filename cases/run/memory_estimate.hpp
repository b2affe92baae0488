#pragma once
// What a scene's points will take, estimated from its bodies' solids before any point is
// sampled: a run that would not fit is refused with the estimate and the keys that drive it,
// instead of growing until the machine runs out (and std::bad_alloc escaping a parallel loop).
#include <memory>
#include <string>
#include <vector>

#include "cases/scene/scene.hpp"
#include "geometry/solid.hpp"

namespace hvi::driver {

// Bytes a point costs in a run: the solver's fields with the hydrocode models (525 B measured on
// the demo's physics, docs/verification/benchmarks.md), its share of the grid and the sampling's
// temporary arrays.
constexpr double bytes_per_point = 600.0;

// About how many points body b's solid will be sampled into: its volume over the lattice cell
// (thin walls one layer across), plus what its refinement zones add over the part of its bounds
// they cover. Within a factor of about 2 of the count, and never far below it.
double estimated_points(const scene::Scene& scene, std::size_t body, const geometry::Solid& solid);

// The memory hvi may still take, in bytes, and what sets it: the least of what the machine has
// available (MemAvailable), what the address-space limit leaves (ulimit -v, less what hvi maps
// already) and what the control group's limit leaves (a batch job's memory, cgroup v2 memory.max
// or v1 memory.limit_in_bytes, less its use). Bytes 0 if none is known.
struct MemoryLimit {
  double bytes = 0;
  std::string what;
};
MemoryLimit available_memory();

// Throws std::invalid_argument if the bodies' points would need more than `limit` bytes (0: the
// memory available), naming the estimate, the largest body and the keys that set its spacing.
// A run spread over `ranks` holds against it one rank's share of the points.
void check_memory(const scene::Scene& scene,
                  const std::vector<std::unique_ptr<geometry::Solid>>& solids, double limit,
                  int ranks = 1);

}  // namespace hvi::driver
