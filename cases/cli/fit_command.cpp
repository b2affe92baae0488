#include "cases/cli/fit_command.hpp"

#include <cmath>
#include <fstream>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <toml++/toml.h>

#include "analysis/dimensional_analysis.hpp"
#include "cases/run/run.hpp"

namespace hvi::driver {

namespace {

using namespace analysis;

// The fit as a table: the constant, each exponent with its standard error, t and p, and R^2.
void print_fit(const FormData& data, const PowerLawFit& fit) {
  for (const auto& n : fit.notes) fmt::print("  note: {}\n", n);
  fmt::print(
      "\n{:<6} {:<18} {:>10} {:>10} {:>9} {:>10}  significant at {:g}% (|t| > {:.3f}, {} dof)\n",
      "", "group", "value", "std error", "t", "p", 100 * fit.alpha, fit.t_critical, fit.dof);
  fmt::print("{:<6} {:<18} {:>10.5g} {:>10.3g}   (ln {} = {:.5g} +- {:.3g})\n", data.constant, "",
             fit.constant, fit.constant_standard_error, data.constant, fit.log_constant,
             fit.log_constant_standard_error);
  for (std::size_t j = 0; j < fit.exponents.size(); ++j) {
    const Exponent& e = fit.exponents[j];
    if (!e.fitted) {
      fmt::print("{:<6} {:<18} {:>10}  (constant in the data: not fitted)\n", data.exponents[j],
                 e.group, "-");
      continue;
    }
    fmt::print("{:<6} {:<18} {:>10.5g} {:>10.3g} {:>9.3g} {:>10.3g}  {}\n", data.exponents[j],
               e.group, e.value, e.standard_error, e.t, e.p_value, e.significant ? "yes" : "no");
  }
  fmt::print("\nR^2 = {:.4f} (ln {}), {:.4f} ({} itself); residual sd of ln {}: {:.4g}\n",
             fit.r2_log, data.response, fit.r2, data.response, data.response,
             fit.residual_standard_deviation);
}

// The fit as JSON (--json FILE).
void write_json(const FitOptions& o, const FormData& data, const PowerLawFit& fit) {
  toml::table j{
      {"form", o.form},
      {"equation", data.equation},
      {"rows", static_cast<std::int64_t>(fit.rows)},
      {"degrees_of_freedom", fit.dof},
      {"alpha", fit.alpha},
      {"t_critical", fit.t_critical},
      {"r2_log", fit.r2_log},
      {"r2", fit.r2},
      {data.constant, toml::table{{"value", fit.constant},
                                  {"standard_error", fit.constant_standard_error},
                                  {"log_value", fit.log_constant},
                                  {"log_standard_error", fit.log_constant_standard_error}}}};
  for (std::size_t k = 0; k < fit.exponents.size(); ++k) {
    const Exponent& e = fit.exponents[k];
    toml::table t{{"group", e.group}, {"fitted", e.fitted}};
    if (e.fitted) {
      t.insert("value", e.value);
      t.insert("standard_error", e.standard_error);
      t.insert("t", e.t);
      t.insert("p_value", e.p_value);
      t.insert("significant", e.significant);
    } else {
      t.insert("note", e.note);
    }
    j.insert(data.exponents[k], t);
  }
  toml::array excluded;
  for (const auto& e : data.excluded) excluded.push_back(e);
  j.insert("excluded_rows", excluded);
  std::ofstream out(o.json);
  out << toml::json_formatter(j) << '\n';
  fmt::print("output: {}\n", o.json.string());
}

}  // namespace

int fit_command(const FitOptions& o) {
  Table table;
  FormData data;
  try {
    for (const auto& input : o.inputs) table.append(read_table_or_runs(input));
    data = build_form(parse_form(o.form), table);
  } catch (const std::exception& e) {  // an unreadable table, missing columns: bad input
    fmt::print(stderr, "hvi fit: {}\n", e.what());
    return ExitCode::input_error;
  }
  std::vector<std::string> names;
  for (const auto& input : o.inputs) names.push_back(input.string());
  fmt::print("hvi fit {}: {}\n", fmt::join(names, " "), data.equation);
  for (const auto& e : data.excluded) fmt::print("  {}\n", e);
  fmt::print("{} of {} rows fitted\n", data.used.size(), table.rows.size());
  PowerLawFit fit;
  try {
    fit = fit_power_law(data.data, o.alpha);
  } catch (const FitError& e) {
    fmt::print(stderr, "hvi fit: {}\n", e.what());
    return ExitCode::input_error;
  }
  print_fit(data, fit);
  if (!o.json.empty()) write_json(o, data, fit);
  return ExitCode::success;
}

}  // namespace hvi::driver
