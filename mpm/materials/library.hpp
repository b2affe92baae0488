#pragma once
// Named parameter sets: the paper's materials (Tables 1 and 4) and three metals for verification.
// An entry holds every parameter it has data for; a scene still names the models it simulates.
#include <optional>
#include <string>
#include <vector>

#include "mpm/materials/hydro_material.hpp"

namespace hvi::mpm {

struct LibraryMaterial {
  std::string name;
  std::string source;                   // where the numbers come from
  HydroModels parameters;               // optional models filled where the source gives them
  std::optional<double> specific_heat;  // J/(kg K), for adiabatic heating
};

const std::vector<LibraryMaterial>& material_library();
const LibraryMaterial* find_library_material(const std::string& name);

}  // namespace hvi::mpm
