#include "coupling/panel_far_field.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

namespace hvi::coupling {

namespace {

bool on_grid_plane(double x, const mpm::GridGeometry& grid, int axis) {
  const double s = (x - grid.origin[axis]) / grid.cell_size;
  return std::abs(s - std::round(s)) < 1e-9;
}

// Element lengths along one axis of the panel [a, b] with the zone [z0, z1], one grid cell long
// over the fine region [l0, l1] (the zone, or the limit of a zone that grows) and its band.
std::vector<double> axis_steps(double a, double b, double z0, double z1, double l0, double l1,
                               const PanelFarFieldSpec& s, double h, double max_element, int axis,
                               const mpm::GridGeometry& grid) {
  const char* name = axis == 0 ? "x" : "y";
  if (!(a <= z0 && z0 < z1 && z1 <= b))
    throw std::invalid_argument(std::string("far field: the MPM zone's ") + name +
                                " range must lie inside the panel's in-plane extent");
  if (!on_grid_plane(z0, grid, axis) || !on_grid_plane(z1, grid, axis))
    throw std::invalid_argument(
        std::string("far field: the MPM zone's ") + name +
        " bounds must lie on grid planes, so the interface nodes are grid nodes");
  if (!(a <= l0 && l0 <= z0 && z1 <= l1 && l1 <= b) || !on_grid_plane(l0, grid, axis) ||
      !on_grid_plane(l1, grid, axis))
    throw std::invalid_argument(
        std::string("far field: the growth limit's ") + name +
        " range must hold the zone's, lie inside the panel and on grid planes");
  // The fine region plus the band, as far as the panel reaches (a panel edge on a symmetry plane
  // may coincide with the zone's).
  const double f0 = std::max(a, l0 - s.band_elements * h),
               f1 = std::min(b, l1 + s.band_elements * h);
  auto snap = [&](double x) {
    return grid.origin[axis] + std::round((x - grid.origin[axis]) / h) * h;
  };
  return fem::graded_steps(a, b, a < f0 ? snap(f0) : a, b > f1 ? snap(f1) : b, h, s.ratio,
                           max_element, 0);
}

}  // namespace

fem::LayeredMesh panel_far_field_mesh(const geometry::HoneycombPanel& panel,
                                      const PanelFarFieldSpec& spec,
                                      const mpm::GridGeometry& grid) {
  const double h = grid.cell_size;
  const double max_element = spec.max_element > 0
                                 ? spec.max_element
                                 : 6.0 * std::min(panel.front_thickness, panel.rear_thickness);
  if (max_element < h)
    throw std::invalid_argument("far field: the largest element is smaller than a grid cell");
  // Double walls make the core's transverse shear differ along and across the ribbon (the pattern's
  // y'): the orthotropic axes must then be the panel's, the pattern turned by a multiple of 90 deg.
  const double quarter_turns = panel.rotation / (std::numbers::pi / 2);
  const bool ribbon_along_x = std::lround(quarter_turns) % 2 != 0;
  if (panel.double_walls && std::abs(quarter_turns - std::round(quarter_turns)) > 1e-9)
    throw std::invalid_argument(
        "far field: a core with double walls needs the cell pattern turned by a multiple "
        "of 90 degrees (its orthotropic axes are the panel's)");
  if (spec.core_elements < 1 || spec.face_elements < 1)
    throw std::invalid_argument("far field: need at least one element through each layer");
  fem::LayeredMesh m;
  m.degree = 1;
  m.finite_strain = spec.finite_strain;
  m.lower = {panel.lower[0], panel.lower[1]};
  const auto& z = spec.zone;
  const auto& l = spec.growth_limit ? *spec.growth_limit : z;
  m.x_steps = axis_steps(panel.lower[0], panel.upper[0], z[0], z[2], l[0], l[2], spec, h,
                         max_element, 0, grid);
  m.y_steps = axis_steps(panel.lower[1], panel.upper[1], z[1], z[3], l[1], l[3], spec, h,
                         max_element, 1, grid);
  m.hole = spec.zone;
  const auto rear = panel.rear_box(), core = panel.core_box(), front = panel.front_box();
  auto iso = [](const SolidMaterial& s) {
    return fem::isotropic(s.youngs_modulus, s.poisson_ratio);
  };
  const double solidity =
      fem::honeycomb_core_solidity(panel.cell_diameter, panel.wall_thickness, panel.double_walls);
  fem::Orthotropic core_moduli =
      fem::honeycomb_core(spec.core_wall.youngs_modulus, spec.core_wall.poisson_ratio,
                          panel.cell_diameter, panel.wall_thickness, panel.double_walls);
  if (ribbon_along_x) std::swap(core_moduli.G13, core_moduli.G23);
  std::optional<fem::CoreYield> core_yield;
  if (spec.yielding_core) {
    if (!spec.core_wall.hardening)
      throw std::invalid_argument(
          "far field: a yielding core needs its walls' yield stress (hardening)");
    core_yield =
        fem::honeycomb_core_yield(core_moduli, spec.core_wall.youngs_modulus,
                                  spec.core_wall.poisson_ratio, spec.core_wall.hardening->A);
  }
  if (spec.failing_core) {
    if (!core_yield || !spec.core_wall.damage)
      throw std::invalid_argument(
          "far field: a failing core yields and needs its walls' Johnson-Cook damage");
    core_yield->failure = fem::honeycomb_core_failure(*spec.core_wall.damage);
  }
  m.layers = {{"rear", rear.lower[2], rear.upper[2], spec.face_elements, iso(spec.rear),
               spec.rear.density, spec.rear.hardening, std::nullopt, spec.rear.damage,
               spec.strain_rate && spec.rear.hardening},
              {"core", core.lower[2], core.upper[2], spec.core_elements, core_moduli,
               spec.core_wall.density * solidity, std::nullopt, core_yield, std::nullopt},
              {"front", front.lower[2], front.upper[2], spec.face_elements, iso(spec.front),
               spec.front.density, spec.front.hardening, std::nullopt, spec.front.damage,
               spec.strain_rate && spec.front.hardening}};
  return m;
}

InterfaceBand panel_interface_band(const PanelFarFieldSpec& spec, const mpm::GridGeometry& grid) {
  return {spec.zone, spec.band_elements * grid.cell_size};
}

}  // namespace hvi::coupling
