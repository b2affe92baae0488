#pragma once
// Turns a scene into a ready solver: grid, boundary conditions, materials, and bodies sampled into
// material points. This is the one place that knows both geometry/ and mpm/.
#include <memory>

#include "cases/scene/scene.hpp"
#include "mpm/solver.hpp"

namespace hvi::driver {

// The scene's background grid.
mpm::GridGeometry grid_geometry(const scene::Scene& scene);

// The solver with its grid, conditions and materials, but no particles yet.
std::unique_ptr<mpm::Solver> make_solver(const scene::Scene& scene);

// Samples every body into material points (bodies.hpp: a lattice aligned with the grid,
// particles_per_cell points per cell and axis, finer in refinement zones, thin walls as single
// layers; volumes summing to the body's exact volume) and sets their velocity. Returns the number
// of points per body. Throws scene::SceneError for a refused surface file.
// Refuses (std::invalid_argument) bodies whose points would need more than `max_memory` bytes
// (0: the memory the machine has available) before sampling any (memory_estimate.hpp).
// Bodies that overlap at the start (a point of one inside another's solid: the overlap holds
// points of both, and its mass counts twice) are named in `warnings`, when given.
// With a share of a run spread over ranks, every rank samples every body and keeps the points
// whose id is rank modulo ranks (the first step sends each to its owner), and the memory check
// is of its share; the ids and the counts are those of one rank.
struct PointShare {
  int rank = 0, ranks = 1;
};
std::vector<std::size_t> add_bodies(const scene::Scene& scene, mpm::Solver& solver,
                                    double max_memory = 0,
                                    std::vector<std::string>* warnings = nullptr,
                                    PointShare share = {});

// With [bond]: the index of the bonded panel's core among the scene's bodies, and its points at
// the facesheets marked as the bond's interface (mpm/bond.hpp; add_bodies calls it).
std::size_t core_body(const scene::Scene& scene, std::size_t panel);
void mark_bond_interface(const scene::Scene& scene, mpm::Particles& particles);

}  // namespace hvi::driver
