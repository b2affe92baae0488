#include "analysis/power_law_fit.hpp"

#include <cmath>

#include <fmt/format.h>
#include <Eigen/Dense>
#include <boost/math/distributions/students_t.hpp>

namespace hvi::analysis {

namespace {

// Relative spread of a log column below which a group counts as constant (round-off in values
// computed from the same inputs is ~1e-16).
constexpr double constant_tolerance = 1e-9;
// Smallest singular value, relative to the largest, of the standardised log columns: below it the
// groups are collinear and the exponents are not identifiable.
constexpr double collinear_tolerance = 1e-7;

std::string combination(const Eigen::VectorXd& null, const std::vector<std::string>& names) {
  const double top = null.cwiseAbs().maxCoeff();
  std::string s;
  for (Eigen::Index k = 0; k < null.size(); ++k) {
    const double c = null[k] / top;
    if (std::abs(c) < 1e-3) continue;
    s += fmt::format("{}{:.3g} ln({})", s.empty() ? (c < 0 ? "-" : "") : (c < 0 ? " - " : " + "),
                     std::abs(c), names[k]);
  }
  return s;
}

// Every response and group value must be positive and finite to enter a log-space fit.
void check_data(const PowerLawData& data) {
  const std::size_t n = data.response.size();
  const std::size_t m = data.groups.size();
  if (data.group_names.size() != m) throw FitError("a name for every group is needed");
  if (n == 0) throw FitError("no rows to fit");
  for (std::size_t i = 0; i < n; ++i)
    if (!(data.response[i] > 0) || !std::isfinite(data.response[i]))
      throw FitError(fmt::format("row {}: the response {} is not positive and finite", i + 1,
                                 data.response[i]));
  for (std::size_t j = 0; j < m; ++j) {
    if (data.groups[j].size() != n)
      throw FitError(fmt::format("group {} has {} values for {} rows", data.group_names[j],
                                 data.groups[j].size(), n));
    for (std::size_t i = 0; i < n; ++i)
      if (!(data.groups[j][i] > 0) || !std::isfinite(data.groups[j][i]))
        throw FitError(fmt::format("row {}: {} = {} is not positive and finite", i + 1,
                                   data.group_names[j], data.groups[j][i]));
  }
}

// The groups that vary (the fit's columns); a group the same in every row is noted in `fit`.
std::vector<std::size_t> varying_groups(const PowerLawData& data, PowerLawFit& fit) {
  std::vector<std::size_t> active;
  for (std::size_t j = 0; j < data.groups.size(); ++j) {
    Exponent& e = fit.exponents[j];
    e.group = data.group_names[j];
    double lo = INFINITY, hi = -INFINITY;
    for (const double g : data.groups[j]) {
      lo = std::min(lo, std::log(g));
      hi = std::max(hi, std::log(g));
    }
    if (hi - lo <= constant_tolerance * std::max(1.0, std::max(std::abs(lo), std::abs(hi)))) {
      e.fitted = false;
      e.note = fmt::format(
          "{} = {:.6g} in every row: its exponent cannot be fitted (the constant absorbs it)",
          e.group, data.groups[j][0]);
      fit.notes.push_back(e.note);
    } else {
      active.push_back(j);
    }
  }
  return active;
}

// Collinearity among the varying groups: singular values of the centred, unit-norm columns of
// the design matrix X (its first column the constant's).
void check_collinearity(const Eigen::MatrixXd& X, const PowerLawData& data,
                        const std::vector<std::size_t>& active) {
  if (active.empty()) return;
  Eigen::MatrixXd Z = X.rightCols(X.cols() - 1);
  Z.rowwise() -= Z.colwise().mean();
  Z.array().rowwise() /= Z.colwise().norm().array();
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(Z, Eigen::ComputeFullV);
  const Eigen::VectorXd sv = svd.singularValues();
  if (sv[sv.size() - 1] < collinear_tolerance * sv[0]) {
    std::vector<std::string> names;
    for (const std::size_t j : active) names.push_back(data.group_names[j]);
    throw FitError(fmt::format(
        "the groups vary together in these data (collinear in log space: {} is the same in "
        "every row), so their exponents cannot be told apart; add runs that vary them "
        "independently",
        combination(svd.matrixV().col(sv.size() - 1), names)));
  }
}

// Least squares ln y = X beta by QR, with the standard errors s^2 (X^T X)^-1, Student-t tests
// and R^2 of the logarithm and of the variable itself.
void solve(const Eigen::MatrixXd& X, const Eigen::VectorXd& y,
           const std::vector<std::size_t>& active, double alpha, PowerLawFit& fit) {
  const auto n = X.rows(), p = X.cols();
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(X);
  const Eigen::VectorXd beta = qr.solve(y);
  const Eigen::MatrixXd R = qr.matrixQR().topRows(p).triangularView<Eigen::Upper>();
  const Eigen::MatrixXd R_inv =
      R.triangularView<Eigen::Upper>().solve(Eigen::MatrixXd::Identity(p, p));
  const Eigen::VectorXd residual = y - X * beta;
  const double sse = residual.squaredNorm();
  fit.dof = static_cast<int>(n - p);
  const double s2 = sse / fit.dof;
  fit.residual_standard_deviation = std::sqrt(s2);
  const Eigen::MatrixXd cov = s2 * R_inv * R_inv.transpose();

  const boost::math::students_t student(fit.dof);
  fit.t_critical = boost::math::quantile(boost::math::complement(student, alpha / 2));
  fit.log_constant = beta[0];
  fit.log_constant_standard_error = std::sqrt(cov(0, 0));
  fit.constant = std::exp(beta[0]);
  fit.constant_standard_error = fit.constant * fit.log_constant_standard_error;
  for (std::size_t k = 0; k < active.size(); ++k) {
    Exponent& e = fit.exponents[active[k]];
    e.value = beta[k + 1];
    e.standard_error = std::sqrt(cov(k + 1, k + 1));
    e.t = e.standard_error > 0 ? e.value / e.standard_error : INFINITY;
    e.p_value = std::isfinite(e.t)
                    ? 2 * boost::math::cdf(boost::math::complement(student, std::abs(e.t)))
                    : 0.0;
    e.significant = e.p_value < alpha;
  }

  const double sst_log = (y.array() - y.mean()).square().sum();
  fit.r2_log = sst_log > 0 ? 1 - sse / sst_log : NAN;
  const Eigen::ArrayXd v = y.array().exp(), v_hat = (X * beta).array().exp();
  const double sst = (v - v.mean()).square().sum();
  fit.r2 = sst > 0 ? 1 - (v - v_hat).square().sum() / sst : NAN;
}

}  // namespace

PowerLawFit fit_power_law(const PowerLawData& data, double alpha) {
  check_data(data);
  const std::size_t n = data.response.size();
  PowerLawFit fit;
  fit.rows = n;
  fit.alpha = alpha;
  fit.exponents.resize(data.groups.size());
  const std::vector<std::size_t> active = varying_groups(data, fit);
  const std::size_t p = active.size() + 1;
  if (n <= p)
    throw FitError(
        fmt::format("{} row{} for {} parameter{} (the constant and {} exponent{}): standard errors "
                    "need at least {} rows",
                    n, n == 1 ? "" : "s", p, p == 1 ? "" : "s", active.size(),
                    active.size() == 1 ? "" : "s", p + 1));

  Eigen::MatrixXd X(n, p);
  Eigen::VectorXd y(n);
  for (std::size_t i = 0; i < n; ++i) {
    X(i, 0) = 1.0;
    y[i] = std::log(data.response[i]);
    for (std::size_t k = 0; k < active.size(); ++k)
      X(i, k + 1) = std::log(data.groups[active[k]][i]);
  }
  check_collinearity(X, data, active);
  solve(X, y, active, alpha, fit);
  return fit;
}

}  // namespace hvi::analysis
