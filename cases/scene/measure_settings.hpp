#pragma once
// Quantities of interest a scene asks to be measured at the end of a run ([[measure]] tables):
// the numbers a resolution study follows (hvi convergence) and a user compares with experiment.
//   extent_max / extent_min   largest / smallest particle coordinate along `axis` (+ offset)
//   diameter                  2 (largest distance from the line through `center` along `axis`
//                             + offset), over particles whose coordinate along `axis` lies in
//                             [from, to]
//   field_max / field_min     extreme of a particle field (e.g. plastic_strain, temperature)
//   energy_error              (E_end - E_0) / E_0, E = kinetic + internal + dissipated + removed
//   peak_pressure             the largest mean pressure seen at any energy.csv row
//   holes                     the panel's hole measurements (hvi measure, paper eqs. 8-12) on the
//                             final snapshot: front_perforated, D_f, e_f, rear_perforated, D_r,
//                             e_r, taper, bulge, debris_mass (measurements.json has the rest);
//                             `body`: the front sheet (default: the panel's)
//   displacement              the `axis` component of the displacement at `point` (undeformed
//                             position): in a hybrid's far field (point outside the MPM zone) of
//                             the nearest node, else the mean over the particles within one grid
//                             cell of the point, of the nearest particle's body (or `body`);
//                             followed over time in probes.csv (probes.hpp)
// `body` restricts a geometric measure to one body. With `surface`, an extent or a diameter's
// radius reaches from the extreme particle's centre to the surface: half its initial point spacing
// (V0^(1/3) / 2) further, so that the same measure holds at any resolution.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "cases/scene/schema.hpp"

namespace hvi::scene {
struct MeasureSettings {
  std::string name, kind, field, body;
  int axis = 2;
  double offset = 0.0;
  bool surface = false;
  bool history = false;  // holes: measured at every snapshot as the run writes it
  // holes with history: stop once the rear sheet has settled over this time (cases/run/settle.hpp)
  std::optional<double> stop_when_settled;
  double settle_tolerance = 0.02;
  std::optional<double> from, to;
  std::array<double, 3> center{};
  std::optional<std::array<double, 3>> point;  // displacement
};

TableSpec measure_table();
// Reads the resolved [[measure]] tables; problems go to `errors` (located by `v`).
std::vector<MeasureSettings> read_measures(const toml::array& tables, const Validated& v,
                                           const std::vector<std::string>& body_names,
                                           std::vector<Diagnostic>& errors);

}  // namespace hvi::scene
