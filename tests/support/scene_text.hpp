#pragma once
// The pieces small test scenes are made of, so that each test writes only what it is about.
#include <string>

namespace hvi::test {

// [run] and [grid]: a box from `lower` to `upper`, TOML arrays of lengths
// (R"(["0 mm", "0 mm", "0 mm"])").
inline std::string run_and_grid(const std::string& end_time, const std::string& lower,
                                const std::string& upper, const std::string& cell_size) {
  return "\n[run]\nend_time = \"" + end_time + "\"\n[grid]\nlower = " + lower +
         "\nupper = " + upper + "\ncell_size = \"" + cell_size + "\"\n";
}

// A [[material]] named `name` with every parameter from the library's `library`.
inline std::string library_material(const std::string& name, const std::string& library) {
  return "[[material]]\nname = \"" + name + "\"\nlibrary = \"" + library + "\"\n";
}

// A linear elastic aluminium (2.7 g/cm^3, 70 GPa, nu = 0.33) named `name`.
inline std::string elastic_aluminium(const std::string& name) {
  return "[[material]]\nname = \"" + name +
         "\"\ndensity = \"2.7 g/cm^3\"\nyoungs_modulus = \"70 GPa\"\npoisson_ratio = 0.33\n";
}

// A [[measure]] of kind "displacement" (a probe) at `point`, a TOML array of lengths, along z.
inline std::string z_probe(const std::string& name, const std::string& point) {
  return "[[measure]]\nname = \"" + name + "\"\nkind = \"displacement\"\npoint = " + point +
         "\naxis = \"z\"\n";
}

// The paper's study alloys under their library names: Al6061 (facesheets, projectile) and
// Al5052 (core).
inline std::string study_materials() {
  return library_material("Al6061", "Al6061") + library_material("Al5052", "Al5052");
}

// A [[panel]] with the study's sheets (0.5 mm), walls (0.05 mm) and 3 mm cells, on a blank line
// of its own; `more` holds further keys, a line each ("top = \"0 mm\"\n").
struct PanelText {
  std::string name = "p";
  std::string front = "Al6061", core = "Al5052", rear = "Al6061";  // materials
  std::string core_height = "14.2 mm";
  std::string lower = R"(["-6 mm", "-6 mm"])", upper = R"(["6 mm", "6 mm"])";
  std::string more;

  std::string text() const {
    return "\n[[panel]]\nname = \"" + name + "\"\nfront_material = \"" + front +
           "\"\ncore_material = \"" + core + "\"\nrear_material = \"" + rear +
           "\"\nfront_thickness = \"0.5 mm\"\nrear_thickness = \"0.5 mm\"\n"
           "wall_thickness = \"0.05 mm\"\ncell_diameter = \"3 mm\"\ncore_height = \"" +
           core_height + "\"\nlower = " + lower + "\nupper = " + upper + "\n" + more;
  }
};

}  // namespace hvi::test
