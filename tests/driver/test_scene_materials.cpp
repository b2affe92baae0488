// Materials in scenes: library values fill what the scene does not give and are written to the
// resolved scene; a missing parameter and a parameter table for a model the material does not
// name are located errors; the EOS warning appears when a fast impact meets a material without one.
#include <gtest/gtest.h>

#include "cases/scene/scene.hpp"
#include "tests/support/scene_text.hpp"

namespace hvi::scene {
namespace {

std::string scene_with(const std::string& material, const std::string& speed = "100 m/s") {
  return hvi::test::run_and_grid("1 us", R"(["0 mm", "0 mm", "0 mm"])",
                                 R"(["4 mm", "4 mm", "4 mm"])", "0.5 mm") +
         "[[material]]\n" + material +
         R"(
[[body]]
name = "b"
material = "m"
velocity = [")" +
         speed + R"(", "0 m/s", "0 m/s"]
sphere = { center = ["2 mm", "2 mm", "2 mm"], radius = "1 mm" }
)";
}

TEST(SceneMaterials, LibraryFillsParametersAndTheResolvedSceneRecordsThem) {
  const Scene s = parse_scene(scene_with(R"(name = "m"
library = "Al6061"
strength = "johnson-cook"
eos = "mie-gruneisen"
johnson_cook = { A = "300 MPa" })"),
                              "scene.toml");
  const auto& h = s.materials[0].models;
  EXPECT_DOUBLE_EQ(h.johnson_cook->A, 300e6);  // the scene's value wins
  EXPECT_DOUBLE_EQ(h.johnson_cook->B, 426e6);  // from the library (paper Table 4)
  EXPECT_DOUBLE_EQ(h.eos_as<materials::MieGruneisen>()->c0, 5350.0);
  EXPECT_DOUBLE_EQ(h.density, 2770.0);
  EXPECT_FALSE(h.damage.has_value());  // not named: no damage, although the library has D1..D5
  const auto& m = *s.resolved["material"][0].as_table();
  EXPECT_DOUBLE_EQ(m["johnson_cook"]["B"].value<double>().value(), 426e6);
  EXPECT_DOUBLE_EQ(m["mie_gruneisen"]["gamma0"].value<double>().value(), 2.0);
  EXPECT_FALSE(m.contains("johnson_cook_damage"));
  EXPECT_EQ(s.materials[0].effects(), "johnson-cook strength, mie-gruneisen eos");
}

TEST(SceneMaterials, MissingParameterWithoutLibraryIsAnError) {
  try {
    parse_scene(scene_with(R"(name = "m"
density = "2.7 g/cm^3"
youngs_modulus = "70 GPa"
poisson_ratio = 0.3
strength = "johnson-cook"
johnson_cook = { A = "300 MPa", B = "400 MPa", n = 0.3, C = 0.01 })"),
                "scene.toml");
    FAIL() << "accepted";
  } catch (const SceneError& e) {
    bool found = false;
    for (const auto& d : e.diagnostics())
      if (d.key == "material.m.johnson_cook" &&
          d.message.find("missing parameter 'm'") != std::string::npos)
        found = true;
    EXPECT_TRUE(found) << e.diagnostics().front().text();
  }
}

TEST(SceneMaterials, ParametersForAModelNotNamedAreRefused) {
  try {
    parse_scene(scene_with(R"(name = "m"
library = "Al6061"
mie_gruneisen = { c0 = "5 km/s" })"),
                "scene.toml");
    FAIL() << "accepted";
  } catch (const SceneError& e) {
    const auto& d = e.diagnostics().front();
    EXPECT_EQ(d.key, "material.m.mie_gruneisen");
    EXPECT_EQ(d.line, 11);
    EXPECT_NE(d.message.find("eos = \"mie-gruneisen\""), std::string::npos) << d.text();
  }
}

// Tuler-Butcher spall: the threshold comes from the library's max-principal-stress limit unless
// given, the time is read with its unit, and a scene that leaves the time out is told where.
TEST(SceneMaterials, TulerButcherTakesTheLibraryThresholdAndNeedsItsTime) {
  const Scene s = parse_scene(scene_with(R"(name = "m"
library = "Al2024-T81"
failure = "tuler-butcher"
tuler_butcher = { time = "20 ns" })"),
                              "scene.toml");
  const auto& tb = *s.materials[0].models.tuler_butcher;
  EXPECT_DOUBLE_EQ(tb.threshold, 1500e6);  // Table 1's spall stress
  EXPECT_DOUBLE_EQ(tb.exponent, 2.0);
  EXPECT_DOUBLE_EQ(tb.time, 20e-9);
  EXPECT_FALSE(s.materials[0].models.max_principal_stress.has_value());
  EXPECT_EQ(s.materials[0].effects(), "elastic strength, tuler-butcher failure");
  try {
    parse_scene(scene_with(R"(name = "m"
library = "Al2024-T81"
failure = "tuler-butcher")"),
                "scene.toml");
    FAIL() << "accepted";
  } catch (const SceneError& e) {
    bool found = false;
    for (const auto& d : e.diagnostics())
      if (d.key == "material.m.tuler_butcher" &&
          d.message.find("missing parameter 'time'") != std::string::npos)
        found = true;
    EXPECT_TRUE(found) << e.diagnostics().front().text();
  }
}

// A fracture energy and a Weibull scatter: read with their units, the band the grid's cell, and
// refused with a located reason where the models they act on are not named.
TEST(SceneMaterials, FractureEnergyAndScatterNeedTheModelsTheyActOn) {
  const Scene s = parse_scene(scene_with(R"(name = "m"
library = "AA2024-T81"
strength = "johnson-cook"
eos = "mie-gruneisen"
damage = "johnson-cook"
damage_evolution = "fracture-energy"
fracture_energy = { energy = "14.3 kJ/m^2" }
scatter = "weibull"
weibull = { modulus = 8, seed = 3 })"),
                              "scene.toml");
  const auto& h = s.materials[0].models;
  EXPECT_DOUBLE_EQ(h.fracture_energy->energy, 14.3e3);
  EXPECT_DOUBLE_EQ(h.fracture_energy->band, 0.5e-3);  // the scene's cell
  EXPECT_DOUBLE_EQ(h.scatter->modulus, 8.0);
  EXPECT_EQ(h.scatter->seed, 3u);
  EXPECT_EQ(s.materials[0].effects(),
            "johnson-cook strength, mie-gruneisen eos, johnson-cook damage with fracture-energy "
            "evolution, weibull scatter");
  const auto error = [](const std::string& material, const std::string& key) {
    try {
      parse_scene(scene_with(material), "scene.toml");
    } catch (const SceneError& e) {
      for (const auto& d : e.diagnostics())
        if (d.key == key) return d.message;
      return "no diagnostic for " + key + "; first: " + e.diagnostics().front().text();
    }
    return std::string("accepted");
  };
  const std::string base = "name = \"m\"\nlibrary = \"AA2024-T81\"\nstrength = \"johnson-cook\"\n";
  EXPECT_NE(error(base + "eos = \"mie-gruneisen\"\ndamage_evolution = \"fracture-energy\"\n"
                         "fracture_energy = { energy = \"14 kJ/m^2\" }",
                  "material.m.damage_evolution")
                .find("needs damage = \"johnson-cook\""),
            std::string::npos);
  EXPECT_NE(error(base + "damage = \"johnson-cook\"\ndamage_evolution = \"fracture-energy\"\n"
                         "fracture_energy = { energy = \"14 kJ/m^2\" }",
                  "material.m.damage_evolution")
                .find("needs an eos"),
            std::string::npos);
  EXPECT_NE(error(base + "eos = \"mie-gruneisen\"\ndamage = \"johnson-cook\"\n"
                         "damage_evolution = \"fracture-energy\"",
                  "material.m.fracture_energy")
                .find("missing parameter 'energy'"),
            std::string::npos);
  EXPECT_NE(
      error(base +
                "eos = \"mie-gruneisen\"\ndamage = \"johnson-cook\"\n"
                "damage_evolution = \"fracture-energy\"\nfracture_energy = { energy = \"14 MPa\" }",
            "material.m.fracture_energy.energy")
          .find("fracture energy"),
      std::string::npos);
  EXPECT_NE(error(base + "scatter = \"weibull\"\nweibull = { modulus = 8 }", "material.m.scatter")
                .find("needs damage = \"johnson-cook\" or failure = \"max-principal-stress\""),
            std::string::npos);
}

TEST(SceneMaterials, LibraryNameTypoGetsASuggestion) {
  try {
    parse_scene(scene_with("name = \"m\"\nlibrary = \"Al6016\""), "scene.toml");
    FAIL() << "accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(e.diagnostics().front().text().find("did you mean \"Al6061\"?"), std::string::npos)
        << e.diagnostics().front().text();
  }
}

