#include "cases/cli/analysis_cli.hpp"

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "cases/scene/units.hpp"

namespace hvi::driver {

namespace {

// A length ("0.5 mm"; a plain number in m).
double length(const std::string& text, const char* option) {
  scene::Quantity q;
  try {
    q = scene::parse_quantity(text);
  } catch (const scene::UnitError& e) {
    throw std::invalid_argument(fmt::format("{} '{}': {}", option, text, e.what()));
  }
  if (q.dim != scene::dims::length && q.dim != scene::dims::none)
    throw std::invalid_argument(
        fmt::format("{} '{}': expected a length (e.g. \"0.5 mm\")", option, text));
  return q.si;
}

double angle(const std::string& text, const char* option) {
  try {
    const scene::Quantity q = scene::parse_quantity(text);
    if (q.dim == scene::dims::none) return q.si;
  } catch (const scene::UnitError&) {
  }
  throw std::invalid_argument(
      fmt::format("{} '{}': expected an angle (e.g. \"60 deg\")", option, text));
}

analysis::DiameterRule rule(const std::string& text) {
  return text == "two-chords" ? analysis::DiameterRule::two_chords
                              : analysis::DiameterRule::six_directions;
}

}  // namespace

MeasureOptions MeasureCli::options() const {
  MeasureOptions o;
  o.run = run;
  o.snapshot = snapshot;
  if (!axis.empty()) {
    const auto comma = axis.find(',');
    if (comma == std::string::npos)
      throw std::invalid_argument(
          fmt::format("--axis '{}': expected x0,y0 (e.g. \"1 mm,0 mm\")", axis));
    o.axis = std::array<double, 2>{length(axis.substr(0, comma), "--axis"),
                                   length(axis.substr(comma + 1), "--axis")};
  }
  if (!resolution.empty()) o.resolution = length(resolution, "--resolution");
  if (!core_height.empty()) o.core_height = length(core_height, "--core-height");
  if (!rotation.empty()) o.rotation = angle(rotation, "--rotation");
  o.front = front;
  o.rear = rear;
  o.front_rule = rule(front_rule);
  o.rear_rule = rule(rear_rule);
  o.mirror = !no_mirror;
  o.gap_closing = gap_closing;
  o.link_factor = link_factor;
  o.images = images;
  o.out = out;
  return o;
}

std::unique_ptr<MeasureCli> add_measure_command(CLI::App& app) {
  auto m = std::make_unique<MeasureCli>();
  CLI::App* c = m->command = app.add_subcommand("measure",
                                                "Hole sizes of the facesheets (paper eqs. 8-12), "
                                                "rear bulge and debris cloud of a run (finished, "
                                                "or still going: its snapshots so far)");
  c->add_option("run", m->run, "Run directory (hvi run --out)")->required();
  c->add_option(
       "--snapshot", m->snapshot,
       "Snapshot index, 'last', or 'all' (one row per snapshot in measurements_history.csv)")
      ->capture_default_str();
  c->add_option("--axis", m->axis,
                "Impact point x0,y0 (default: the projectile's centroid at t = 0)");
  c->add_option("--resolution", m->resolution,
                "Raster pixel (default: a quarter of the finest point spacing)");
  c->add_option("--front", m->front, "Front facesheet body (default: <panel>.front)");
  c->add_option("--rear", m->rear, "Rear facesheet body (default: <panel>.rear)");
  c->add_option("--core-height", m->core_height,
                "S for the taper, eq. (12) (default: the panel's core_height)");
  c->add_option("--rotation", m->rotation,
                "Turn the measurement directions (e.g. \"60 deg\", as the paper's Fig. 5)");
  c->add_option("--front-rule", m->front_rule, "two-chords (eq. 8) or six-directions (eqs. 9-10)")
      ->check(CLI::IsMember({"two-chords", "six-directions"}))
      ->capture_default_str();
  c->add_option("--rear-rule", m->rear_rule, "two-chords (eq. 8) or six-directions (eqs. 9-10)")
      ->check(CLI::IsMember({"two-chords", "six-directions"}))
      ->capture_default_str();
  c->add_flag("--no-mirror", m->no_mirror,
              "Do not mirror a half/quarter model across its symmetry planes");
  c->add_option("--gap-closing", m->gap_closing, "Closing radius / point spacing (0: none)")
      ->check(CLI::Range(0.0, 2.0))
      ->capture_default_str();
  c->add_option("--link", m->link_factor,
                "Attached-cluster link / point spacing (0: keep detached pieces)")
      ->check(CLI::Range(0.0, 10.0))
      ->capture_default_str();
  c->add_flag("--images", m->images,
              "Write the top views as top_view_{front,rear}.pgm beside the measurements");
  c->add_option("--out", m->out,
                "Write the files to this directory instead of RUN (created if missing; for a run "
                "still going)");
  return m;
}

std::unique_ptr<FitCli> add_fit_command(CLI::App& app) {
  auto f = std::make_unique<FitCli>();
  CLI::App* c = f->command = app.add_subcommand(
      "fit", "Fit the paper's dimensional-analysis power laws (eqs. 15, 18, 21) to measured runs");
  c->add_option("input", f->options.inputs,
                "CSVs (one row per run) or directories of runs with measurements.csv; their rows "
                "are fitted together")
      ->required();
  c->add_option("--form", f->options.form, "front (eq. 15), rear (eq. 18) or taper (eq. 21)")
      ->required()
      ->check(CLI::IsMember({"front", "rear", "taper"}));
  c->add_option("--alpha", f->options.alpha, "Significance level")
      ->check(CLI::Range(1e-6, 0.5))
      ->capture_default_str();
  c->add_option("--json", f->options.json, "Also write the fit as JSON to this file");
  return f;
}

}  // namespace hvi::driver
