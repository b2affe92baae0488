// The far-field mesh of the paper's study panel around a quarter-model MPM zone.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>

#include "coupling/panel_far_field.hpp"

namespace hvi::coupling {
namespace {

// Table 3/4 panel (t_f = t_r = 0.5 mm, S = 14.2 mm, D_hc = 3 mm, t_hc = 0.05 mm), a quarter
// [0, 30 mm]^2 with the MPM zone [0, 9.2 mm]^2, grid cells 0.4 mm from the origin (0, 0, -16 mm).
struct StudyPanel {
  geometry::HoneycombPanel panel;
  PanelFarFieldSpec spec;
  mpm::GridGeometry grid;
  StudyPanel() {
    panel.front_thickness = panel.rear_thickness = 0.5e-3;
    panel.wall_thickness = 0.05e-3;
    panel.cell_diameter = 3e-3;
    panel.core_height = 14.2e-3;
    panel.lower = {0, 0};
    panel.upper = {30e-3, 30e-3};
    panel.top = 0;
    spec.front = spec.rear = {75e9, 0.33, 2770, {}, {}};
    spec.core_wall = {73e9, 0.33, 2680, {}, {}};
    spec.zone = {0, 0, 9.2e-3, 9.2e-3};
    grid.origin = {0, 0, -16e-3};
    grid.cell_size = 0.4e-3;
    grid.cells = {80, 80, 45};
  }
};

TEST(PanelFarField, LayersMassAndInterfaceNodesFollowThePanelAndTheGrid) {
  StudyPanel s;
  const auto mesh = panel_far_field_mesh(s.panel, s.spec, s.grid);
  ASSERT_EQ(mesh.layers.size(), 3u);
  EXPECT_DOUBLE_EQ(mesh.layers[0].z_lower, -15.2e-3);
  EXPECT_DOUBLE_EQ(mesh.layers[1].z_lower, -14.7e-3);
  EXPECT_DOUBLE_EQ(mesh.layers[2].z_lower, -0.5e-3);
  EXPECT_DOUBLE_EQ(mesh.layers[2].z_upper, 0.0);
  for (const double v : mesh.x_steps) EXPECT_LE(v, 6 * 0.5e-3 * (1 + 1e-12));
  fem::FarField f(mesh);
  // Mass: the panel's per area (faces plus the core at its solidity) times the area outside the
  // zone.
  double total = 0;
  for (const double m : f.lumped_mass()) total += m;
  const double per_area =
      2 * 2770 * 0.5e-3 + 2680 * fem::honeycomb_core_solidity(3e-3, 0.05e-3) * 14.2e-3;
  EXPECT_NEAR(total / (per_area * (30e-3 * 30e-3 - 9.2e-3 * 9.2e-3)), 1.0, 1e-12);
  // Every node of the band (zone + 2 cells) sits on a grid node in plane.
  const auto band = panel_interface_band(s.spec, s.grid);
  const auto x = f.reference_positions();
  std::size_t in_band = 0;
  for (std::size_t a = 0; a < f.node_count(); ++a) {
    if (x[3 * a] > 9.2e-3 + band.width + 1e-12 || x[3 * a + 1] > 9.2e-3 + band.width + 1e-12)
      continue;
    ++in_band;
    for (int d = 0; d < 2; ++d) {
      const double cells = x[3 * a + d] / 0.4e-3;
      EXPECT_NEAR(cells, std::round(cells), 1e-9) << "node " << a;
    }
  }
  EXPECT_GT(in_band, 0u);
  // The coupling ties them; through the thickness the layer surfaces at -0.5, -14.7 and -15.2 mm
  // fall between grid planes (0.4 mm apart from -16 mm: -0.4, -0.8, ...), z = 0 on one.
  FarFieldCoupling coupling(f, s.grid, band);
  EXPECT_EQ(coupling.tied_node_count(), in_band);
  EXPECT_GT(coupling.exact_node_count(), 0u);
  EXPECT_LT(coupling.exact_node_count(), in_band);
}

TEST(PanelFarField, RefusesAZoneOffTheGridPlanesAndTurnedDoubleWalls) {
  StudyPanel s;
  s.spec.zone = {0, 0, 9.3e-3, 9.2e-3};
  EXPECT_THROW(panel_far_field_mesh(s.panel, s.spec, s.grid), std::invalid_argument);
  s.spec.zone = {0, 0, 40e-3, 9.2e-3};
  EXPECT_THROW(panel_far_field_mesh(s.panel, s.spec, s.grid), std::invalid_argument);
  s.spec.zone = {0, 0, 9.2e-3, 9.2e-3};
  s.panel.double_walls = true;
  s.panel.rotation = std::numbers::pi / 6;
  EXPECT_THROW(panel_far_field_mesh(s.panel, s.spec, s.grid), std::invalid_argument);
}

// A zone that grows up to 20 mm: the elements are one grid cell long out to the limit plus the
// band (20.8 mm), so every band the zone can grow to ties nodes that sit on grid nodes, and
// beyond they grow to at most 6 facesheet thicknesses; a limit that does not hold the zone or is
// off the grid planes is refused.
TEST(PanelFarField, AGrowingZoneHasGridCellElementsOutToItsLimitAndBand) {
  StudyPanel s;
  s.spec.growth_limit = std::array<double, 4>{0, 0, 20e-3, 20e-3};
  const auto mesh = panel_far_field_mesh(s.panel, s.spec, s.grid);
  double x = 0;
  int fine = 0;
  for (const double v : mesh.x_steps) {
    if (x < 20.8e-3 - 1e-12) {
      EXPECT_NEAR(v, 0.4e-3, 1e-15) << "at x = " << x;
      ++fine;
    }
    EXPECT_LE(v, 3e-3 * (1 + 1e-12));  // 6 facesheet thicknesses
    x += v;
  }
  EXPECT_EQ(fine, 52);  // 20.8 mm of 0.4 mm cells
  EXPECT_NEAR(x, 30e-3, 1e-15);
  for (const auto& bad :
       {std::array<double, 4>{0, 0, 8.8e-3, 20e-3}, std::array<double, 4>{0, 0, 20.1e-3, 20e-3},
        std::array<double, 4>{0, 0, 31e-3, 20e-3}}) {
    s.spec.growth_limit = bad;
    EXPECT_THROW(panel_far_field_mesh(s.panel, s.spec, s.grid), std::invalid_argument);
  }
}

// Double walls: the core is heavier by the ribbon walls and stiffer in shear along the ribbon (y'
// of the pattern), which a quarter turn of the pattern puts on x.
TEST(PanelFarField, DoubleWallsFollowTheRibbonDirection) {
  StudyPanel s;
  const fem::Layer single = panel_far_field_mesh(s.panel, s.spec, s.grid).layers[1];
  s.panel.double_walls = true;
  const fem::Layer along_y = panel_far_field_mesh(s.panel, s.spec, s.grid).layers[1];
  s.panel.rotation = std::numbers::pi / 2;
  const fem::Layer along_x = panel_far_field_mesh(s.panel, s.spec, s.grid).layers[1];
  EXPECT_DOUBLE_EQ(along_y.density / single.density,
                   4.0 / 3.0);  // (8t/3D) / (2t/D), same (1 - t/2D)
  EXPECT_DOUBLE_EQ(along_y.elasticity.E3 / single.elasticity.E3, 4.0 / 3.0);
  EXPECT_DOUBLE_EQ(along_y.elasticity.G13, single.elasticity.G13);
  EXPECT_DOUBLE_EQ(along_y.elasticity.G23 / single.elasticity.G23, 19.0 / 12.0);
  EXPECT_DOUBLE_EQ(along_x.elasticity.G13, along_y.elasticity.G23);
  EXPECT_DOUBLE_EQ(along_x.elasticity.G23, along_y.elasticity.G13);
}

}  // namespace
}  // namespace hvi::coupling
