#pragma once
// Essential conditions on grid nodes (paper Sec. 2.3, steps 2 and 4): on an axis-aligned plane of
// grid nodes, and on every node beyond it, the constrained velocity components (and with them the
// momentum and force components) are set to zero.
//   fixed:    all three components (a rigid, sticking wall)
//   symmetry: the normal component only (a frictionless roller; a mirror plane of the model)
// A side with no condition is free: nothing is imposed.
#include <cstddef>
#include <vector>

#include "mpm/grid.hpp"
#include "mpm/particles.hpp"

namespace hvi::mpm {

enum class BoundaryType { fixed, symmetry };

struct GridBoundary {
  int axis = 0;               // 0, 1, 2 = x, y, z
  int plane = 0;              // global node index of the plane along `axis`
  bool outside_below = true;  // true: nodes with index <= plane are constrained (material above)
  BoundaryType type = BoundaryType::symmetry;
};

// Zeroes the constrained components of the nodal vectors (p, f, q) of every active node the
// conditions cover. Valid in every phase of the step, whatever the vectors hold then.
void apply_grid_conditions(SparseGrid& grid, const std::vector<GridBoundary>& conditions);

// After the position update: a point that has crossed a symmetry plane is replaced by its mirror
// image, the point the mirrored half of the model sends back across the plane,
//   x_n <- 2 x_s - x_n,   v_n <- -v_n   (for the particle and the grid velocity),
// x_s the plane's coordinate, n its axis. Only points on or within a cell of the plane can cross:
// with cpGIMP a point lying on the plane feels the interior node's normal velocity through its
// domain, though the plane's own nodes are held at v_n = 0. The reflection keeps mass and kinetic
// energy; the point's tensors are not mirrored (it is within a fraction of a cell of the plane,
// where symmetry makes the normal shear stresses vanish). Fixed walls are left alone. Returns the
// number of points reflected.
std::size_t reflect_at_symmetry_planes(Particles& particles, const GridGeometry& geometry,
                                       const std::vector<GridBoundary>& conditions);

// A symmetry plane as the reflection sees it: its axis, coordinate and the side the material is on.
struct MirrorPlane {
  int axis;
  double position;  // m
  double side;      // +1: material above the plane, -1: below
};
std::vector<MirrorPlane> mirror_planes(const GridGeometry& geometry,
                                       const std::vector<GridBoundary>& conditions);

// The reflection of one point (position x, velocity v, grid velocity vg) at a plane it crossed.
// Returns whether it had crossed.
inline bool reflect(const MirrorPlane& m, double* x, double* v, double* vg) {
  const int d = m.axis;
  const double depth = m.side * (m.position - x[d]);  // > 0: beyond the plane
  if (!(depth > 0.0)) return false;
  x[d] = m.position + m.side * depth;
  v[d] = -v[d];
  vg[d] = -vg[d];
  return true;
}

}  // namespace hvi::mpm
