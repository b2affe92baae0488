#pragma once
// `hvi geometry SCENE --out DIR`: builds and samples every body of a scene without running it, so
// that the bodies and their material points can be checked in ParaView first. Writes
//   DIR/<body>.stl           each body's closed surface (binary STL, m), cut to its clip box
//   DIR/points.h5, .xmf      the material points: position, volume, mass, half_width, body,
//   material DIR/bodies.csv           per body: points, exact volume, sampled (raw) volume, mass
// and prints the same table with the wall time and peak memory. Nothing is written when a body
// cannot be built (a refused surface file is a scene error).
#include <filesystem>

#include "cases/scene/scene.hpp"

namespace hvi::driver {

int geometry_command(const scene::Scene& scene, const std::filesystem::path& out);

}  // namespace hvi::driver
