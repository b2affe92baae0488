#pragma once
// Internal to geometry/: the CGAL types behind the plain TriangleMesh, and conversions. Included
// only by geometry/*.cpp, never by a public header, so CGAL stays inside this library.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include "geometry/solid.hpp"

namespace hvi::geometry::cgal {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point3 = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point3>;

// A consistently oriented, manifold triangle surface (check with check_surface first).
Mesh to_cgal(const TriangleMesh& m);
TriangleMesh from_cgal(const Mesh& m);  // triangulates non-triangular faces

}  // namespace hvi::geometry::cgal
