#pragma once
// hvi fit CSV_OR_DIR --form front|rear|taper: the paper's dimensional-analysis power laws
// (eqs. 15, 18, 21) fitted by least squares in log space (analysis/dimensional_analysis.hpp), with
// R^2 (log space and on the variable itself), standard errors, t statistics and the significance
// of each exponent at 5% (two-sided Student t, n - p degrees of freedom).
//   hvi fit runs/ --form rear            # every runs/*/measurements.csv (hvi measure)
//   hvi fit study.csv --form front --json front_fit.json
#include <filesystem>
#include <string>

namespace hvi::driver {

struct FitOptions {
  std::filesystem::path input;  // a CSV, or a directory of runs
  std::string form;             // front | rear | taper
  double alpha = 0.05;
  std::filesystem::path json;  // optional output
};

int fit_command(const FitOptions& options);

}  // namespace hvi::driver
