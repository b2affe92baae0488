#pragma once
// The nodal part of the step (paper Sec. 2.3, step 5): momentum -> velocity, force -> velocity
// increment, on every node that carries mass.
#include "mpm/grid.hpp"

namespace hvi::mpm {

// For each node with mass: if `velocity`, p <- p / m (v_I); if `increment`, f <- dt f / m (dv_I).
// Nodes without mass are zeroed.
void update_nodes(SparseGrid& grid, bool velocity, bool increment, double dt);

// q <- q / m on every node with mass (MUSL: remapped momentum -> velocity).
void update_remapped(SparseGrid& grid);

}  // namespace hvi::mpm
