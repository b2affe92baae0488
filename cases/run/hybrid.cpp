#include "cases/run/hybrid.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <regex>

#include <fmt/format.h>

#include "cases/run/bodies.hpp"
#include "cases/run/build_solver.hpp"
#include "coupling/panel_far_field.hpp"
#include "mpm/io/hdf5_file.hpp"

namespace hvi::driver {

namespace fs = std::filesystem;

namespace {

// `plastic`: the material's Johnson-Cook hardening, for J2 facesheets or a yielding core's walls;
// `failing`: its Johnson-Cook damage, for failing facesheets or a failing core's walls (the scene
// checked it has them).
coupling::SolidMaterial solid(const scene::Scene& s, std::size_t body, bool plastic = false,
                              bool failing = false) {
  const auto& m = s.materials[s.bodies[body].material].models;
  return {m.youngs_modulus, m.poisson_ratio, m.density, plastic ? m.johnson_cook : std::nullopt,
          failing ? m.damage : std::nullopt};
}

// The body index of part `part` (0 front, 1 core, 2 rear) of panel `panel`.
std::size_t panel_body(const scene::Scene& s, std::size_t panel, int part) {
  for (std::size_t b = 0; b < s.bodies.size(); ++b)
    if (const auto* p = std::get_if<scene::PanelPart>(&s.bodies[b].shape))
      if (p->panel == panel && static_cast<int>(p->part) == part) return b;
  throw std::logic_error("panel body not found");
}

// Components of far-field node x held at zero: the scene's boundary planes (a node on or beyond
// one takes its condition, as grid nodes do) and clamped outer edges not on such a plane.
unsigned conditions(const double* x, const scene::Scene& s, const scene::FarFieldSettings& f,
                    double tol) {
  unsigned fixed = 0;
  bool on_plane[2][2] = {{false, false}, {false, false}};  // [axis][upper side]
  for (const auto& b : s.boundaries) {
    const bool beyond =
        b.lower_face ? x[b.axis] <= b.position + tol : x[b.axis] >= b.position - tol;
    if (beyond) fixed |= b.type == "fixed" ? 7u : 1u << b.axis;
    if (b.axis < 2)
      for (int side = 0; side < 2; ++side)
        if (std::abs(f.extent[2 * side + b.axis] - b.position) <= tol)
          on_plane[b.axis][side] = true;
  }
  if (f.clamped_edges)
    for (int d = 0; d < 2; ++d)
      for (int side = 0; side < 2; ++side)
        if (!on_plane[d][side] && std::abs(x[d] - f.extent[2 * side + d]) <= tol) fixed = 7u;
  return fixed;
}

}  // namespace

Hybrid::Hybrid(const scene::Scene& scene, mpm::Solver& solver) : scene_(scene) {
  const scene::FarFieldSettings& f = *scene.far_field;
  geometry::HoneycombPanel panel = panel_geometry(scene.panels[f.panel]);
  panel.lower = {f.extent[0], f.extent[1]};
  panel.upper = {f.extent[2], f.extent[3]};
  for (int part = 0; part < 3; ++part) panel_bodies_[part] = panel_body(scene, f.panel, part);
  pattern_.emplace(panel);
  coupling::PanelFarFieldSpec& spec = spec_;
  spec.front = solid(scene, panel_bodies_[0], f.plastic_faces, f.failing_faces);
  spec.core_wall = solid(scene, panel_bodies_[1], f.yielding_core, f.failing_core);
  spec.rear = solid(scene, panel_bodies_[2], f.plastic_faces, f.failing_faces);
  spec.zone = f.zone;
  if (f.grow) {
    spec.growth_limit = f.grow->limit;
    coupling::ZoneGrowth g;
    g.limit = f.grow->limit;
    g.step = f.grow->step;
    g.margin = f.grow->margin;
    g.damage = f.grow->damage;
    g.z_lower = panel.rear_box().lower[2];
    g.z_upper = panel.front_box().upper[2];
    // A side on the panel's edge (a symmetry plane of a half or quarter model) stays.
    for (int side = 0; side < 4; ++side) g.movable[side] = f.zone[side] != f.extent[side];
    growth_ = g;
  }
  spec.band_elements = f.band_elements;
  spec.ratio = f.growth;
  spec.max_element = f.max_element;
  spec.core_elements = f.core_elements;
  spec.face_elements = f.face_elements;
  spec.finite_strain = f.finite_strain;
  spec.strain_rate = f.strain_rate;
  spec.yielding_core = f.yielding_core;
  spec.failing_core = f.failing_core;
  plastic_faces_ = f.plastic_faces;
  failing_faces_ = f.failing_faces;
  yielding_core_ = f.yielding_core;
  failing_core_ = f.failing_core;
  const mpm::GridGeometry grid = grid_geometry(scene);
  far_field_ =
      std::make_unique<fem::FarField>(coupling::panel_far_field_mesh(panel, spec, grid), 1);
  const auto x = far_field_->reference_positions();
  const double tol = 1e-9 * scene.grid.cell_size;
  for (std::size_t a = 0; a < far_field_->node_count(); ++a)
    if (const unsigned c = conditions(&x[3 * a], scene, f, tol)) {
      far_field_->fix(a, c);
      ++fixed_nodes_;
    }
  coupling_ = std::make_unique<coupling::FarFieldCoupling>(
      *far_field_, grid, coupling::panel_interface_band(spec, grid), scene.grid.flip, f.safety);
  if (growth_) {
    coupling_->enable_growth();
    solver.particles().add_field(coupling::reference_position_field, mpm::FieldKind::vector, "m");
  }
  solver.add_coupling(coupling_.get());
}

void Hybrid::record_reference_positions(mpm::Solver& solver) const {
  if (!growth_) return;
  mpm::Particles& P = solver.particles();
  P.field(coupling::reference_position_field) = P.position;
}

std::string Hybrid::describe() const {
  const fem::FarField& f = *far_field_;
  const char* faces = failing_faces_   ? ", failing J2 facesheets"
                      : plastic_faces_ ? ", J2 facesheets"
                                       : "";
  const char* core = failing_core_ ? ", failing core" : yielding_core_ ? ", yielding core" : "";
  std::string text = fmt::format(
      "far field: {} nodes, {} elements (trilinear{}{}{}{}), {} tied to grid nodes ({} exactly), "
      "{} with conditions; stable step {:.4g} s; {:.1f} MB",
      f.node_count(), f.cell_count(), f.finite_strain() ? ", finite strain" : "", faces,
      spec_.strain_rate ? " at their strain rate" : "", core, coupling_->tied_node_count(),
      coupling_->exact_node_count(), fixed_nodes_, f.stable_time_step(), f.bytes() / 1e6);
  if (f.owned_node_count() < f.node_count())  // spread over ranks
    text += fmt::format("; this rank owns {} of its nodes and evaluates {} cell batches",
                        f.owned_node_count(), f.evaluated_batch_count());
  return text;
}

std::string Hybrid::nodes_file(std::int64_t step) {
  return fmt::format("far_field/nodes_{:06d}.h5", step);
}

void Hybrid::write_snapshot(const fs::path& dir, std::int64_t step, double time) {
  fs::create_directories(dir / "far_field");
  const std::string file = fmt::format("far_field/far_field_{:06d}.vtu", step);
  far_field_->write_vtu((dir / file).string());
  snapshots_.emplace_back(time, file);
  fem::FarField::write_pvd((dir / "far_field.pvd").string(), snapshots_);

  const fem::FarField& f = *far_field_;
  mpm::io::Hdf5File nodes((dir / nodes_file(step)).string(), mpm::io::Hdf5File::Mode::create);
  nodes.write("reference_position", f.reference_positions().data(), f.node_count(), 3);
  nodes.write("displacement", f.displacement().data(), f.node_count(), 3);
  nodes.write("lumped_mass", f.lumped_mass().data(), f.node_count(), 1);
  nodes.write_attribute("time", time);
  nodes.write_attribute("step", step);
}

void Hybrid::restore_zone() {
  if (growth_ && coupling_->band().zone != spec_.zone) {
    // The checkpoint gave the band of the grown zone: the far field gives up its cells again.
    spec_.zone = coupling_->band().zone;
    const coupling::InterfaceBand band = coupling_->band();
    far_field_->remove_cells(band.zone);
    coupling_->retie(band);
  }
}

void Hybrid::resume(const fs::path& dir, std::int64_t last_step) {
  restore_zone();
  // far_field.pvd lists <DataSet timestep="t" ... file="far_field/far_field_<step>.vtu"/>.
  std::ifstream in(dir / "far_field.pvd");
  const std::regex entry(R"re(timestep="([^"]+)".*file="(far_field/far_field_(\d+)\.vtu)")re");
  std::string line;
  std::smatch m;
  snapshots_.clear();
  while (std::getline(in, line))
    if (std::regex_search(line, m, entry)) {
      if (std::stoll(m[3].str()) <= last_step)
        snapshots_.emplace_back(std::stod(m[1].str()), m[2].str());
      else {
        fs::remove(dir / m[2].str());
        fs::remove(dir / nodes_file(std::stoll(m[3].str())));
      }
    }
}

coupling::NewPoints Hybrid::sample_ring(const std::vector<std::array<double, 4>>& boxes,
                                        const mpm::Solver& solver) const {
  coupling::NewPoints points;
  auto append = [](auto& to, const auto& from) { to.insert(to.end(), from.begin(), from.end()); };
  for (const auto& box : boxes)
    for (const std::size_t b : panel_bodies_) {
      // The body's clip in a hybrid is the zone cut by the panel's clip: keep its z range.
      const auto& clip = *scene_.bodies[b].clip;
      const geometry::Bounds cut{{box[0], box[1], clip.lower[2]}, {box[2], box[3], clip.upper[2]}};
      const geometry::PointSet set = sample_body(scene_, b, *make_body_solid(scene_, b, cut));
      const std::size_t material = scene_.bodies[b].material;
      append(points.position, set.position);
      append(points.volume, set.volume);
      append(points.half_width, set.half_width);
      // The core's points are its walls': each takes its wall's direction.
      for (std::size_t k = 0; k < set.size(); ++k) {
        const geometry::Point2 t = b == panel_bodies_[1]
                                       ? pattern_->wall_direction(pattern_->wall_family(
                                             {set.position[3 * k], set.position[3 * k + 1]}))
                                       : geometry::Point2{0.0, 0.0};
        points.wall_direction.insert(points.wall_direction.end(), {t[0], t[1]});
      }
      points.density.insert(points.density.end(), set.size(),
                            solver.materials()[material]->reference_density());
      points.body.insert(points.body.end(), set.size(), static_cast<std::int64_t>(b));
      points.material.insert(points.material.end(), set.size(),
                             static_cast<std::int64_t>(material));
    }
  // Half-widths only when every body has them (GIMP domains of the sampler's points).
  if (points.half_width.size() != 3 * points.size()) points.half_width.clear();
  return points;
}

std::optional<coupling::TakeoverReport> Hybrid::grow(mpm::Solver& solver) {
  if (!growth_) return std::nullopt;
  const std::array<double, 4> zone = coupling_->band().zone;
  const std::vector<std::int64_t> bodies(panel_bodies_.begin(), panel_bodies_.end());
  // The panel's points damaged at a side, or the far field's own cells torn just beyond it.
  // Spread, each rank's points and the far-field cells it reports, OR-ed over the ranks.
  std::array<bool, 4> reached = coupling::sides_reached(solver.particles(), bodies, zone, *growth_);
  const std::array<bool, 4> outside = coupling::sides_reached_from_outside(
      far_field_->damaged_cell_centres(growth_->damage), zone, *growth_);
  for (int side = 0; side < 4; ++side) reached[side] = reached[side] || outside[side];
  if (mpm::Communicator* comm = solver.communicator()) {
    const std::vector<double> mine(reached.begin(), reached.end());
    for (const auto& from : comm->all_gather(mine))
      for (int side = 0; side < 4; ++side) reached[side] = reached[side] || from.at(side) != 0.0;
  }
  const std::array<bool, 4> held = coupling::sides_held_at_limit(reached, zone, *growth_);
  if (std::find(held.begin(), held.end(), true) != held.end()) {
    if (held_at_limit_.steps++ == 0) held_at_limit_.first_time = solver.time();
    held_at_limit_.last_time = solver.time();
    for (int side = 0; side < 4; ++side)
      held_at_limit_.sides[side] = held_at_limit_.sides[side] || held[side];
  }
  const std::array<double, 4> grown = coupling::grown_zone(reached, zone, *growth_);
  if (grown == zone) return std::nullopt;
  // Spread over ranks, rank 0 adds them all, from the far field's state there; the next step
  // sends each to its rank.
  coupling_->gather_to_root();
  coupling::NewPoints points =
      solver.rank() == 0 ? sample_ring(coupling::ring(zone, grown), solver) : coupling::NewPoints{};
  spec_.zone = grown;
  // The far field's layers: rear, core, front; the facesheets carry their stress over, the
  // homogenised core's points take its walls' (coupling/zone_growth.hpp).
  using Kind = coupling::LayerTakeover::Kind;
  const coupling::LayerTakeover solid{Kind::solid, 0.0, 0.0};
  const coupling::LayerTakeover walls{Kind::walls, spec_.core_wall.youngs_modulus,
                                      spec_.core_wall.poisson_ratio};
  const auto report = coupling::take_over(
      *coupling_, *far_field_, solver, points,
      coupling::panel_interface_band(spec_, grid_geometry(scene_)), {solid, walls, solid});
  last_points_ = std::move(points.position);
  return report;
}

void Hybrid::save(std::map<std::string, double>& extras) const {
  if (!growth_) return;
  const LimitRecord& r = held_at_limit_;
  extras["zone_limit_steps"] = static_cast<double>(r.steps);
  extras["zone_limit_first_time"] = r.first_time;
  extras["zone_limit_last_time"] = r.last_time;
  extras["zone_limit_sides"] = r.sides[0] + 2 * r.sides[1] + 4 * r.sides[2] + 8 * r.sides[3];
}

void Hybrid::load(const std::map<std::string, double>& extras) {
  const auto steps = extras.find("zone_limit_steps");
  if (!growth_ || steps == extras.end())
    return;  // a checkpoint from before hvi kept the record: none so far
  LimitRecord& r = held_at_limit_;
  r.steps = static_cast<std::int64_t>(steps->second);
  r.first_time = extras.at("zone_limit_first_time");
  r.last_time = extras.at("zone_limit_last_time");
  const auto sides = static_cast<unsigned>(extras.at("zone_limit_sides"));
  for (int side = 0; side < 4; ++side) r.sides[side] = (sides >> side) & 1u;
}

std::unique_ptr<Hybrid> make_hybrid(const scene::Scene& scene, mpm::Solver& solver) {
  if (!scene.far_field) return nullptr;
  return std::make_unique<Hybrid>(scene, solver);
}

}  // namespace hvi::driver
