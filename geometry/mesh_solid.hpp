#pragma once
// A solid bounded by a closed triangle surface: a CAD body (STL, OFF, OBJ, PLY) or any generated
// surface. The surface is checked on construction (closed, manifold, outward, no
// self-intersection, bounds a volume) and refused with a SurfaceError naming the problem; the
// inside test shoots rays through an AABB tree of the triangles (CGAL Side_of_triangle_mesh).
#include <memory>
#include <stdexcept>
#include <string>

#include "geometry/solid.hpp"

namespace hvi::geometry {

class SurfaceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// How a surface file is placed in the scene: x_scene = R (scale x_file) + translate, with
// R = Rz(rotate[2]) Ry(rotate[1]) Rx(rotate[0]) (rotations about the fixed x, then y, then z
// axes, radians). `scale` includes the file's length unit (0.001 for a file in mm).
struct Placement {
  double scale = 1.0;
  Point rotate{0.0, 0.0, 0.0};
  Point translate{0.0, 0.0, 0.0};
};

// Reads a triangle surface from STL (ASCII or binary), OFF, OBJ or PLY (by the file extension),
// merges coincident vertices, triangulates polygons and applies the placement. Throws
// SurfaceError if the file cannot be read. Does not check the surface (MeshSolid does).
TriangleMesh read_surface(const std::string& path, const Placement& placement = {});

class MeshSolid : public Solid {
 public:
  // Throws SurfaceError with check_surface()'s message if `surface` does not bound a solid.
  explicit MeshSolid(TriangleMesh surface);
  ~MeshSolid() override;
  MeshSolid(MeshSolid&&) noexcept;
  bool contains(const Point& x) const override;
  double volume() const override { return volume_; }  // PMP::volume of the surface
  Bounds bounds() const override { return bounds_; }
  TriangleMesh surface() const override { return surface_; }

 private:
  struct Impl;  // CGAL surface mesh, AABB tree and side-of-mesh functor
  std::unique_ptr<Impl> impl_;
  TriangleMesh surface_;
  double volume_ = 0.0;
  Bounds bounds_{};
};

}  // namespace hvi::geometry
