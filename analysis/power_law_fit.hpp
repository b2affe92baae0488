#pragma once
// A power law y = c0 prod_j g_j^{b_j} fitted by linear least squares in log space,
//   ln y = ln c0 + sum_j b_j ln g_j,
// the paper's method for eqs. (15), (18) and (21) ("multiple linear regression using least squares
// ... significance level alpha = 0.05"). With X the n x p design matrix (a column of ones and the
// ln g_j), beta = argmin |X beta - ln y|, s^2 = SSE / (n - p), Cov(beta) = s^2 (X^T X)^-1 (from the
// QR factor R: (X^T X)^-1 = R^-1 R^-T), standard errors the square roots of its diagonal,
// t_j = b_j / se_j, and b_j significant when the two-sided p-value of Student's t with n - p
// degrees of freedom is below alpha.
//
// A group that is the same in every row carries no information on its exponent: it is left out
// with a note (its value is absorbed into c0). Groups that vary together (collinear in log space)
// make the exponents unidentifiable: that is an error naming the combination, not a fit.
#include <stdexcept>
#include <string>
#include <vector>

namespace hvi::analysis {

class FitError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct PowerLawData {
  std::vector<double> response;  // y_i > 0
  std::vector<std::string> group_names;
  std::vector<std::vector<double>> groups;  // groups[j][i] > 0
};

struct Exponent {
  std::string group;
  bool fitted = true;  // false: constant across the data (see note)
  double value = 0, standard_error = 0, t = 0, p_value = 1;
  bool significant = false;
  std::string note;
};

struct PowerLawFit {
  std::size_t rows = 0;
  int dof = 0;          // n - p
  double constant = 0;  // c0 = exp(beta_0)
  double log_constant = 0, log_constant_standard_error = 0;
  double constant_standard_error = 0;      // c0 se(ln c0), the delta method
  std::vector<Exponent> exponents;         // one per group, in order
  double r2_log = 0;                       // 1 - SSE / SST of ln y
  double r2 = 0;                           // the same on y itself, with y_hat = exp(X beta)
  double residual_standard_deviation = 0;  // s, of ln y
  double alpha = 0.05;
  double t_critical = 0;  // t_{1 - alpha/2, n - p}
  std::vector<std::string> notes;
};

PowerLawFit fit_power_law(const PowerLawData& data, double alpha = 0.05);

}  // namespace hvi::analysis
