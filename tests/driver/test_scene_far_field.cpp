// The [far_field] table: a valid hybrid resolves (the panel's material points cut to the zone, the
// default element length recorded), and each way it can be wrong is a located scene error.
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "cases/scene/scene.hpp"
#include "tests/driver/scene_errors.hpp"

namespace hvi::scene {
namespace {

std::string small_hybrid() {
  std::ifstream in(std::string(HVI_SOURCE_DIR) + "/tests/driver/data/small_hybrid.toml");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

Diagnostic error_for(const std::vector<std::string>& overrides, const std::string& key) {
  return test::error_for(small_hybrid(), key, overrides, "small_hybrid.toml");
}

TEST(SceneFarField, ResolvesThePanelZoneAndDefaults) {
  const Scene s = parse_scene(small_hybrid(), "small_hybrid.toml");
  ASSERT_TRUE(s.far_field.has_value());
  const FarFieldSettings& f = *s.far_field;
  EXPECT_EQ(s.panels[f.panel].name, "panel");
  // The panel's extent cut by its clip (the quarter), and the zone.
  EXPECT_DOUBLE_EQ(f.extent[0], 0.0);
  EXPECT_DOUBLE_EQ(f.extent[2], 10e-3);
  EXPECT_DOUBLE_EQ(f.zone[2], 3e-3);
  EXPECT_EQ(f.band_elements, 2);
  EXPECT_FALSE(f.clamped_edges);
  // Default largest element: 6 x the thinner facesheet (0.5 mm), written to the resolved scene.
  EXPECT_DOUBLE_EQ(f.max_element, 3e-3);
  EXPECT_DOUBLE_EQ(s.resolved["far_field"]["max_element"].value_or(0.0), 3e-3);
  // The panel's bodies are material points in the zone only: their clip is the zone in plane.
  for (const auto& b : s.bodies) {
    if (b.name.rfind("panel.", 0) != 0) continue;
    ASSERT_TRUE(b.clip.has_value()) << b.name;
    EXPECT_DOUBLE_EQ(b.clip->upper[0], 3e-3) << b.name;
    EXPECT_DOUBLE_EQ(b.clip->upper[1], 3e-3) << b.name;
    EXPECT_DOUBLE_EQ(b.clip->lower[0], 0.0) << b.name;
  }
}

TEST(SceneFarField, WithoutTheTableThereIsNoFarField) {
  std::string text = small_hybrid();
  const auto from = text.find("\n[far_field]"), to = text.find("\n[[measure]]");
  text.erase(from, to - from);
  const Scene s =
      parse_scene(text, "small_hybrid.toml", {"grid.upper=[\"11 mm\", \"11 mm\", \"3 mm\"]"});
  EXPECT_FALSE(s.far_field.has_value());
  EXPECT_FALSE(s.resolved.contains("far_field"));
}

TEST(SceneFarField, ErrorsNameTheKey) {
  Diagnostic d = error_for({"far_field.panel=plate"}, "far_field.panel");
  EXPECT_NE(d.message.find("no [[panel]] named 'plate'; panels: 'panel'"), std::string::npos)
      << d.message;
  EXPECT_GT(d.line, 0);

  d = error_for({"far_field.zone.upper=[\"3.2 mm\", \"3 mm\"]"}, "far_field.zone");
  EXPECT_NE(d.message.find("not on a grid plane"), std::string::npos) << d.message;

  d = error_for({"far_field.zone.upper=[\"12 mm\", \"3 mm\"]"}, "far_field.zone");
  EXPECT_NE(d.message.find("must lie inside the panel"), std::string::npos) << d.message;

  // The grid ends at 4 mm: a 3 mm zone and 3 band cells of 0.5 mm reach 4.5 mm.
  d = error_for({"far_field.band_elements=3"}, "far_field.zone");
  EXPECT_NE(d.message.find("outside the grid"), std::string::npos) << d.message;

  d = error_for({"far_field.max_element=0.2 mm"}, "far_field.max_element");
  EXPECT_NE(d.message.find("smaller than a grid cell"), std::string::npos) << d.message;

  d = error_for({"panel.panel.double_walls=true", "panel.panel.rotation=30 deg"},
                "far_field.panel");
  EXPECT_NE(d.message.find("multiple of 90 deg"), std::string::npos) << d.message;

  // A core lifted off the rear facesheet has no far field to match: the far field's core stands on
  // it.
  d = error_for({"panel.panel.rear_gap=0.4 mm"}, "panel.panel.rear_gap");
  EXPECT_NE(d.message.find("no [far_field] on it"), std::string::npos) << d.message;

  d = error_for({"far_field.edges=pinned"}, "far_field.edges");
  EXPECT_NE(d.message.find("clamped"), std::string::npos) << d.message;

  d = error_for({"far_field.kinematics=large"}, "far_field.kinematics");
  EXPECT_NE(d.message.find("finite"), std::string::npos) << d.message;

  // J2 facesheets harden as their material's Johnson-Cook strength: the elastic aluminium has none.
  d = error_for({"far_field.plasticity=j2"}, "far_field.plasticity");
  EXPECT_NE(d.message.find("'aluminium' (panel.front) names strength = \"elastic\""),
            std::string::npos)
      << d.message;

  // A yielding core caps its stresses at its walls' yield, their Johnson-Cook A.
  d = error_for({"far_field.core=yielding"}, "far_field.core");
  EXPECT_NE(d.message.find("'aluminium' (panel.core) names strength = \"elastic\""),
            std::string::npos)
      << d.message;
  d = error_for({"far_field.core=crushable"}, "far_field.core");
  EXPECT_NE(d.message.find("yielding"), std::string::npos) << d.message;
  // A failing core also tears its walls by their Johnson-Cook damage: strength alone is not enough.
  d = error_for({"far_field.core=failing", "material.aluminium.library=Al6061",
                 "material.aluminium.strength=johnson-cook"},
                "far_field.core");
  EXPECT_NE(d.message.find("'aluminium' (panel.core) names damage = \"none\""), std::string::npos)
      << d.message;
  // Failing facesheets harden (strength) and tear (damage) as their material's Johnson-Cook models.
  d = error_for({"far_field.plasticity=failing", "material.aluminium.library=Al6061",
                 "material.aluminium.strength=johnson-cook"},
                "far_field.plasticity");
  EXPECT_NE(d.message.find("\"failing\" tears the facesheets"), std::string::npos) << d.message;
  EXPECT_NE(d.message.find("'aluminium' (panel.front) names damage = \"none\""), std::string::npos)
      << d.message;
}

TEST(SceneFarField, FailingFacesheetsOnlyWhenNamed) {
  const Scene j2 = parse_scene(
      small_hybrid(), "small_hybrid.toml",
      {"far_field.plasticity=j2", "material.aluminium.library=Al6061",
       "material.aluminium.strength=johnson-cook", "material.aluminium.damage=johnson-cook"});
  EXPECT_TRUE(j2.far_field->plastic_faces);
  EXPECT_FALSE(j2.far_field->failing_faces);
  // "failing" facesheets are J2 facesheets that also tear.
  const Scene f = parse_scene(
      small_hybrid(), "small_hybrid.toml",
      {"far_field.plasticity=failing", "material.aluminium.library=Al6061",
       "material.aluminium.strength=johnson-cook", "material.aluminium.damage=johnson-cook"});
  EXPECT_TRUE(f.far_field->plastic_faces);
  EXPECT_TRUE(f.far_field->failing_faces);
  EXPECT_FALSE(f.far_field->yielding_core);
  EXPECT_EQ(f.resolved["far_field"]["plasticity"].value_or(std::string{}), "failing");
}

TEST(SceneFarField, YieldingCoreOnlyWhenNamed) {
  const Scene small = parse_scene(small_hybrid(), "small_hybrid.toml");
  EXPECT_FALSE(small.far_field->yielding_core);
  EXPECT_EQ(small.resolved["far_field"]["core"].value_or(std::string{}), "elastic");
  const Scene s = parse_scene(small_hybrid(), "small_hybrid.toml",
                              {"far_field.core=yielding", "material.aluminium.library=Al6061",
                               "material.aluminium.strength=johnson-cook"});
  EXPECT_TRUE(s.far_field->yielding_core);
  EXPECT_FALSE(s.far_field->failing_core);
  EXPECT_FALSE(s.far_field->plastic_faces);
  EXPECT_FALSE(small.far_field->failing_core);
  // "failing" is a yielding core whose walls also tear.
  const Scene f = parse_scene(
      small_hybrid(), "small_hybrid.toml",
      {"far_field.core=failing", "material.aluminium.library=Al6061",
       "material.aluminium.strength=johnson-cook", "material.aluminium.damage=johnson-cook"});
  EXPECT_TRUE(f.far_field->yielding_core);
  EXPECT_TRUE(f.far_field->failing_core);
  EXPECT_EQ(f.resolved["far_field"]["core"].value_or(std::string{}), "failing");
}

// The far field's elements share the solver's (field 0's) nodes: a part of its panel cannot be on
// the impactor's field.
TEST(SceneFarField, ContactRefusesThePanelsParts) {
  const Diagnostic d = error_for({"contact.bodies=[\"panel.front\"]"}, "contact.bodies");
  EXPECT_NE(d.text().find("'panel.front' is part of the far field's panel"), std::string::npos)
      << d.text();
}

TEST(SceneFarField, PlasticFacesheetsOnlyWhenNamed) {
  EXPECT_FALSE(parse_scene(small_hybrid(), "small_hybrid.toml").far_field->plastic_faces);
  const Scene s = parse_scene(small_hybrid(), "small_hybrid.toml",
                              {"far_field.plasticity=j2", "material.aluminium.library=Al6061",
                               "material.aluminium.strength=johnson-cook"});
  EXPECT_TRUE(s.far_field->plastic_faces);
  EXPECT_EQ(s.resolved["far_field"]["plasticity"].value_or(std::string{}), "j2");
}

// The facesheets' yield takes the rate factor only when named, and only J2 facesheets have one.
TEST(SceneFarField, StrainRateOnlyWhenNamedAndOnlyForJ2Facesheets) {
  const Scene small = parse_scene(small_hybrid(), "small_hybrid.toml");
  EXPECT_FALSE(small.far_field->strain_rate);
  EXPECT_EQ(small.resolved["far_field"]["strain_rate"].value_or(std::string{}), "reference");
  const Scene s = parse_scene(
      small_hybrid(), "small_hybrid.toml",
      {"far_field.plasticity=j2", "far_field.strain_rate=johnson-cook",
       "material.aluminium.library=Al6061", "material.aluminium.strength=johnson-cook"});
  EXPECT_TRUE(s.far_field->strain_rate);
  EXPECT_EQ(s.resolved["far_field"]["strain_rate"].value_or(std::string{}), "johnson-cook");
  Diagnostic d = error_for({"far_field.strain_rate=johnson-cook"}, "far_field.strain_rate");
  EXPECT_NE(d.message.find("plasticity = \"none\" has none"), std::string::npos) << d.message;
  d = error_for({"far_field.strain_rate=plastic"}, "far_field.strain_rate");
  EXPECT_NE(d.message.find("johnson-cook"), std::string::npos) << d.message;
}

TEST(SceneFarField, FiniteStrainOnlyWhenNamed) {
  const Scene small = parse_scene(small_hybrid(), "small_hybrid.toml");
  EXPECT_FALSE(small.far_field->finite_strain);
  EXPECT_EQ(small.resolved["far_field"]["kinematics"].value_or(std::string{}), "small");
  const Scene s = parse_scene(small_hybrid(), "small_hybrid.toml", {"far_field.kinematics=finite"});
  EXPECT_TRUE(s.far_field->finite_strain);
  EXPECT_EQ(s.resolved["far_field"]["kinematics"].value_or(std::string{}), "finite");
}

// [far_field.zone.grow]: a zone that grows, with step and margin defaulting to 8 and 4 grid cells
// (recorded in the resolved scene); absent, the zone stays.
const std::vector<std::string> growing = {"grid.upper=[\"7 mm\", \"7 mm\", \"3 mm\"]",
                                          "material.aluminium.library=Al5052",
                                          "material.aluminium.strength=johnson-cook",
                                          "material.aluminium.damage=johnson-cook",
                                          "far_field.zone.grow.lower=[\"0 mm\", \"0 mm\"]",
                                          "far_field.zone.grow.upper=[\"6 mm\", \"6 mm\"]"};

std::vector<std::string> growing_with(std::vector<std::string> more) {
  more.insert(more.begin(), growing.begin(), growing.end());
  return more;
}

TEST(SceneFarField, AGrowingZoneResolvesItsLimitAndDefaults) {
  EXPECT_FALSE(parse_scene(small_hybrid(), "small_hybrid.toml").far_field->grow.has_value());
  const Scene s = parse_scene(small_hybrid(), "small_hybrid.toml", growing);
  ASSERT_TRUE(s.far_field->grow.has_value());
  const auto& g = *s.far_field->grow;
  EXPECT_DOUBLE_EQ(g.limit[2], 6e-3);
  EXPECT_DOUBLE_EQ(g.limit[3], 6e-3);
  EXPECT_DOUBLE_EQ(g.step, 4e-3);    // 8 cells of 0.5 mm
  EXPECT_DOUBLE_EQ(g.margin, 2e-3);  // 4 cells
  EXPECT_DOUBLE_EQ(g.damage, 1.0);
  EXPECT_DOUBLE_EQ(s.resolved["far_field"]["zone"]["grow"]["step"].value_or(0.0), 4e-3);
  EXPECT_DOUBLE_EQ(s.resolved["far_field"]["zone"]["grow"]["margin"].value_or(0.0), 2e-3);
}

TEST(SceneFarField, AGrowingZonesErrorsNameTheKey) {
  Diagnostic d = error_for(growing_with({"far_field.zone.grow.upper=[\"2 mm\", \"6 mm\"]"}),
                           "far_field.zone.grow.upper");
  EXPECT_NE(d.message.find("must hold the zone's"), std::string::npos) << d.message;

  d = error_for(growing_with({"far_field.zone.grow.upper=[\"5.2 mm\", \"6 mm\"]"}),
                "far_field.zone.grow.upper");
  EXPECT_NE(d.message.find("not on a grid plane"), std::string::npos) << d.message;

  // The grid ends at 7 mm: a 6 mm limit and 3 band cells of 0.5 mm reach 7.5 mm.
  d = error_for(growing_with({"far_field.band_elements=3"}), "far_field.zone.grow.upper");
  EXPECT_NE(d.message.find("outside the grid"), std::string::npos) << d.message;

  d = error_for(growing_with({"far_field.zone.grow.step=0.7 mm"}), "far_field.zone.grow.step");
  EXPECT_NE(d.message.find("not a whole number of grid cells"), std::string::npos) << d.message;

  d = error_for(growing_with({"far_field.zone.grow.damage=0"}), "far_field.zone.grow.damage");
  EXPECT_NE(d.message.find("in (0, 1]"), std::string::npos) << d.message;

  d = error_for(growing_with({"material.aluminium.damage=none"}), "far_field.zone.grow.damage");
  EXPECT_NE(d.message.find("none of its materials names damage"), std::string::npos) << d.message;
}

}  // namespace
}  // namespace hvi::scene
