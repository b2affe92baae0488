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

std::map<std::string, double> evaluate(const std::vector<scene::MeasureSettings>& measures,
                                       const mpm::Solver& solver, const RunRecord& record);

}  // namespace hvi::driver
