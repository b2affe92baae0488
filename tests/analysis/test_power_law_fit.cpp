// The dimensional-analysis power laws (paper eqs. 15, 18, 21) fitted by least squares in log
// space, on synthetic data with known coefficients.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include <gtest/gtest.h>

#include "analysis/dimensional_analysis.hpp"
#include "analysis/power_law_fit.hpp"

namespace hvi::analysis {
namespace {

namespace fs = std::filesystem;

// A parameter study shaped like the paper's (Sections 4-5): 5 velocities x 5 projectile sizes at
// the reference structure, then each structure parameter varied alone at two velocities (Table 7),
// and the front facesheet thickness at one. SI units.
struct StudyRun {
  double v_p, d_p, t_f, c, t_hc, D_hc, S;
};
std::vector<StudyRun> study(bool structure = true) {
  std::vector<StudyRun> runs;
  for (const double v : {1300.0, 2200.0, 2900.0, 3600.0, 4500.0})
    for (const double d : {8.81e-3, 11.10e-3, 15.07e-3, 18.99e-3, 23.92e-3})
      runs.push_back({v, d, 0.5e-3, 5350, 0.05e-3, 3.0e-3, 14.2e-3});
  if (!structure) return runs;
  for (const double v : {2200.0, 4500.0}) {
    for (const double D_hc : {1.5e-3, 4.5e-3})
      runs.push_back({v, 8.81e-3, 0.5e-3, 5350, 0.05e-3, D_hc, 14.2e-3});
    for (const double S : {4.5e-3, 5.4e-3, 7.1e-3, 21.3e-3})
      runs.push_back({v, 8.81e-3, 0.5e-3, 5350, 0.05e-3, 3.0e-3, S});
    for (const double t : {0.1e-3, 0.15e-3})
      runs.push_back({v, 8.81e-3, 0.5e-3, 5350, t, 3.0e-3, 14.2e-3});
  }
  for (const double tf : {0.3e-3, 1.0e-3})
    runs.push_back({4500, 8.81e-3, tf, 5350, 0.05e-3, 3.0e-3, 14.2e-3});
  return runs;
}

std::string fmt_double(double v) {
  std::ostringstream o;
  o.precision(17);
  o << v;
  return o.str();
}

// True coefficients (of the order of what such a study gives).
constexpr double a[3] = {1.8, 0.45, 0.35};                 // eq. (15)
constexpr double b[5] = {0.9, 0.30, 0.25, -0.20, 0.10};    // eq. (18)
constexpr double c[5] = {0.05, 0.60, 0.20, -0.30, -0.15};  // eq. (21)

std::array<double, 4> groups(const StudyRun& r) {
  return {r.v_p * r.v_p / (r.c * r.c), r.t_hc / r.d_p, r.t_hc / r.D_hc,
          r.t_hc * r.D_hc / (r.S * r.S)};
}
double law(const double* k, const std::array<double, 4>& g) {
  return k[0] * std::pow(g[0], k[1]) * std::pow(g[1], k[2]) * std::pow(g[2], k[3]) *
         std::pow(g[3], k[4]);
}

// One row per run: D_f from eq. (15), D_r from eq. (18) (or, with `taper_data`, D_r = D_f + S t
// with t from eq. (21)), each times exp(N(0, noise^2)).
Table table(const std::vector<StudyRun>& runs, double noise, bool taper_data = false) {
  std::mt19937 rng(2024);
  std::normal_distribution<double> normal(0.0, 1.0);
  auto factor = [&] { return noise > 0 ? std::exp(noise * normal(rng)) : 1.0; };
  Table t;
  t.columns = {"v_p", "d_p", "t_f", "c_f", "c_r", "c_hc", "t_hc", "D_hc", "S", "D_f", "D_r"};
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const StudyRun& r = runs[i];
    const auto g = groups(r);
    const double D_f =
        r.d_p * (1 + a[0] * std::pow(r.v_p / r.c, a[1]) * std::pow(r.t_f / r.d_p, a[2]) * factor());
    const double D_r = taper_data ? D_f + r.S * law(c, g) * factor() : r.d_p * law(b, g) * factor();
    std::vector<std::string> row;
    for (const double v : {r.v_p, r.d_p, r.t_f, r.c, r.c, r.c, r.t_hc, r.D_hc, r.S, D_f, D_r})
      row.push_back(fmt_double(v));
    t.rows.push_back(row);
    t.labels.push_back("run " + std::to_string(i));
  }
  return t;
}

PowerLawFit fit(PowerLawForm form, const Table& t) {
  return fit_power_law(build_form(form, t).data);
}

// Without noise every coefficient is recovered to round-off (1e-9 relative, against values of
// order 0.1-1 from 36 rows) and R^2 is 1.
TEST(PowerLawFit, ExactDataGiveTheCoefficients) {
  const Table t = table(study(), 0.0), tt = table(study(), 0.0, true);
  const PowerLawFit front = fit(PowerLawForm::front, t);
  EXPECT_NEAR(front.constant, a[0], 1e-9);
  for (int j = 0; j < 2; ++j) EXPECT_NEAR(front.exponents[j].value, a[j + 1], 1e-9);
  const PowerLawFit rear = fit(PowerLawForm::rear, t);
  EXPECT_NEAR(rear.constant, b[0], 1e-9);
  for (int j = 0; j < 4; ++j) EXPECT_NEAR(rear.exponents[j].value, b[j + 1], 1e-9) << "b" << j + 1;
  EXPECT_NEAR(rear.r2_log, 1.0, 1e-12);
  EXPECT_NEAR(rear.r2, 1.0, 1e-12);
  const PowerLawFit taper = fit(PowerLawForm::taper, tt);
  EXPECT_NEAR(taper.constant, c[0], 1e-9);
  for (int j = 0; j < 4; ++j) EXPECT_NEAR(taper.exponents[j].value, c[j + 1], 1e-9) << "c" << j + 1;
  EXPECT_EQ(taper.rows, study().size());
  EXPECT_EQ(taper.dof, static_cast<int>(study().size()) - 5);
}

// With log-normal noise (sd 0.05 in ln y) the true values lie within 3 standard errors (each a
// 99.7% interval; the seed is fixed, so the test is deterministic), the fit is good (R^2 > 0.9)
// and every non-zero exponent here is significant at 5%.
TEST(PowerLawFit, NoisyDataWithinThreeStandardErrors) {
  const Table t = table(study(), 0.05), tt = table(study(), 0.05, true);
  for (const auto form : {PowerLawForm::front, PowerLawForm::rear, PowerLawForm::taper}) {
    const PowerLawFit f = fit(form, form == PowerLawForm::taper ? tt : t);
    const double* truth = form == PowerLawForm::front ? a : form == PowerLawForm::rear ? b : c;
    EXPECT_NEAR(f.log_constant, std::log(truth[0]), 3 * f.log_constant_standard_error);
    for (std::size_t j = 0; j < f.exponents.size(); ++j) {
      const Exponent& e = f.exponents[j];
      EXPECT_NEAR(e.value, truth[j + 1], 3 * e.standard_error) << e.group;
      EXPECT_TRUE(e.significant) << e.group << " p = " << e.p_value;
      std::printf("%s: %s = %.4f +- %.4f (true %.2f, %.2f se off), t = %.1f, p = %.2g\n",
                  build_form(form, t).response.c_str(), e.group.c_str(), e.value, e.standard_error,
                  truth[j + 1], (e.value - truth[j + 1]) / e.standard_error, e.t, e.p_value);
    }
    EXPECT_GT(f.r2_log, 0.9);
    EXPECT_GT(f.r2, 0.9);
  }
}

// The statistics against closed forms: one group, y = c0 x^b; se(b) = s / sqrt(sum (ln x - mean)^2)
// and the critical t of 10 degrees of freedom at alpha = 0.05, 2.228139 (tables), p(t) = 0.05
// there.
TEST(PowerLawFit, StatisticsMatchClosedForms) {
  PowerLawData d;
  d.group_names = {"x"};
  d.groups.resize(1);
  std::mt19937 rng(1);
  std::normal_distribution<double> normal(0.0, 0.1);
  double sxx = 0, mean = 0;
  for (int i = 0; i < 12; ++i) {
    const double x = 1.0 + 0.5 * i;
    d.groups[0].push_back(x);
    d.response.push_back(2.0 * std::pow(x, 0.7) * std::exp(normal(rng)));
    mean += std::log(x) / 12;
  }
  for (const double x : d.groups[0]) sxx += (std::log(x) - mean) * (std::log(x) - mean);
  const PowerLawFit f = fit_power_law(d);
  EXPECT_EQ(f.dof, 10);
  EXPECT_NEAR(f.t_critical, 2.228139, 1e-6);
  EXPECT_NEAR(f.exponents[0].standard_error, f.residual_standard_deviation / std::sqrt(sxx), 1e-12);
  EXPECT_NEAR(f.exponents[0].t, f.exponents[0].value / f.exponents[0].standard_error, 1e-12);
}

// The paper's Section 4 study alone varies only v_p and d_p: t_hc/D_hc and t_hc D_hc/S^2 are the
// same in every row. Their exponents are reported as not fittable, the others are still found
// (exact data), and the constant absorbs the fixed groups: b0' = b0 g3^b3 g4^b4.
TEST(PowerLawFit, ConstantGroupIsReportedNotFitted) {
  const Table t = table(study(false), 0.0);
  const PowerLawFit f = fit(PowerLawForm::rear, t);
  EXPECT_TRUE(f.exponents[0].fitted);
  EXPECT_TRUE(f.exponents[1].fitted);
  EXPECT_FALSE(f.exponents[2].fitted);
  EXPECT_FALSE(f.exponents[3].fitted);
  EXPECT_NE(f.exponents[2].note.find("cannot be fitted"), std::string::npos);
  EXPECT_EQ(f.notes.size(), 2u);
  EXPECT_NEAR(f.exponents[0].value, b[1], 1e-9);
  EXPECT_NEAR(f.exponents[1].value, b[2], 1e-9);
  const auto g = groups(study(false)[0]);
  EXPECT_NEAR(f.constant, b[0] * std::pow(g[2], b[3]) * std::pow(g[3], b[4]), 1e-9);
}

// Groups that vary together cannot be told apart: only D_hc and v_p vary, so ln(t_hc/D_hc) +
// ln(t_hc D_hc/S^2) is constant. An error names them; no coefficients are returned.
TEST(PowerLawFit, CollinearGroupsAreAnError) {
  std::vector<StudyRun> runs;
  for (const double v : {2200.0, 3600.0, 4500.0})
    for (const double D_hc : {1.5e-3, 3.0e-3, 4.5e-3})
      runs.push_back({v, 8.81e-3, 0.5e-3, 5350, 0.05e-3, D_hc, 14.2e-3});
  // d_p fixed too: t_hc/d_p is constant (dropped with a note), the other two are collinear.
  try {
    fit(PowerLawForm::rear, table(runs, 0.01));
    FAIL() << "expected a FitError";
  } catch (const FitError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("t_hc/D_hc"), std::string::npos) << m;
    EXPECT_NE(m.find("t_hc D_hc/S^2"), std::string::npos) << m;
  }
}

