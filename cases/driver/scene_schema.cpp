#include "cases/driver/scene_schema.hpp"

namespace hvi::scene {
namespace {

TableSpec run_table() {
  TableSpec t{.name = "run", .doc = "How long to simulate.", .required = true};
  t.quantity_required("end_time", dims::time, positive(), "Simulated time at which the run stops")
      .integer("max_steps", non_negative(), 0,
               "Stop after this many steps (0: no limit); a checkpoint is written so the run can "
               "be resumed");
  return t;
}

TableSpec output_table() {
  TableSpec t{.name = "output", .doc = "What is written, and how often."};
  t.optional_quantity("interval", dims::time, positive(),
                      "Simulated time between particle snapshots (default: end_time / 10)")
      .integer("energy_every", closed(1, 1e9), 10, "Steps between rows of energy.csv")
      .optional_quantity("checkpoint_interval", dims::time, positive(),
                         "Simulated time between checkpoints (default: the snapshot interval)");
  return t;
}

TableSpec grid_table() {
  TableSpec t{.name = "grid", .doc = "The background grid and the MPM scheme.", .required = true};
  t.vector_required("lower", dims::length, "Lower corner of the domain; node (0, 0, 0)")
      .vector_required("upper", dims::length,
                       "Upper corner of the domain (rounded up to a whole number of cells)")
      .quantity_required("cell_size", dims::length, positive(), "Edge of a cubic grid cell")
      .choice("shape_function", {"linear", "gimp"}, "linear",
              "Grid shape functions: linear (standard MPM, as the paper) or gimp (uGIMP)")
      .choice("scheme", {"musl", "usl", "usf"}, "musl",
              "Update scheme: musl, usl, or usf (update stress first, the paper's flowchart)")
      .number("flip", closed(0, 1), 1.0,
              "FLIP fraction of the particle velocity update (1: FLIP, as the paper; 0: PIC)")
      .number("cfl", left_open(0, 1), 0.5,
              "Courant number: dt = cfl h / max(sound speed + particle speed)")
      .optional_quantity("max_time_step", dims::time, positive(), "Upper bound on the time step");
  return t;
}

TableSpec boundary_table() {
  TableSpec t{.name = "boundary",
              .doc = "A condition on a plane of grid nodes (and all nodes beyond it). Faces "
                     "without a condition are free.",
              .array = true};
  t.choice("face", {"x-", "x+", "y-", "y+", "z-", "z+"}, std::nullopt,
           "Which side is outside: x- constrains nodes at and below the plane along x")
      .choice("type", {"fixed", "symmetry"}, std::nullopt,
              "fixed: all velocity components zero; symmetry: the normal component zero (a "
              "frictionless roller, a mirror plane)")
      .optional_quantity("position", dims::length, Range{},
                         "Coordinate of the plane; must lie on grid nodes (default: the domain "
                         "face)");
  return t;
}

TableSpec material_table() {
  TableSpec t{.name = "material", .doc = "A material, referenced by bodies through its name.",
              .array = true, .required = true};
  t.string_required("name", "Name bodies use to refer to it")
      .choice("strength", {"elastic"}, "elastic",
              "Deviatoric response: elastic (isotropic, Jaumann stress rate, no yield)")
      .quantity_required("density", dims::density, positive(), "Reference density")
      .quantity_required("youngs_modulus", dims::pressure, positive(), "Young's modulus E")
      .number("poisson_ratio", right_open(0, 0.5), 0.3, "Poisson's ratio");
  return t;
}

TableSpec body_table() {
  TableSpec sphere{.name = "sphere", .doc = "A solid sphere."};
  sphere.vector_required("center", dims::length, "Centre").quantity_required("radius", dims::length, positive(), "Radius");
  TableSpec box{.name = "box", .doc = "An axis-aligned box."};
  box.vector_required("lower", dims::length, "Lower corner").vector_required("upper", dims::length, "Upper corner");
  TableSpec cylinder{.name = "cylinder", .doc = "A solid circular cylinder along a coordinate axis."};
  cylinder.vector_required("base_center", dims::length, "Centre of the base disc")
      .choice("axis", {"x", "y", "z"}, std::nullopt, "Direction of the axis")
      .quantity_required("radius", dims::length, positive(), "Radius")
      .quantity_required("length", dims::length, positive(), "Length along the axis");

  TableSpec t{.name = "body", .doc = "A body of material points; exactly one shape sub-table.",
              .array = true, .required = true};
  t.string_required("name", "Unique name (used in messages and output)")
      .string_required("material", "Name of a [[material]]")
      .vector("velocity", dims::velocity, std::vector<double>{0, 0, 0}, "Initial velocity")
      .integer("particles_per_cell", closed(1, 8), 2,
               "Material points per grid cell along each axis")
      .table(sphere)
      .table(box)
      .table(cylinder);
  t.one_of = {"sphere", "box", "cylinder"};
  return t;
}

TableSpec make_schema() {
  TableSpec root;
  root.string("title", "", "A line describing the scene");
  root.table(run_table())
      .table(output_table())
      .table(grid_table())
      .table(boundary_table())
      .table(material_table())
      .table(body_table());
  return root;
}

}  // namespace

const TableSpec& scene_schema() {
  static const TableSpec schema = make_schema();
  return schema;
}

}  // namespace hvi::scene