TEST(SceneMaterials, FastImpactWithoutEquationOfStateWarns) {
  const std::string elastic = "name = \"m\"\nlibrary = \"Al6061\"";
  // Bulk sound speed of Al6061 from E = 75 GPa, nu = 0.33: sqrt(K / rho) = 5.15 km/s; 10% is 515
  // m/s.
  EXPECT_TRUE(parse_scene(scene_with(elastic, "200 m/s"), "s.toml").warnings.empty());
  const Scene fast = parse_scene(scene_with(elastic, "4.5 km/s"), "s.toml");
  ASSERT_EQ(fast.warnings.size(), 1u);
  EXPECT_NE(fast.warnings[0].find("names no equation of state"), std::string::npos)
      << fast.warnings[0];
  EXPECT_TRUE(parse_scene(scene_with(elastic + "\neos = \"mie-gruneisen\"", "4.5 km/s"), "s.toml")
                  .warnings.empty());
}

}  // namespace
}  // namespace hvi::scene

namespace hvi::scene {
namespace {

// A honeycomb whose core cannot fail only channels: `hvi check` says so.
TEST(SceneMaterials, HoneycombCoreWithoutFailureWarns) {
  const std::string study = std::string(HVI_SOURCE_DIR) + "/cases/paper/study/panel.toml";
  auto core_warnings = [](const Scene& s) {
    int n = 0;
    for (const auto& w : s.warnings) n += w.find("is a honeycomb core") != std::string::npos;
    return n;
  };
  EXPECT_EQ(core_warnings(load_scene(study)), 0);
  const Scene s = load_scene(study, {"material.Al5052.damage=none"});
  EXPECT_EQ(core_warnings(s), 1);
}

}  // namespace
}  // namespace hvi::scene