// Rows that cannot enter the log-space fit are left out with a message: a rear facesheet not
// perforated (no D_r), a taper t <= 0 (rear hole no larger than the front one). Too few rows left
// is an error.
TEST(PowerLawFit, RowsLeftOutAreReported) {
  Table t = table(study(), 0.0, true);
  const int D_r = t.column("D_r"), D_f = t.column("D_f");
  t.rows[0][D_r] = "NP";
  t.rows[1][D_r] = t.rows[1][D_f];                      // t = 0
  t.rows[2][D_r] = fmt_double(t.number(2, D_f) * 0.9);  // t < 0
  const FormData form = build_form(PowerLawForm::taper, t);
  ASSERT_EQ(form.excluded.size(), 3u);
  EXPECT_NE(form.excluded[0].find("no value for D_r"), std::string::npos) << form.excluded[0];
  EXPECT_NE(form.excluded[1].find("not positive"), std::string::npos) << form.excluded[1];
  EXPECT_NE(form.excluded[2].find("not positive"), std::string::npos) << form.excluded[2];
  EXPECT_EQ(form.data.response.size(), study().size() - 3);
  const PowerLawFit f = fit_power_law(form.data);
  EXPECT_NEAR(f.exponents[0].value, c[1], 1e-9);

  // Three rows for three parameters (a0, a1, a2: v_p and d_p both vary): no degrees of freedom.
  const Table all = table(study(false), 0.0);
  Table few = all;
  few.rows = {all.rows[0], all.rows[6], all.rows[12]};
  few.labels = {all.labels[0], all.labels[6], all.labels[12]};
  EXPECT_THROW(fit(PowerLawForm::front, few), FitError);
  Table missing = few;
  missing.columns[missing.column("c_f")] = "c_front";
  EXPECT_THROW(build_form(PowerLawForm::front, missing), FitError);
}

