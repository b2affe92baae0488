#pragma once
// hvi fit CSV_OR_DIR... --form front|rear|taper: the paper's dimensional-analysis power laws
// (eqs. 15, 18, 21) fitted by least squares in log space (analysis/dimensional_analysis.hpp), with
// R^2 (log space and on the variable itself), standard errors, t statistics and the significance
// of each exponent at 5% (two-sided Student t, n - p degrees of freedom).
//   hvi fit runs/ --form rear            # every runs/*/measurements.csv (hvi measure)
//   hvi fit study.csv --form front --json front_fit.json
//   hvi fit runs/study runs/structure --form rear   # the paper fits eq. (18) to both studies
#include <filesystem>
#include <string>
#include <vector>

namespace hvi::driver {

struct FitOptions {
  std::vector<std::filesystem::path> inputs;  // CSVs or directories of runs, merged
  std::string form;                           // front | rear | taper
  double alpha = 0.05;
  std::filesystem::path json;  // optional output
};

int fit_command(const FitOptions& options);

}  // namespace hvi::driver
