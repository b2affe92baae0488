#pragma once
// hvi measure RUN_DIR: the paper's hole measurements (Section 4.2, eqs. 8-12), the rear bulge and
// the debris cloud of a run, from its resolved scene and snapshots (a run still going has written
// whole snapshots only: each is renamed into place once complete). Writes
// RUN_DIR/measurements.json and RUN_DIR/measurements.csv (one header line and one row; SI units;
// the columns hvi fit reads). With --snapshot all, every snapshot: RUN_DIR/measurements_history.csv
// (the same columns, one row per snapshot), to see whether the holes have settled.
//   hvi measure runs/study_1g                      # last snapshot, panel facesheets
//   hvi measure runs/plate --front plate --snapshot 5 --axis "1 mm,0 mm"
//   hvi measure runs/validation_printed/case3 --snapshot all
//   hvi measure runs/long_run --snapshot all --out runs/long_run_so_far   # while it runs
// (--out: the files go to that directory instead of RUN_DIR.)
#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "analysis/bulge.hpp"
#include "analysis/debris.hpp"
#include "analysis/facesheet.hpp"

namespace hvi::driver {

struct MeasureOptions {
  std::filesystem::path run;
  std::string snapshot = "last";  // an index N (snapshots/particles_N.h5), "last" or "all"
  std::optional<std::array<double, 2>>
      axis;                 // impact point (x0, y0), m; default: the projectile's centroid
  double resolution = 0;    // raster pixel, m; 0: a quarter of the finest spacing
  std::string front, rear;  // facesheet bodies; default <panel>.front / .rear
  std::optional<double> core_height;  // S, m; default: the panel's
  analysis::DiameterRule front_rule = analysis::DiameterRule::two_chords;     // eq. (8)
  analysis::DiameterRule rear_rule = analysis::DiameterRule::six_directions;  // eqs. (9)-(10)
  double rotation = 0;         // of the measurement directions, rad
  bool mirror = true;          // mirror a half/quarter model across its symmetry planes
  double gap_closing = 0.375;  // see analysis/top_view.hpp
  double link_factor = 1.75;   // see analysis/clusters.hpp
  bool images = false;         // write the top views as PGM images
  // Where the files go (created if missing); empty: the run directory. Measuring a run that is
  // still going into a directory of its own leaves the run's directory as the run writes it.
  std::filesystem::path out;
};

struct SheetMeasurement {
  std::string body;
  analysis::HoleGeometry hole;
  double spacing = 0;         // finest point spacing of the sheet, m
  double closing_radius = 0;  // m
  std::size_t intact = 0, detached = 0;
};

struct Measurements {
  std::filesystem::path run;
  std::filesystem::path snapshot_file;
  double time = 0;
  std::int64_t step = 0;
  std::array<double, 2> axis{};
  analysis::MirrorPlanes mirror;
  std::optional<SheetMeasurement> front, rear;
  std::optional<double> taper, core_height;  // eq. (12); S
  std::optional<analysis::Bulge> bulge;      // rear facesheet not perforated
  analysis::Debris debris;
  // Detached spall: intact rear-sheet material no longer attached to the sheet (clusters.hpp) and
  // more than one spacing behind its back face; absent without a rear sheet.
  std::optional<analysis::Debris> spall;
  std::string debris_behind;  // the sheet whose back face it is measured from
  double debris_back_face = 0, debris_threshold = 0;  // z of the back face, m; threshold, m
  // The variables of the dimensional analysis (paper Section 6), where the scene defines them.
  std::vector<std::pair<std::string, double>>
      variables;  // v_p, d_p, t_f, t_r, c_f, c_r, c_hc, t_hc, D_hc, S
  std::vector<std::string> notes;
  // For images.
  std::optional<analysis::FacesheetResult> front_view, rear_view;
};

// Throws std::invalid_argument for bad input (no such run, body or snapshot; no initial snapshot).
Measurements measure_run(const MeasureOptions& options);
// Every snapshot of the run, in index order (options.snapshot is not read).
std::vector<Measurements> measure_history(const MeasureOptions& options);

// Prints the measurements (mm), writes measurements.json and .csv (SI); with --snapshot all, prints
// one line per snapshot and writes measurements_history.csv. Returns the exit code.
int measure_command(const MeasureOptions& options);

// The files, for tests and scripts.
void write_measurements(const Measurements& m, const std::filesystem::path& dir);
void write_history(const std::vector<Measurements>& history, const std::filesystem::path& dir);
// A run's own hole history (a holes measure with history = true): the columns of
// measurements_history.csv, one row appended per snapshot as the run writes it. Its own name, so
// that hvi measure --snapshot all on a run that kept only its newest snapshots leaves it whole.
inline constexpr const char* hole_history_file = "holes_history.csv";
// Appends m's row to `file`, the header first when the file is new or empty.
void append_history_row(const Measurements& m, const std::filesystem::path& file);
// Keeps the header and the rows of steps up to `last_step`: a run resumed from that step writes
// the later ones again. No file: nothing to do.
void keep_history_rows(const std::filesystem::path& file, std::int64_t last_step);
// Removes what the two above wrote into a run directory, and the sweep's log of the measurement
// (measure.log): a run replaced or continued makes them describe a state it no longer ends in.
void remove_measurements(const std::filesystem::path& dir);
// The printed report (mm).
void print_measurements(const Measurements& m);
// The headline numbers, SI, for a run's summary (the [[measure]] kind "holes"): front_perforated
// and rear_perforated (1 or 0), D_f, e_f, D_r, e_r (where perforated), taper, bulge (where not
// perforated), debris_mass.
std::vector<std::pair<std::string, double>> headline_quantities(const Measurements& m);

}  // namespace hvi::driver