// hvi fit DIR reads every run's measurements.csv below DIR.
TEST(PowerLawFit, TableFromRunDirectories) {
  const fs::path dir = fs::path(testing::TempDir()) / "hvi_fit_runs";
  fs::remove_all(dir);
  fs::create_directories(dir / "run_a");
  fs::create_directories(dir / "run_b");
  std::ofstream(dir / "run_a" / "measurements.csv") << "run,v_p,D_f\nrun_a,4500,0.01\n";
  std::ofstream(dir / "run_b" / "measurements.csv") << "run,v_p,D_r\nrun_b,2200,0.02\n";
  const Table t = read_table_or_runs(dir);
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_EQ(t.columns.size(), 4u);
  EXPECT_EQ(t.number(0, t.column("v_p")), 4500);
  EXPECT_TRUE(std::isnan(t.number(0, t.column("D_r"))));
  EXPECT_EQ(t.number(1, t.column("D_r")), 0.02);
  EXPECT_NE(t.labels[1].find("run_b"), std::string::npos);
}

// The fine-cell front law docs/verification/paper_cases.md and docs/log/paper_results.md quote,
// from the CSV they name: the figures there are this fit's, to the digits printed.
TEST(PowerLawFit, FineCellFrontHolesGiveTheDocumentedLaw) {
  const Table t =
      read_csv(fs::path(HVI_SOURCE_DIR) / "docs" / "verification" / "front_holes_0141.csv");
  ASSERT_EQ(t.rows.size(), 25u);
  const PowerLawFit f = fit(PowerLawForm::front, t);
  EXPECT_NEAR(f.constant, 5.689, 0.005);
  EXPECT_NEAR(f.log_constant, 1.7385, 0.0005);
  EXPECT_NEAR(f.log_constant_standard_error, 0.245, 0.0005);
  EXPECT_NEAR(f.exponents[0].value, 0.743, 0.0005);
  EXPECT_NEAR(f.exponents[0].standard_error, 0.059, 0.0005);
  EXPECT_NEAR(f.exponents[1].value, 1.026, 0.0005);
  EXPECT_NEAR(f.exponents[1].standard_error, 0.071, 0.0005);
  EXPECT_NEAR(f.r2_log, 0.9431, 0.0005);
  EXPECT_NEAR(f.r2, 0.934, 0.0005);
}

}  // namespace
}  // namespace hvi::analysis
