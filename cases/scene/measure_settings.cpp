#include <algorithm>

#include <fmt/format.h>

#include "cases/scene/measure_settings.hpp"

namespace hvi::scene {

TableSpec measure_table() {
  TableSpec t{.name = "measure",
              .doc = "A quantity measured at the end of the run (summary.json, hvi convergence).",
              .array = true};
  t.string_required("name", "Name of the quantity in the outputs")
      .choice_required("kind",
                       {"extent_max", "extent_min", "diameter", "field_max", "field_min",
                        "energy_error", "peak_pressure", "holes", "displacement"},
                       "What to measure (see docs/user/studies.md, Measures)")
      .choice("axis", {"x", "y", "z"}, "z",
              "Axis of an extent, or of the line a diameter is measured around")
      .string("body", "", "Restrict a geometric measure to this body (default: all)")
      .string("field", "", "Particle field of field_max / field_min")
      .boolean("surface", false,
               "Extents and diameters reach the surface: half the extreme particle's initial point "
               "spacing beyond its centre")
      .quantity("offset", dims::length, Range{}, 0.0,
                "Added to an extent or to the radius of a diameter")
      .optional_quantity("from", dims::length, Range{},
                         "Diameter: lowest coordinate along the axis of the particles counted")
      .optional_quantity("to", dims::length, Range{},
                         "Diameter: highest coordinate along the axis of the particles counted")
      .vector("center", dims::length, std::vector<double>{0, 0, 0}, "Diameter: a point of the line")
      .boolean("history", false,
               "Holes: also measure every snapshot as the run writes it, one row each in "
               "holes_history.csv "
               "(the columns of hvi measure's measurements_history.csv)")
      .optional_quantity("stop_when_settled", dims::time, positive(),
                         "Holes with history: stop the run once the rear sheet's outcome and hole "
                         "(or bulge) have stayed within settle_tolerance for this long")
      .number("settle_tolerance", closed(1e-6, 0.5), 0.02,
              "Holes with stop_when_settled: relative change of D_r (or the bulge) still settled")
      .vector("point", dims::length, std::nullopt,
              "Displacement: the probe's point in the undeformed configuration; its `axis` "
              "component is "
              "followed in probes.csv at every energy.csv row");
  return t;
}

std::vector<MeasureSettings> read_measures(const toml::array& tables, const Validated& v,
                                           const std::vector<std::string>& body_names,
                                           std::vector<Diagnostic>& errors) {
  std::vector<MeasureSettings> out;
  for (std::size_t i = 0; i < tables.size(); ++i) {
    const toml::table& t = *tables[i].as_table();
    MeasureSettings m;
    m.name = t["name"].value<std::string>().value();
    const std::string path = "measure." + m.name;
    m.kind = t["kind"].value<std::string>().value();
    m.axis = t["axis"].value<std::string>().value()[0] - 'x';
    m.body = t["body"].value<std::string>().value();
    m.field = t["field"].value<std::string>().value();
    m.offset = t["offset"].value<double>().value();
    m.surface = t["surface"].value<bool>().value();
    m.history = t["history"].value<bool>().value();
    m.stop_when_settled = t["stop_when_settled"].value<double>();
    m.settle_tolerance = t["settle_tolerance"].value<double>().value();
    m.from = t["from"].value<double>();
    m.to = t["to"].value<double>();
    const toml::array& c = *t["center"].as_array();
    for (int d = 0; d < 3; ++d) m.center[d] = c[d].value<double>().value();
    if (const toml::array* point = t["point"].as_array()) {
      m.point = std::array<double, 3>{};
      for (int d = 0; d < 3; ++d) (*m.point)[d] = (*point)[d].value<double>().value();
    }
    if ((m.kind == "displacement") != m.point.has_value())
      errors.push_back(v.at(
          path, m.point ? "`point` belongs to a displacement measure"
                        : "a displacement measure needs `point`, the probe's undeformed position"));
    if (!m.body.empty() &&
        std::find(body_names.begin(), body_names.end(), m.body) == body_names.end())
      errors.push_back(v.at(path + ".body", fmt::format("no body named '{}'", m.body)));
    if ((m.kind == "field_max" || m.kind == "field_min") && m.field.empty())
      errors.push_back(v.at(path, "a field measure needs `field` (e.g. \"plastic_strain\")"));
    if (m.history && m.kind != "holes")
      errors.push_back(
          v.at(path + ".history", "`history` belongs to a holes measure (kind = \"holes\")"));
    if (m.stop_when_settled && !m.history)
      errors.push_back(v.at(path + ".stop_when_settled",
                            "the rear sheet is judged settled on the holes history: "
                            "stop_when_settled needs history = true (and kind = \"holes\")"));
    if (m.kind == "holes" &&
        std::any_of(out.begin(), out.end(), [](const auto& o) { return o.kind == "holes"; }))
      errors.push_back(
          v.at(path + ".kind",
               "the holes are measured once per run: a second kind = \"holes\" measure"));
    for (const auto& other : out)
      if (other.name == m.name)
        errors.push_back(v.at(path + ".name", "a measure of this name is already defined"));
    out.push_back(m);
  }
  return out;
}

}  // namespace hvi::scene
