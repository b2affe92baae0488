#pragma once
// Checks and operations on closed triangle surfaces (CGAL Polygon Mesh Processing behind plain
// types): is it closed, manifold, consistently and outward oriented, free of self-intersections,
// does it bound a volume, and what volume; clipping by a box; binary STL output.
#include <cstddef>
#include <string>

#include "geometry/solid.hpp"

namespace hvi::geometry {

struct SurfaceCheck {
  std::size_t triangles = 0;
  std::size_t border_edges = 0;        // edges with one triangle: the surface has holes
  std::size_t non_manifold_edges = 0;  // edges with more than two triangles
  std::size_t misoriented_edges = 0;   // edges whose two triangles run the same way along them
  bool non_manifold_vertex = false;    // a vertex whose triangles do not form one fan
  std::size_t degenerate_triangles = 0;
  std::size_t self_intersections = 0;  // pairs of intersecting triangles (not neighbours)
  bool outward = false;                // oriented with normals pointing out
  bool bounds_volume = false;          // PMP::does_bound_a_volume
  double volume = 0.0;                 // enclosed volume (PMP::volume), m^3; < 0 when inside-out
  bool ok() const { return problem().empty(); }
  // "" when the surface is a valid solid boundary; else what is wrong, with the counts.
  std::string problem() const;
};

SurfaceCheck check_surface(const TriangleMesh& mesh);

// The part of the closed solid bounded by `mesh` that lies inside `box`, as a closed surface
// (PMP::clip with clip_volume). Throws std::runtime_error if CGAL cannot clip it.
TriangleMesh clip_surface(const TriangleMesh& mesh, const Bounds& box);

// The same for a convex solid, without CGAL: each triangle is cut by each plane of the box
// (vertices exactly on a plane stay where they are, so a symmetric mesh cut on its mirror plane
// gives exactly its half), and each cut is closed by a fan of triangles around the centroid of
// the cut outline.
TriangleMesh clip_convex_surface(const TriangleMesh& mesh, const Bounds& box);

// Signed volume enclosed by a closed, consistently oriented surface (sum of signed tetrahedra).
double enclosed_volume(const TriangleMesh& mesh);

// Binary STL (float32 coordinates, as the format defines). Throws std::runtime_error.
void write_stl(const TriangleMesh& mesh, const std::string& path);

}  // namespace hvi::geometry
