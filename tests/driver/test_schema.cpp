// The declarative key schema: resolution of a valid scene (defaults, SI values, array naming),
// one test per class of error with its message and location, command-line overrides and the
// Markdown reference.
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cases/scene/schema.hpp"

namespace hvi::scene {
namespace {

// A small scene schema in the shape of the real one.
TableSpec test_schema() {
  TableSpec root;
  root.string("title", "untitled", "Name of the run");

  TableSpec grid{.name = "grid", .doc = "Background grid.", .required = true};
  grid.quantity_required("cell_size", dims::length, positive(), "Edge of a grid cell")
      .number("cfl", left_open(0, 1), 0.5, "Courant number")
      .choice("shape_function", {"linear", "gimp", "cpdi"}, "linear",
              "Particle-grid shape function")
      .integer("threads", closed(1, 256), 1, "Worker threads");

  TableSpec output{.name = "output", .doc = "What is written and how often."};
  output.quantity("interval", dims::time, positive(), 1e-6, "Time between frames")
      .boolean("fields", true, "Write grid fields")
      .string_list("variables", {"velocity", "stress"}, "Particle variables");

  TableSpec time{.name = "time", .doc = "Simulated time."};
  time.quantity_required("end", dims::time, positive(), "End time");

  TableSpec sphere{.name = "sphere", .doc = "A solid sphere."};
  sphere.quantity_required("radius", dims::length, positive(), "Radius")
      .vector_required("center", dims::length, "Center");
  TableSpec box{.name = "box", .doc = "An axis-aligned box."};
  box.vector_required("min", dims::length, "Lower corner")
      .vector_required("max", dims::length, "Upper corner");

  TableSpec body{.name = "body", .doc = "A material body.", .array = true, .required = true};
  body.string_required("name", "Unique name")
      .string_required("material", "Material name")
      .vector("velocity", dims::velocity, std::vector<double>{0, 0, 0}, "Initial velocity")
      .quantity("temperature", dims::temperature, positive(), 293.15, "Initial temperature")
      .optional_quantity("spin", dims::rate, Range{}, "Angular rate; computed when absent")
      .table(sphere)
      .table(box);
  body.one_of = {"sphere", "box"};

  root.table(grid).table(output).table(time).table(body);
  return root;
}

toml::table parse(const std::string& text) {
  return toml::parse(std::string_view(text), std::string_view("scene.toml"));
}

Validated check(const std::string& text) {
  return validate(parse(text), test_schema(), "scene.toml");
}

// The diagnostic for a key path; fails the test when there is none.
Diagnostic error_for(const Validated& v, const std::string& key) {
  for (const Diagnostic& d : v.errors) {
    if (d.key == key) return d;
  }
  std::string all;
  for (const Diagnostic& d : v.errors) all += d.text() + "\n";
  ADD_FAILURE() << "no diagnostic for '" << key << "'; diagnostics:\n" << all;
  return {};
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

#define EXPECT_CONTAINS(text, part) EXPECT_TRUE(contains(text, part)) << (text)

// A scene without errors; other tests change one line of it.
const std::string kValid = R"(title = "sphere on plate"
[grid]
cell_size = "0.5 mm"

[[body]]
name = "projectile"
material = "Al"
velocity = ["4.5 km/s", 0, "-10 m/s"]
[body.sphere]
radius = "1.5 mm"
center = [0, 0, "2 mm"]

[[body]]
name = "target"
material = "Al"
temperature = "20 degC"
[body.box]
min = ["-10 mm", "-10 mm", "-1 mm"]
max = ["10 mm", "10 mm", 0]
)";

TEST(Schema, ValidSceneResolvesToSiWithDefaults) {
  const Validated v = check(kValid);
  ASSERT_TRUE(v.ok()) << v.errors.front().text();
  const toml::table& r = v.resolved;
  EXPECT_EQ(r["title"].value<std::string>(), "sphere on plate");
  EXPECT_DOUBLE_EQ(*r["grid"]["cell_size"].value<double>(), 5e-4);
  EXPECT_DOUBLE_EQ(*r["grid"]["cfl"].value<double>(), 0.5);
  EXPECT_EQ(r["grid"]["shape_function"].value<std::string>(), "linear");
  ASSERT_TRUE(r["grid"]["threads"].is_integer());
  EXPECT_EQ(*r["grid"]["threads"].value<std::int64_t>(), 1);
  // [output] was not written: it exists with its defaults.
  EXPECT_DOUBLE_EQ(*r["output"]["interval"].value<double>(), 1e-6);
  EXPECT_EQ(r["output"]["fields"].value<bool>(), true);
  ASSERT_TRUE(r["output"]["variables"].is_array());
  EXPECT_EQ(r["output"]["variables"][1].value<std::string>(), "stress");
  // [time] has a required key and cannot be made from defaults: it stays absent.
  EXPECT_FALSE(r.contains("time"));

  const toml::array& bodies = *r["body"].as_array();
  ASSERT_EQ(bodies.size(), 2u);
  const toml::table& projectile = *bodies[0].as_table();
  EXPECT_DOUBLE_EQ(*projectile["velocity"][0].value<double>(), 4500.0);
  EXPECT_DOUBLE_EQ(*projectile["velocity"][2].value<double>(), -10.0);
  EXPECT_DOUBLE_EQ(*projectile["sphere"]["radius"].value<double>(), 1.5e-3);
  EXPECT_DOUBLE_EQ(*projectile["sphere"]["center"][2].value<double>(), 2e-3);
  EXPECT_DOUBLE_EQ(*projectile["temperature"].value<double>(), 293.15);
  EXPECT_FALSE(projectile.contains("spin"));  // optional without default
  EXPECT_FALSE(projectile.contains("box"));   // the other alternative of one_of
  const toml::table& target = *bodies[1].as_table();
  EXPECT_DOUBLE_EQ(*target["temperature"].value<double>(), 293.15);
  EXPECT_DOUBLE_EQ(*target["velocity"][0].value<double>(), 0.0);
  EXPECT_DOUBLE_EQ(*target["box"]["min"][0].value<double>(), -0.01);
}

TEST(Schema, LocationsUseElementNames) {
  const Validated v = check(kValid);
  ASSERT_TRUE(v.ok());
  ASSERT_TRUE(v.locations.contains("body.projectile.sphere.radius"));
  EXPECT_EQ(v.locations.at("body.projectile.sphere.radius").begin.line, 10u);
  EXPECT_EQ(v.locations.at("body.target").begin.line, 13u);
  EXPECT_EQ(v.locations.at("grid").begin.line, 2u);
  EXPECT_EQ(*v.locations.at("grid.cell_size").path, "scene.toml");
}

TEST(Schema, PlainNumbersAndUnitlessStringsAreAccepted) {
  const Validated v = check(R"([grid]
cell_size = 0.001
cfl = "0.3"
[[body]]
name = "p"
material = "Al"
[body.sphere]
radius = 1
center = [0, 0, 0]
)");
  ASSERT_TRUE(v.ok()) << v.errors.front().text();
  EXPECT_DOUBLE_EQ(*v.resolved["grid"]["cell_size"].value<double>(), 1e-3);
  EXPECT_DOUBLE_EQ(*v.resolved["grid"]["cfl"].value<double>(), 0.3);
  ASSERT_TRUE(v.resolved["body"][0]["sphere"]["radius"].is_floating_point());
  EXPECT_DOUBLE_EQ(*v.resolved["body"][0]["sphere"]["radius"].value<double>(), 1.0);
}

TEST(Schema, UnknownKeySuggestsClosestKey) {
  const Validated v = check(R"([grid]
cell_size = "0.5 mm"
cel_size = "0.5 mm"
[[body]]
name = "p"
material = "Al"
[body.sphere]
radious = "1 mm"
radius = "1 mm"
center = [0, 0, 0]
)");
  EXPECT_EQ(error_for(v, "grid.cel_size").text(),
            "scene.toml:3:1: key 'grid.cel_size': unknown key in [grid]; did you mean "
            "'cell_size'?");
  EXPECT_EQ(error_for(v, "body.p.sphere.radious").text(),
            "scene.toml:8:1: key 'body.p.sphere.radious': unknown key in [body.sphere]; did you "
            "mean 'radius'?");
  EXPECT_EQ(v.errors.size(), 2u);
}

TEST(Schema, UnknownKeyWithoutCloseMatchListsValidKeys) {
  const Validated v = check(kValid + "[solver]\nthreads = 4\n");
  const Diagnostic d = error_for(v, "solver");
  EXPECT_EQ(d.line, 20);
  EXPECT_CONTAINS(d.text(),
                  "unknown top-level key; valid keys: title, [grid], [output], [time], "
                  "[[body]]");
  // A sub-table name is a candidate too.
  const Validated typo = check(kValid + "[outptu]\nfields = false\n");
  EXPECT_CONTAINS(error_for(typo, "outptu").text(), "did you mean 'output'?");
}

TEST(Schema, WrongType) {
  const Validated v = check(R"([grid]
cell_size = { value = 1 }
threads = "four"
[[body]]
name = "p"
material = 3
sphere = 2
)");
  EXPECT_EQ(error_for(v, "grid.threads").text(),
            "scene.toml:3:1: key 'grid.threads' = \"four\": expected an integer, got a string");
  EXPECT_EQ(error_for(v, "grid.cell_size").text(),
            "scene.toml:2:1: key 'grid.cell_size': expected a length (e.g. \"0.5 mm\"), got a "
            "table");
  EXPECT_CONTAINS(error_for(v, "body.p.material").text(),
                  "scene.toml:6:1: key 'body.p.material' = 3: expected a string, got an integer");
  EXPECT_CONTAINS(error_for(v, "body.p.sphere").text(),
                  "scene.toml:7:1: key 'body.p.sphere' = 2: expected a table [body.sphere], got "
                  "an integer");
}

TEST(Schema, ArrayOfTablesWrittenAsTable) {
  const Validated v = check(R"([grid]
cell_size = "0.5 mm"
[body]
name = "p"
)");
  EXPECT_CONTAINS(error_for(v, "body").text(),
                  "scene.toml:3:2: key 'body': expected an array of tables [[body]], got a table "
                  "(write [[body]] instead of [body])");
}

TEST(Schema, WrongUnit) {
  const Validated v = check(R"([grid]
    cell_size = "0.5 kg"
cfl = "0.3 s"
[[body]]
name = "p"
material = "Al"
temperature = "300 furlong"
[body.sphere]
radius = "1 mm"
center = [0, 0, 0]
)");
  EXPECT_EQ(error_for(v, "grid.cell_size").text(),
            "scene.toml:2:5: key 'grid.cell_size' = \"0.5 kg\": expected a length (e.g. \"0.5 "
            "mm\"), got a mass");
  EXPECT_EQ(error_for(v, "grid.cfl").text(),
            "scene.toml:3:1: key 'grid.cfl' = \"0.3 s\": expected a number without unit, got a "
            "time");
  const std::string text = error_for(v, "body.p.temperature").text();
  EXPECT_CONTAINS(text,
                  "scene.toml:7:1: key 'body.p.temperature' = \"300 furlong\": unknown "
                  "unit 'furlong'");
}

TEST(Schema, OutOfRange) {
  const Validated v = check(R"([grid]
cell_size = "-1 mm"
cfl = 1.5
threads = 0
[[body]]
name = "p"
material = "Al"
[body.sphere]
radius = 0
center = [0, 0, 0]
)");
  EXPECT_EQ(error_for(v, "grid.cfl").text(),
            "scene.toml:3:1: key 'grid.cfl' = 1.5: expected a number in (0, 1]");
  EXPECT_EQ(error_for(v, "grid.cell_size").text(),
            "scene.toml:2:1: key 'grid.cell_size' = \"-1 mm\": expected a length > 0 m, got "
            "-0.001 m");
  EXPECT_EQ(error_for(v, "grid.threads").text(),
            "scene.toml:4:1: key 'grid.threads' = 0: expected an integer in [1, 256]");
  EXPECT_EQ(error_for(v, "body.p.sphere.radius").text(),
            "scene.toml:9:1: key 'body.p.sphere.radius' = 0: expected a length > 0 m");
}

TEST(Schema, RangeDescriptions) {
  EXPECT_EQ(positive().describe(), "> 0");
  EXPECT_EQ(non_negative().describe(), ">= 0");
  EXPECT_EQ(closed(0, 1).describe(), "in [0, 1]");
  EXPECT_EQ(left_open(0, 1).describe(), "in (0, 1]");
  EXPECT_EQ(right_open(0, 0.5).describe(), "in [0, 0.5)");
  EXPECT_EQ((Range{std::nullopt, 1.0, true, false}).describe(), "< 1");
  EXPECT_TRUE(left_open(0, 1).contains(1.0));
  EXPECT_FALSE(left_open(0, 1).contains(0.0));
  EXPECT_FALSE(right_open(0, 1).contains(1.0));
  EXPECT_FALSE(Range{}.contains(std::nan("")));
}

TEST(Schema, IntegerWrittenAsFloatAndNonFiniteNumbers) {
  const Validated v = check(R"([grid]
cell_size = "0.5 mm"
threads = 4.0
cfl = nan
)");
  EXPECT_EQ(error_for(v, "grid.threads").text(),
            "scene.toml:3:1: key 'grid.threads' = 4.0: expected an integer, got a floating point "
            "number");
  EXPECT_EQ(error_for(v, "grid.cfl").text(),
            "scene.toml:4:1: key 'grid.cfl' = nan: expected a finite number");
}

TEST(Schema, MissingRequiredKeyIsReportedAtTableHeader) {
  const Validated v = check(R"(title = "t"

[grid]
cfl = 0.5
[[body]]
name = "p"
[body.sphere]
center = [0, 0, 0]
)");
  EXPECT_EQ(error_for(v, "grid.cell_size").text(),
            "scene.toml:3:1: key 'grid.cell_size': missing required key: expected a length (e.g. "
            "\"0.5 mm\")");
  EXPECT_EQ(error_for(v, "body.p.material").line, 5);
  EXPECT_EQ(error_for(v, "body.p.sphere.radius").line, 7);
}

TEST(Schema, MissingRequiredTableAndArray) {
  const Validated v = check("title = \"t\"\n");
  EXPECT_EQ(error_for(v, "grid").text(),
            "scene.toml:1:1: key 'grid': missing required table [grid]");
  EXPECT_EQ(error_for(v, "body").text(),
            "scene.toml:1:1: key 'body': missing [[body]]: at least one is required");
  EXPECT_EQ(v.errors.size(), 2u);
}

TEST(Schema, OneOfNoneOrSeveral) {
  const Validated v = check(R"([grid]
cell_size = "0.5 mm"
[[body]]
name = "none"
material = "Al"
[[body]]
name = "both"
material = "Al"
[body.sphere]
radius = "1 mm"
center = [0, 0, 0]
[body.box]
min = [0, 0, 0]
max = [1, 1, 1]
)");
  EXPECT_EQ(error_for(v, "body.none").text(),
            "scene.toml:3:1: key 'body.none': missing one of [body.sphere], [body.box]: exactly "
            "one is required");
  EXPECT_EQ(error_for(v, "body.both").text(),
            "scene.toml:12:1: key 'body.both': only one of [body.sphere], [body.box] may be given, "
            "found [body.sphere] and [body.box]");
}

TEST(Schema, InvalidChoiceSuggestsClosest) {
  const Validated c = check(R"([grid]
cell_size = "0.5 mm"
shape_function = "lineer"
)");
  EXPECT_EQ(error_for(c, "grid.shape_function").text(),
            "scene.toml:3:1: key 'grid.shape_function' = \"lineer\": invalid choice: expected one "
            "of \"linear\", \"gimp\", \"cpdi\"; did you mean \"linear\"?");
}

TEST(Schema, VectorComponentsCountAndUnits) {
  const Validated v = check(R"([grid]
cell_size = "0.5 mm"
[[body]]
name = "p"
material = "Al"
velocity = [1, 2]
[body.sphere]
radius = "1 mm"
center = [0, "1 m/s", "1 furlong"]
)");
  EXPECT_CONTAINS(error_for(v, "body.p.velocity").text(),
                  "scene.toml:6:1: key 'body.p.velocity' = [1, 2]: expected an array of 3 "
                  "velocity values (e.g. [\"4.5 km/s\", 0, 0]), got 2 components");
  // Both bad components are reported, each at its own column.
  std::vector<std::string> center;
  for (const Diagnostic& d : v.errors) {
    if (d.key == "body.p.sphere.center") center.push_back(d.text());
  }
  ASSERT_EQ(center.size(), 2u);
  EXPECT_EQ(center[0],
            "scene.toml:9:14: key 'body.p.sphere.center' = \"1 m/s\": component 2 of 3: expected "
            "a length (e.g. \"0.5 mm\"), got a velocity");
  EXPECT_CONTAINS(center[1],
                  "scene.toml:9:23: key 'body.p.sphere.center' = \"1 furlong\": "
                  "component 3 of 3: unknown unit 'furlong'");
}

TEST(Schema, CollectsAllErrorsInReadingOrder) {
  const Validated v = check(R"([grid]
cell_size = "0.5 kg"
cfl = 2
shape_function = "quadratic"
[[body]]
name = "p"
[body.sphere]
radius = "1 mm"
center = [0, 0]
)");
  ASSERT_EQ(v.errors.size(), 5u);
  EXPECT_EQ(v.errors[0].key, "grid.cell_size");
  EXPECT_EQ(v.errors[1].key, "grid.cfl");
  EXPECT_EQ(v.errors[2].key, "grid.shape_function");
  EXPECT_EQ(v.errors[3].key, "body.p.material");
  EXPECT_EQ(v.errors[4].key, "body.p.sphere.center");
  EXPECT_FALSE(v.ok());
}

TEST(Schema, ElementsWithoutNameAreAddressedByIndex) {
  const Validated v = check(R"([grid]
cell_size = "0.5 mm"
[[body]]
material = "Al"
[body.sphere]
radius = "-1 mm"
center = [0, 0, 0]
)");
  EXPECT_EQ(error_for(v, "body.0.name").line, 3);
  EXPECT_EQ(error_for(v, "body.0.sphere.radius").line, 6);
}

TEST(Schema, DuplicateElementNames) {
  const Validated v = check(kValid + R"(
[[body]]
name = "target"
material = "Al"
[body.box]
min = [0, 0, 0]
max = [1, 1, 1]
)");
  EXPECT_EQ(error_for(v, "body.2.name").text(),
            "scene.toml:22:8: key 'body.2.name' = \"target\": duplicate name: every [[body]] "
            "needs a unique name");
}

TEST(Schema, AtLocatesKeysOrTheirNearestWrittenAncestor) {
  const Validated v = check(kValid);
  EXPECT_EQ(v.at("body.projectile.material", "material 'Al' is not defined").text(),
            "scene.toml:7:1: key 'body.projectile.material': material 'Al' is not defined");
  // Not written (default): the element's [[body]] header.
  const Diagnostic spin = v.at("body.projectile.spin", "spin too fast");
  EXPECT_EQ(spin.line, 5);
  EXPECT_EQ(spin.key, "body.projectile.spin");
  const Diagnostic root = v.at("nothing.here", "x");
  EXPECT_EQ(root.text(), "scene.toml:1:1: key 'nothing.here': x");
}

TEST(Schema, OverridesReplaceValues) {
  toml::table doc = parse(kValid);
  apply_override(doc, "grid.cell_size=0.25 mm");
  apply_override(doc, "grid.cfl = 0.3");
  apply_override(doc, "body.projectile.velocity=[\"5 km/s\", 0, 0]");
  apply_override(doc, "body.1.temperature=300");
  apply_override(doc, "output.interval=2 us");  // creates [output]
  apply_override(doc, "grid.shape_function=gimp");
  const Validated v = validate(doc, test_schema(), "scene.toml");
  ASSERT_TRUE(v.ok()) << v.errors.front().text();
  EXPECT_DOUBLE_EQ(*v.resolved["grid"]["cell_size"].value<double>(), 2.5e-4);
  EXPECT_DOUBLE_EQ(*v.resolved["grid"]["cfl"].value<double>(), 0.3);
  EXPECT_DOUBLE_EQ(*v.resolved["body"][0]["velocity"][0].value<double>(), 5000.0);
  EXPECT_DOUBLE_EQ(*v.resolved["body"][1]["temperature"].value<double>(), 300.0);
  EXPECT_DOUBLE_EQ(*v.resolved["output"]["interval"].value<double>(), 2e-6);
  EXPECT_EQ(v.resolved["grid"]["shape_function"].value<std::string>(), "gimp");
  // The location of an overridden key names the override.
  EXPECT_EQ(v.at("grid.cell_size", "m").text(),
            "--set grid.cell_size=0.25 mm:1:1: key 'grid.cell_size': m");
  EXPECT_EQ(v.at("grid.cell_size", "m").file, "--set grid.cell_size=0.25 mm");
}

TEST(Schema, OverrideDiagnosticsNameTheOverride) {
  toml::table doc = parse(kValid);
  apply_override(doc, "grid.cel_size=1 mm");
  apply_override(doc, "body.target.temperature=20 kg");
  apply_override(doc, "solver.threads=4");  // unknown table created by the override
  const Validated v = validate(doc, test_schema(), "scene.toml");
  EXPECT_EQ(error_for(v, "grid.cel_size").text(),
            "--set grid.cel_size=1 mm:1:1: key 'grid.cel_size': unknown key in [grid]; did you "
            "mean 'cell_size'?");
  EXPECT_EQ(error_for(v, "body.target.temperature").text(),
            "--set body.target.temperature=20 kg:1:1: key 'body.target.temperature' = \"20 kg\": "
            "expected a temperature (e.g. \"293 K\"), got a mass");
  EXPECT_CONTAINS(error_for(v, "solver").text(),
                  "--set solver.threads=4:1:1: key 'solver': "
                  "unknown top-level key");
}

TEST(Schema, OverrideErrors) {
  toml::table doc = parse(kValid);
  EXPECT_THROW(apply_override(doc, "grid.cell_size"), std::invalid_argument);
  try {
    apply_override(doc, "body.bullet.radius=1 mm");
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_CONTAINS(std::string(e.what()),
                    "there is no [[body]] element named 'bullet' (elements: projectile, target)");
  }
  EXPECT_THROW(apply_override(doc, "body.5.radius=1"), std::invalid_argument);
  EXPECT_THROW(apply_override(doc, "grid..cfl=1"), std::invalid_argument);
  EXPECT_THROW(apply_override(doc, "grid.cell_size.x=1"), std::invalid_argument);
}

TEST(Schema, MarkdownReference) {
  const std::string md = markdown_reference(test_schema());
  EXPECT_CONTAINS(md, "### [grid]\n");
  EXPECT_CONTAINS(md, "### [[body]]\n");
  EXPECT_CONTAINS(md, "### [body.sphere]\n");
  EXPECT_CONTAINS(md, "| key | type | unit | range | default | description |");
  EXPECT_CONTAINS(md, "| `cell_size` | length | m | > 0 | required | Edge of a grid cell |");
  EXPECT_CONTAINS(md, "| `cfl` | number | — | in (0, 1] | `0.5` | Courant number |");
  EXPECT_CONTAINS(md,
                  "| `shape_function` | choice | — | `linear`, `gimp`, `cpdi` | "
                  "`\"linear\"` |");
  EXPECT_CONTAINS(md, "| `velocity` | velocity vector[3] | m/s | — | `[0, 0, 0] m/s` |");
  EXPECT_CONTAINS(md, "| `interval` | time | s | > 0 | `1e-06 s` |");
  EXPECT_CONTAINS(md, "| `spin` | rate | 1/s | — | — |");
  EXPECT_CONTAINS(md, "Exactly one of [body.sphere], [body.box].");
}

}  // namespace
}  // namespace hvi::scene
