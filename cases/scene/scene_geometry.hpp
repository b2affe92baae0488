#pragma once
// Internal to the scene layer (scene.cpp): the geometry tables of a scene. [[panel]] entries become
// three bodies each; [[refinement]] zones name the bodies they refine; a [[body]] mesh file is
// resolved against the scene file's folder. Problems are appended as located diagnostics.
#include <optional>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "cases/scene/scene.hpp"

namespace hvi::scene::detail {

// The index of the [[material]] named `name`, or a message naming the defined ones.
std::optional<std::size_t> find_material(const Scene& s, const std::string& name,
                                         std::string* problem);

// Rewrites each [[body]] mesh.file as an absolute path (relative paths are relative to the folder
// of `scene_file`) so that the resolved scene, read back from a run directory, finds it too.
// A file that does not exist is an error unless `mesh_files` allows it (then it is kept as given).
void resolve_mesh_files(toml::array& bodies, const std::string& scene_file, const Validated& v,
                        MeshFiles mesh_files, std::vector<Diagnostic>& errors);
MeshShape read_mesh(const toml::table& mesh, const GridSettings& grid);
// What is wrong with a body's or a panel's clip (empty, or missing the grid), or "".
std::string clip_problem(const BoxShape& clip, const GridSettings& grid);
// The scene's panels for a message: "'a', 'b'", or "none".
std::string panel_names(const Scene& s);
// Appends <panel>.front, .core and .rear to s.bodies (after the [[body]] entries). The panel a
// [far_field] table names (`far_field`, may be null) is material points in its zone only.
void read_panels(const toml::array& panels, Scene& s, const Validated& v,
                 std::vector<Diagnostic>& errors, const toml::table* far_field);
// Fills s.far_field from the [far_field] table (after read_panels): the panel it names, its zone
// inside the panel and on grid planes, the grid holding the zone and its band. Records the
// default max_element in s.resolved.
void read_far_field(const toml::table& far_field, Scene& s, const Validated& v,
                    std::vector<Diagnostic>& errors);
void read_refinements(const toml::array& zones, Scene& s, const Validated& v,
                      std::vector<Diagnostic>& errors);

}  // namespace hvi::scene::detail
