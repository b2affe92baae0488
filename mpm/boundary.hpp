#pragma once
// Essential conditions on grid nodes (paper Sec. 2.3, steps 2 and 4): on an axis-aligned plane of
// grid nodes, and on every node beyond it, the constrained velocity components (and with them the
// momentum and force components) are set to zero.
//   fixed:    all three components (a rigid, sticking wall)
//   symmetry: the normal component only (a frictionless roller; a mirror plane of the model)
// A side with no condition is free: nothing is imposed.
#include <vector>

#include "mpm/grid.hpp"

namespace hvi::mpm {

enum class BoundaryType { fixed, symmetry };

struct GridBoundary {
  int axis = 0;           // 0, 1, 2 = x, y, z
  int plane = 0;          // global node index of the plane along `axis`
  bool outside_below = true;  // true: nodes with index <= plane are constrained (material above)
  BoundaryType type = BoundaryType::symmetry;
};

// Zeroes the constrained components of the nodal vectors (p, f, q) of every active node the
// conditions cover. Valid in every phase of the step, whatever the vectors hold then.
void apply_grid_conditions(SparseGrid& grid, const std::vector<GridBoundary>& conditions);

}  // namespace hvi::mpm
