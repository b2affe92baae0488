#pragma once
// The values of a scene's [[measure]]s (cases/scene/measure_settings.hpp says what each kind
// measures), from the solver at the end of a run and from what the run tracked while it stepped.
#include <map>
#include <string>
#include <vector>

#include "cases/scene/measure_settings.hpp"

namespace hvi::mpm {
class Solver;
}

namespace hvi::driver {
// What a run tracks for the measures while it steps.
struct RunRecord {
  double initial_energy = 0.0;
  double peak_pressure = 0.0;
};

// Updates the running maxima (called at every energy.csv row).
void track(const mpm::Solver& solver, RunRecord& record);

// The measures that read points (extent_max/min, diameter, field_max/min) are each the largest
// of a pair (value, tie) over the points: the tie is the half spacing of the point that decides an
// extent or a diameter with surface = true, so two points at the same place decide it alike in
// any order. point_extrema gives this rank's pairs, in the order of the measures;
// mpm::Solver::max_pairs_over_ranks takes them over the ranks of a spread run.
std::vector<double> point_extrema(const std::vector<scene::MeasureSettings>& measures,
                                  const mpm::Solver& solver);

// Every measure but the holes and the probes, with the point extrema of all ranks (collective on
// a spread run: the energy).
std::map<std::string, double> evaluate(const std::vector<scene::MeasureSettings>& measures,
                                       const mpm::Solver& solver, const RunRecord& record,
                                       const std::vector<double>& extrema);

}  // namespace hvi::driver
