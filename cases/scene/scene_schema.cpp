#include "cases/scene/scene_schema.hpp"

#include <string>
#include <type_traits>

#include <fmt/format.h>

#include "cases/scene/measure_settings.hpp"
#include "cases/scene/units.hpp"

#include "materials/equation_of_state.hpp"
#include "mpm/materials/library.hpp"

namespace hvi::scene {
namespace {

std::vector<std::string> library_names() {
  std::vector<std::string> names;
  for (const auto& m : mpm::material_library()) names.push_back(m.name);
  return names;
}

TableSpec run_table() {
  TableSpec t{.name = "run", .doc = "How long to simulate.", .required = true};
  t.quantity_required("end_time", dims::time, positive(), "Simulated time at which the run stops")
      .integer("max_steps", non_negative(), 0,
               "Stop after this many steps (0: no limit); a checkpoint is written so the run can "
               "be resumed")
      .number("max_energy_growth", non_negative(), 0.5,
              "Stop with an error when the total energy exceeds the initial by this fraction (0: "
              "never): the run has gone unstable");
  return t;
}

TableSpec output_table() {
  TableSpec t{.name = "output", .doc = "What is written, and how often."};
  t.optional_quantity("interval", dims::time, positive(),
                      "Simulated time between particle snapshots (default: end_time / 10)")
      .integer("energy_every", closed(1, 1e9), 10, "Steps between rows of energy.csv")
      .boolean("energy_ledger", false,
               "Also write energy_ledger.csv: each body's energy phase by phase (the kinetic "
               "energy of the grid-to-particle update, the work of its stresses on the grid, the "
               "internal energy of the stress update, removals), so an energy balance that drifts "
               "shows where; one more gradient pass a step (docs/user/output.md)")
      .optional_quantity("checkpoint_interval", dims::time, positive(),
                         "Simulated time between checkpoints (default: the snapshot interval)")
      .integer(
          "keep_snapshots", closed(0, 1e9), 0,
          "Keep the first snapshot (t = 0) and the newest N others, deleting older ones as the run "
          "writes new ones (0: keep all); a holes measure with `history = true` measures each as "
          "it "
          "is written");
  return t;
}

TableSpec grid_table() {
  TableSpec t{.name = "grid", .doc = "The background grid and the MPM scheme.", .required = true};
  t.vector_required("lower", dims::length, "Lower corner of the domain; node (0, 0, 0)")
      .vector_required("upper", dims::length,
                       "Upper corner of the domain (rounded up to a whole number of cells)")
      .quantity_required("cell_size", dims::length, positive(), "Edge of a cubic grid cell")
      .choice(
          "shape_function", {"cpgimp", "gimp", "linear"}, "cpgimp",
          "Grid shape functions: cpgimp (GIMP whose particle domains stretch with the flow), gimp "
          "(uGIMP, fixed domains) or linear (standard MPM, the paper's; loses shock pressure to "
          "cell-crossing noise, see docs/user/materials.md)")
      .choice("scheme", {"musl", "usl", "usf"}, "musl",
              "Update scheme: musl, usl, or usf (update stress first, the paper's flowchart)")
      .number("flip", closed(0, 1), 1.0,
              "FLIP fraction of the particle velocity update (1: FLIP, as the paper; 0: PIC)")
      .choice(
          "dilatation", {"particle", "node-average"}, "particle",
          "Volume change a point follows: particle (its own, standard MPM, the paper's) or "
          "node-average (averaged through the grid nodes over the intact points of its body, "
          "with the mean stress averaged alike in the force: lifts the volumetric locking of walls "
          "a few cells thick; see docs/theory/mpm.md)")
      .boolean(
          "stencil_cache", false,
          "Keep each point's GIMP weights from the first transfer of a step to the last: the same "
          "results to the bit, 152 bytes a point; false: every transfer evaluates its own, which "
          "costs less than streaming the stored weights (docs/verification/benchmarks.md). Not "
          "used with linear shape functions or [contact]")
      .number(
          "cfl", left_open(0, 0.9), 0.5,
          "Courant number: dt = cfl h / max(sound speed + particle speed). At most 0.9: dt comes "
          "from the previous step's sound speed and a shock stiffens the material within a step")
      .optional_quantity("max_time_step", dims::time, positive(), "Upper bound on the time step");
  return t;
}

TableSpec boundary_table() {
  TableSpec t{.name = "boundary",
              .doc =
                  "A condition on a plane of grid nodes (and all nodes beyond it). Faces "
                  "without a condition are free.",
              .array = true};
  t.choice_required("face", {"x-", "x+", "y-", "y+", "z-", "z+"},
                    "Which side is outside: x- constrains nodes at and below the plane along x")
      .choice_required(
          "type", {"fixed", "symmetry"},
          "fixed: all velocity components zero; symmetry: the normal component zero (a "
          "frictionless roller, a mirror plane)")
      .optional_quantity("position", dims::length, Range{},
                         "Coordinate of the plane; must lie on grid nodes (default: the domain "
                         "face)");
  return t;
}

// A model parameter's check: its unit's dimension and its bound.
void add_parameter(TableSpec& t, const materials::ModelParameter& p) {
  using Bound = materials::ModelParameter::Bound;
  const Range range = p.bound == Bound::positive       ? positive()
                      : p.bound == Bound::non_negative ? non_negative()
                                                       : Range{};
  if (*p.si_unit)
    t.optional_quantity(p.key, parse_quantity(std::string("1 ") + p.si_unit).dim, range, p.doc);
  else
    t.number(p.key, range, std::nullopt, p.doc);
}

// The parameter table of a registered equation of state (materials/equation_of_state.hpp).
template <class Law>
TableSpec law_table(std::type_identity<Law>) {
  TableSpec t{.name = Law::table, .doc = Law::doc};
  for (const auto& p : Law::parameters) add_parameter(t, p);
  return t;
}

// Each model a material can name has its own parameter table; a parameter not given comes from
// the `library` entry. Tables of models the material does not name are refused.
// The models' parameter tables, in the order the material's keys name the models.
std::vector<TableSpec> model_tables() {
  TableSpec jc{.name = "johnson_cook", .doc = "Johnson-Cook strength parameters (paper eq. 1)."};
  jc.optional_quantity("A", dims::pressure, non_negative(), "Initial yield stress")
      .optional_quantity("B", dims::pressure, non_negative(), "Hardening modulus")
      .number("n", positive(), std::nullopt, "Hardening exponent")
      .number("C", non_negative(), std::nullopt, "Strain-rate coefficient")
      .number("m", positive(), std::nullopt, "Thermal-softening exponent")
      .optional_quantity("melt_temperature", dims::temperature, positive(), "T_melt")
      .optional_quantity("room_temperature", dims::temperature, positive(), "T_room")
      .optional_quantity("reference_strain_rate", dims::rate, positive(),
                         "Reference strain rate (1/s in the paper)");
  TableSpec damage{.name = "johnson_cook_damage",
                   .doc = "Johnson-Cook damage parameters (paper eqs. 2-3)."};
  damage.number("D1", Range{}, std::nullopt, "D1")
      .number("D2", Range{}, std::nullopt, "D2")
      .number("D3", Range{}, std::nullopt, "D3")
      .number("D4", Range{}, std::nullopt, "D4")
      .number("D5", Range{}, std::nullopt, "D5 (multiplies the homologous temperature T*)")
      .optional_quantity("reference_strain_rate", dims::rate, positive(), "Reference strain rate");
  TableSpec fracture{
      .name = "fracture_energy",
      .doc =
          "Damage evolution after initiation (materials/fracture_energy.hpp): the point softens, "
          "its flow stress and tension scaled by (1 - omega), omega growing with the work it "
          "does from then on per unit area of a one-cell band, and fails at omega = 1."};
  fracture.optional_quantity("energy", dims::fracture_energy, positive(),
                             "G_f: the energy a crack dissipates per unit area, e.g. K_c^2 / E "
                             "from the alloy's fracture toughness (required)");
  TableSpec weibull{.name = "weibull",
                    .doc =
                        "Failure thresholds with scatter (materials/weibull_scatter.hpp): each "
                        "point's Johnson-Cook failure strain and max-principal-stress limit "
                        "times its own factor, Weibull-distributed with mean 1, drawn from its "
                        "id."};
  weibull.number("modulus", positive(), std::nullopt, "m: the larger, the narrower (required)")
      .integer("seed", closed(0, 9.0e15), 0, "Another seed draws another set of factors");
  TableSpec spall{.name = "max_principal_stress", .doc = "Max-principal-stress (spall) failure."};
  spall.optional_quantity("limit", dims::pressure, positive(),
                          "sigma_max: failure when the largest principal stress reaches it");
  TableSpec tuler{.name = "tuler_butcher",
                  .doc =
                      "Tuler-Butcher (time-dependent) spall: failure when (1/tau) times the "
                      "integral of max(sigma_1/sigma_0 - 1, 0)^lambda dt reaches 1."};
  tuler
      .optional_quantity("threshold", dims::pressure, positive(),
                         "sigma_0: tension below it does no damage (default: the library "
                         "material's max-principal-stress limit)")
      .number("exponent", positive(), 2.0, "lambda")
      .optional_quantity("time", dims::time, positive(),
                         "tau = K / sigma_0^lambda: a stress held at sigma_1 fails the material "
                         "after tau / (sigma_1/sigma_0 - 1)^lambda (required)");
  TableSpec erosion{.name = "compression_erosion",
                    .doc =
                        "Erosion of points crushed beyond any physical state: they keep mass, "
                        "momentum and internal energy but carry no stress."};
  erosion.number("min_volume_ratio", open_interval(0, 1), 0.5,
                 "r_min: a point erodes when V / V0 falls below it (0.5: on its own Hugoniot, "
                 "aluminium reaches it only in an Al-on-Al impact at ~16 km/s)");
  TableSpec heating{.name = "adiabatic_heating", .doc = "Temperature rise from plastic work."};
  heating.optional_quantity("specific_heat", dims::specific_heat, positive(), "c_v")
      .number("taylor_quinney", closed(0, 1), 0.9, "Fraction of plastic work turned into heat");
  TableSpec viscosity{.name = "bulk_viscosity",
                      .doc =
                          "Artificial bulk viscosity q = rho h (linear c |tr D| + quadratic h (tr "
                          "D)^2) in compression, h the cell size."};
  viscosity.number("linear", non_negative(), 0.2, "Linear coefficient (AUTODYN's default)")
      .number("quadratic", non_negative(), 1.0, "Quadratic coefficient (AUTODYN's default)");
  std::vector<TableSpec> tables{jc};
  materials::for_each_equation_of_state([&](auto law) { tables.push_back(law_table(law)); });
  for (auto* t : {&damage, &fracture, &weibull, &spall, &tuler, &heating, &viscosity, &erosion})
    tables.push_back(*t);
  return tables;
}

TableSpec material_table(const std::vector<std::string>& library_names) {
  std::vector<std::string> library_choices = library_names;
  std::vector<std::string> eos_choices{"none"};
  std::string eos_doc;
  materials::for_each_equation_of_state([&](auto law) {
    using Law = typename decltype(law)::type;
    eos_choices.push_back(Law::name);
    eos_doc += fmt::format(" or {} ({})", Law::name, Law::summary);
  });
  TableSpec t{.name = "material",
              .doc =
                  "A material, referenced by bodies through its name. It names the models it "
                  "simulates; a model not named costs nothing.",
              .array = true,
              .required = true};
  t.string_required("name", "Name bodies use to refer to it")
      .choice("library", library_choices, std::nullopt,
              "A library material that supplies every parameter not given here")
      .optional_quantity("density", dims::density, positive(),
                         "Reference density (required without library)")
      .optional_quantity("youngs_modulus", dims::pressure, positive(),
                         "Young's modulus E (required without library)")
      .number("poisson_ratio", right_open(0, 0.5), std::nullopt,
              "Poisson's ratio (required without library)")
      .optional_quantity(
          "initial_temperature", dims::temperature, positive(),
          "Initial temperature (default: the room temperature of the strength model, else 293 K)")
      .choice("strength", {"elastic", "johnson-cook", "none"}, "elastic",
              "Deviatoric response: elastic (Jaumann stress rate, no yield), johnson-cook (eq. 1, "
              "radial return), or none (hydrodynamic)")
      .choice("eos", eos_choices, "none",
              "Pressure: none (the elastic bulk modulus E / 3(1 - 2 nu))" + eos_doc)
      .choice("viscosity", {"none", "bulk"}, "none",
              "Artificial bulk viscosity in compression (shocks)")
      .choice("damage", {"none", "johnson-cook"}, "none",
              "Damage accumulation (eqs. 2-3); failure when D reaches 1")
      .choice("damage_evolution", {"instant", "fracture-energy"}, "instant",
              "What follows damage initiation (D = 1): instant failure (the paper's), or "
              "softening until the point has dissipated [fracture_energy] per unit area of a "
              "one-cell band, so a crack's energy does not fall with the cell")
      .choice("scatter", {"none", "weibull"}, "none",
              "Scatter of the failure thresholds over the points: weibull, each point's failure "
              "strain and spall limit times its own factor of mean 1 ([weibull])")
      .choice("failure", {"none", "max-principal-stress", "tuler-butcher"}, "none",
              "Spall: max-principal-stress (instantaneous, the paper's) or tuler-butcher "
              "(time-dependent)")
      .choice("heating", {"none", "adiabatic"}, "none",
              "Temperature from plastic work (feeds the Johnson-Cook T*)")
      .choice("erosion", {"none", "compression"}, "none",
              "compression: a point crushed below min_volume_ratio loses its stress and moves as a "
              "point mass (keeps grid-squeezed thin walls from collapsing the time step)");
  for (const TableSpec& model : model_tables()) t.table(model);
  return t;
}

// The box and cylinder of a body's shape and of a refinement zone: the same keys, their own docs.
TableSpec box_table(const char* doc) {
  TableSpec box{.name = "box", .doc = doc};
  box.vector_required("lower", dims::length, "Lower corner")
      .vector_required("upper", dims::length, "Upper corner");
  return box;
}

TableSpec cylinder_table(const char* doc) {
  TableSpec cylinder{.name = "cylinder", .doc = doc};
  cylinder.vector_required("base_center", dims::length, "Centre of the base disc")
      .choice_required("axis", {"x", "y", "z"}, "Direction of the axis")
      .quantity_required("radius", dims::length, positive(), "Radius")
      .quantity_required("length", dims::length, positive(), "Length along the axis");
  return cylinder;
}

TableSpec body_table() {
  TableSpec sphere{.name = "sphere", .doc = "A solid sphere."};
  sphere.vector_required("center", dims::length, "Centre")
      .quantity_required("radius", dims::length, positive(), "Radius");
  const TableSpec box = box_table("An axis-aligned box.");
  const TableSpec cylinder = cylinder_table("A solid circular cylinder along a coordinate axis.");

  TableSpec mesh{
      .name = "mesh",
      .doc =
          "A solid bounded by a closed triangle surface from a CAD file, placed by x = "
          "R (scale x_file) + translate with R = Rz Ry Rx. A surface that is not closed, "
          "intersects itself or is inside-out is refused."};
  mesh.string_required("file",
                       "STL (ASCII or binary), OFF, OBJ or PLY file, by its extension; relative to "
                       "the scene file")
      .choice_required("unit", {"m", "cm", "mm", "um", "in"},
                       "Length unit of the file's coordinates")
      .number("scale", positive(), 1.0, "Factor applied to the coordinates after the unit")
      .vector("rotate", dims::none, std::vector<double>{0, 0, 0},
              "Rotations about x, then y, then z (angles: \"90 deg\", or radians)")
      .vector("translate", dims::length, std::vector<double>{0, 0, 0}, "Translation, applied last");

  TableSpec clip{.name = "clip",
                 .doc =
                     "Keep only the part of the body inside this box: a half or quarter model cut "
                     "on symmetry planes (pair it with [[boundary]] type = \"symmetry\")."};
  clip.vector_required("lower", dims::length, "Lower corner")
      .vector_required("upper", dims::length, "Upper corner");

  TableSpec t{.name = "body",
              .doc =
                  "A body of material points; exactly one shape sub-table (a cube is a box). A "
                  "scene needs at least one [[body]] or [[panel]].",
              .array = true};
  t.string_required("name", "Unique name (used in messages and output)")
      .string_required("material", "Name of a [[material]]")
      .vector("velocity", dims::velocity, std::vector<double>{0, 0, 0}, "Initial velocity")
      .integer("particles_per_cell", closed(1, 8), 2,
               "Material points per grid cell along each axis")
      .table(sphere)
      .table(box)
      .table(cylinder)
      .table(mesh)
      .table(clip);
  t.one_of = {"sphere", "box", "cylinder", "mesh"};
  return t;
}

// A honeycomb sandwich panel (geometry/honeycomb.hpp): three bodies <name>.front, <name>.core,
// <name>.rear, at rest.
TableSpec panel_table() {
  TableSpec clip{.name = "clip",
                 .doc =
                     "Keep only the part of the panel inside this box (a half or quarter model; "
                     "pair it with [[boundary]] type = \"symmetry\")."};
  clip.vector_required("lower", dims::length, "Lower corner")
      .vector_required("upper", dims::length, "Upper corner");
  TableSpec t{
      .name = "panel",
      .doc =
          "A honeycomb sandwich panel in the x-y plane, struck along -z (paper Section 2.1, "
          "Fig. 1): front facesheet z in [top - t_f, top], core of height S below it, rear "
          "facesheet below the core. Becomes the bodies <name>.front, <name>.core and "
          "<name>.rear.",
      .array = true};
  t.string_required("name", "Unique name; the bodies are <name>.front, <name>.core, <name>.rear")
      .string_required("front_material", "[[material]] of the front facesheet")
      .string_required("core_material", "[[material]] of the honeycomb core")
      .string_required("rear_material", "[[material]] of the rear facesheet")
      .quantity_required("front_thickness", dims::length, positive(), "t_f")
      .quantity_required("rear_thickness", dims::length, positive(), "t_r")
      .quantity_required("wall_thickness", dims::length, positive(),
                         "t_hc, the cell-wall foil thickness")
      .quantity_required("cell_diameter", dims::length, positive(),
                         "D_hc, the inscribed-circle diameter of a cell, between wall mid-surfaces")
      .quantity_required("core_height", dims::length, positive(),
                         "S, the distance between the facesheets")
      .vector_required("lower", dims::length, "Lower corner (x, y) of the in-plane extent", 2)
      .vector_required("upper", dims::length, "Upper corner (x, y) of the in-plane extent", 2)
      .quantity_required("top", dims::length, Range{}, "z of the front face")
      .number(
          "rotation", Range{}, 0.0,
          "Rotation of the cell pattern about z (angle: \"30 deg\", or radians); at 0 two walls "
          "of each cell are parallel to y")
      .vector("pattern_origin", dims::length, std::vector<double>{0, 0},
              "Where the pattern feature named by origin_at sits (x, y): usually the impact axis",
              2)
      .choice("origin_at", {"cell-center", "vertex", "wall"}, "cell-center",
              "What sits at pattern_origin: a cell centre, a wall vertex, or the middle of a wall")
      .boolean(
          "double_walls", false,
          "Walls along the ribbon direction (parallel to y before rotation) 2 t_hc thick, as in "
          "expanded honeycomb")
      .integer("particles_per_cell", closed(1, 8), 2,
               "Material points per grid cell along each axis")
      .choice(
          "thin_walls", {"auto", "lattice", "point-type"}, "auto",
          "Core sampling: point-type (one layer of points on each wall mid-surface carrying the "
          "wall's volume, the paper's eq. 7), lattice, or auto (point-type when t_hc < 2 point "
          "spacings)")
      .quantity("rear_gap", dims::length, non_negative(), 0.0,
                "Clearance between the core and the rear facesheet: the walls end this far above "
                "the sheet instead of standing on it (and sharing its grid nodes). 0: they stand "
                "on it. A gap of two cells or more is an unbonded sheet, which the walls can "
                "strike but not hold")
      .table(clip);
  return t;
}

// The hybrid (coupling/): the panel outside an in-plane zone as finite elements.
// [far_field.zone]: the MPM zone, and [far_field.zone.grow], the zone growing over the far field.
TableSpec far_field_zone_table() {
  TableSpec zone{.name = "zone",
                 .doc =
                     "The MPM zone in plane: the part of the panel that is material points. Its "
                     "bounds lie on grid planes; the grid holds it and the band beyond it.",
                 .required = true};
  TableSpec grow{
      .name = "grow",
      .doc =
          "A zone that grows over the far field, as hydrocodes turn failing elements into "
          "particles: a side moves out by `step` when a panel point that started within `margin` "
          "of "
          "it, and is within `margin` of the panel's thickness (not its debris or ejecta, nor "
          "fragments flown out from nearer the axis), has Johnson-Cook damage >= `damage` (or "
          "has failed), or when the far field's failing layers tear within `margin` beyond it, "
          "up to the limit box. The far-field "
          "cells it takes are sampled into points that start from the far field's displacement, "
          "velocity, the facesheets' stress and plastic state and the core walls' stress. "
          "Absent: the zone stays as declared."};
  grow.vector_required("lower", dims::length,
                       "x, y of the largest zone's lower corner (on grid planes)", 2)
      .vector_required("upper", dims::length,
                       "x, y of the largest zone's upper corner (on grid planes)", 2)
      .optional_quantity("step", dims::length, positive(),
                         "How far a side moves at once, a whole number of "
                         "grid cells (default 8 cells)")
      .optional_quantity(
          "margin", dims::length, positive(),
          "Damage this close to a side, and to the panel's faces, moves it (default 4 cells)")
      .number("damage", left_open(0, 1), 1.0,
              "Johnson-Cook damage D that counts as reaching the side");
  zone.vector_required("lower", dims::length, "x, y of the zone's lower corner", 2)
      .vector_required("upper", dims::length, "x, y of the zone's upper corner", 2)
      .table(grow);
  return zone;
}

TableSpec far_field_table() {
  TableSpec t{
      .name = "far_field",
      .doc =
          "The hybrid: the named [[panel]] is material points inside `zone` and finite "
          "elements (fem/: facesheets of solid bricks, the core a homogenised orthotropic "
          "solid, elastic with the materials' E, nu and density, small or finite strain, "
          "optionally J2 "
          "facesheets that may tear and a core that may yield or tear) over the rest "
          "of its in-plane extent (cut by its clip). Both share the grid nodes of a band "
          "around the zone and advance with one time step. Absent: nothing of fem/ is built."};
  t.string_required("panel", "The [[panel]] whose far field this is")
      .table(far_field_zone_table())
      .integer(
          "band_elements", closed(1, 16), 2,
          "Elements one grid cell wide beyond the zone, tied to grid nodes (the interface band)")
      .number("growth", closed(1, 2), 1.25, "Ratio of neighbouring element lengths beyond the band")
      .optional_quantity("max_element", dims::length, positive(),
                         "Largest in-plane element length (default: 6 times the thinner facesheet; "
                         "trilinear facesheets stiffen in bending as (length / thickness)^2)")
      .integer("core_elements", closed(1, 64), 8,
               "Elements through the core height (4 deflected 17% less than pure MPM 20 mm from "
               "an impact, 8 deflected 11% less; docs/verification/pure_vs_hybrid.md)")
      .integer("face_elements", closed(1, 8), 1, "Elements through each facesheet")
      .choice("plasticity", {"none", "j2", "failing"}, "none",
              "The far field's facesheets: elastic; J2 plasticity hardening as their materials' "
              "Johnson-Cook A + B eps_p^n (thermal factor 1, rate factor as `strain_rate`); or "
              "failing, J2 and torn (only "
              "compressive pressure kept) where their Johnson-Cook damage reaches 1; the core: see "
              "`core`")
      .choice(
          "core", {"elastic", "yielding", "failing"}, "elastic",
          "The far field's homogenised core: elastic; yielding, its out-of-plane normal and "
          "transverse shear stresses capped where its walls yield (their Johnson-Cook A; "
          "fem/core_yield.hpp), so the facesheets can pull away from a crushed or torn core; or "
          "failing, capped and dropped to zero where the walls' Johnson-Cook damage reaches 1")
      .choice(
          "strain_rate", {"reference", "johnson-cook"}, "reference",
          "The strain rate of the J2 facesheets' yield stress: the reference rate (eq. 1's rate "
          "factor 1 + C ln(epsdot*) at 1); or johnson-cook, that factor at each quadrature "
          "point's equivalent deviatoric strain rate, as the material points take it (and eq. 3's "
          "D4 factor at the plastic strain rate in failing facesheets)")
      .choice(
          "kinematics", {"small", "finite"}, "small",
          "The far field's strain: small (linearised, sigma = C eps) or finite (total Lagrangian "
          "Green-Lagrange strain E, S = C E, P = F S: rotations of any size give no stress)")
      .choice("edges", {"free", "clamped"}, "free",
              "The panel's outer edges (sides on a [[boundary]] plane take that condition instead)")
      .number("safety", left_open(0, 1), 0.9,
              "Fraction of the far field's computed stable step it may take");
  return t;
}

// Two velocity fields on the grid, the impactor's and the rest's, with contact between them.
TableSpec contact_table() {
  TableSpec t{
      .name = "contact",
      .doc =
          "Contact between an impactor and everything else (mpm/contact.hpp): the bodies "
          "named here move on a velocity field of their own, the rest on another; where both "
          "meet on a grid node they may not interpenetrate but may slide and separate "
          "(Bardenhagen et al. 2000, with Coulomb friction). Absent: one velocity field, "
          "bodies sharing a node move together (the paper's)."};
  t.string_list_required("bodies",
                         "The impactor's bodies (e.g. [\"projectile\"]); at least one, not all")
      .number("friction", non_negative(), 0.0,
              "Coulomb friction coefficient between the two fields");
  return t;
}

// A panel's core bonded to its facesheets, on a velocity field of its own (mpm/bond.hpp).
TableSpec bond_table() {
  TableSpec t{
      .name = "bond",
      .doc =
          "The bond between a [[panel]]'s core and its facesheets (mpm/bond.hpp): the core "
          "moves on a velocity field of its own, tied to the sheets (no slip, no separation) "
          "where its points at the sheets are still bonded; a point's bond breaks for good "
          "when its traction passes (sigma_n / normal_strength)^2 + (tau / shear_strength)^2 "
          "= 1, and from then on core and sheets meet by contact, with the sheet's normal. "
          "Elsewhere, the core meets everything else (the projectile, the debris) by contact "
          "too. Absent: walls and sheets share their grid nodes, welded (the paper's). Not "
          "with [contact]."};
  t.string_required("panel", "The [[panel]] whose core is bonded")
      .quantity_required("normal_strength", dims::pressure, positive(),
                         "S_n: the adhesive's strength in tension across the bond")
      .quantity_required("shear_strength", dims::pressure, positive(),
                         "S_s: its strength in shear along the bond")
      .quantity_required("width", dims::length, positive(),
                         "The bonded strip's width under each wall (the foil and its adhesive "
                         "fillets): the panel's flatwise strength is S_n width 2 / D_hc");
  return t;
}

// Zones where bodies are sampled with more points per cell (paper Fig. 4).
TableSpec refinement_table() {
  const TableSpec box = box_table("An axis-aligned box zone.");
  const TableSpec cylinder = cylinder_table("A circular cylinder zone along a coordinate axis.");
  TableSpec t{.name = "refinement",
              .doc =
                  "A zone sampled with factor times more points per cell along each axis (paper "
                  "Fig. 4). The grid is unchanged; a grid-aligned lattice cell whose centre is in "
                  "the zone is split into factor^3 cells.",
              .array = true};
  t.string("name", std::nullopt, "Optional name (for --set refinement.<name>.factor=...)")
      .integer("factor", closed(1, 8), 2,
               "Points per coarse spacing along each axis inside the zone (1: no refinement)")
      .string_list("bodies", {},
                   "Bodies it applies to (panel parts as <panel>.core, ...); empty: all")
      .table(box)
      .table(cylinder);
  t.one_of = {"box", "cylinder"};
  return t;
}

TableSpec make_schema() {
  TableSpec root;
  root.string("title", "", "A line describing the scene");
  root.string(
      "resolution", "",
      "Name of a [resolutions.<name>] table of the scene whose \"key.path\" = value entries are "
      "applied as overrides before the command line's --set (e.g. coarse, paper); empty: none");
  root.table(run_table())
      .table(output_table())
      .table(grid_table())
      .table(boundary_table())
      .table(material_table(library_names()))
      .table(body_table())
      .table(panel_table())
      .table(refinement_table())
      .table(far_field_table())
      .table(contact_table())
      .table(bond_table())
      .table(measure_table());
  return root;
}

}  // namespace

const TableSpec& scene_schema() {
  static const TableSpec schema = make_schema();
  return schema;
}

}  // namespace hvi::scene
