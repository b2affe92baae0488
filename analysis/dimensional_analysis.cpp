#include "analysis/dimensional_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace hvi::analysis {

PowerLawForm parse_form(const std::string& name) {
  if (name == "front") return PowerLawForm::front;
  if (name == "rear") return PowerLawForm::rear;
  if (name == "taper") return PowerLawForm::taper;
  throw FitError(fmt::format("unknown form '{}': expected front, rear or taper", name));
}

namespace {

using Row = std::map<std::string, double>;

struct Spec {
  std::string equation, response, constant;
  std::vector<std::string> exponents, variables, groups;
  std::function<double(const Row&)> y;
  std::vector<std::function<double(const Row&)>> g;
};

// The four groups of eqs. (17)-(21).
std::vector<std::function<double(const Row&)>> core_groups() {
  return {[](const Row& r) { return r.at("v_p") * r.at("v_p") / (r.at("c_r") * r.at("c_hc")); },
          [](const Row& r) { return r.at("t_hc") / r.at("d_p"); },
          [](const Row& r) { return r.at("t_hc") / r.at("D_hc"); },
          [](const Row& r) { return r.at("t_hc") * r.at("D_hc") / (r.at("S") * r.at("S")); }};
}
const std::vector<std::string> core_group_names = {"v_p^2/(c_r c_hc)", "t_hc/d_p", "t_hc/D_hc",
                                                   "t_hc D_hc/S^2"};

Spec spec(PowerLawForm form) {
  switch (form) {
    case PowerLawForm::front:
      return {"eq. (15): (D_f - d_p)/d_p = a0 (v_p/c_f)^a1 (t_f/d_p)^a2",
              "(D_f - d_p)/d_p",
              "a0",
              {"a1", "a2"},
              {"v_p", "d_p", "t_f", "c_f", "D_f"},
              {"v_p/c_f", "t_f/d_p"},
              [](const Row& r) { return (r.at("D_f") - r.at("d_p")) / r.at("d_p"); },
              {[](const Row& r) { return r.at("v_p") / r.at("c_f"); },
               [](const Row& r) { return r.at("t_f") / r.at("d_p"); }}};
    case PowerLawForm::rear:
      return {
          "eq. (18): D_r/d_p = b0 (v_p^2/(c_r c_hc))^b1 (t_hc/d_p)^b2 (t_hc/D_hc)^b3 (t_hc "
          "D_hc/S^2)^b4",
          "D_r/d_p",
          "b0",
          {"b1", "b2", "b3", "b4"},
          {"v_p", "d_p", "c_r", "c_hc", "t_hc", "D_hc", "S", "D_r"},
          core_group_names,
          [](const Row& r) { return r.at("D_r") / r.at("d_p"); },
          core_groups()};
    case PowerLawForm::taper:
      return {
          "eq. (21): t = (D_r - D_f)/S = c0 (v_p^2/(c_r c_hc))^c1 (t_hc/d_p)^c2 (t_hc/D_hc)^c3 "
          "(t_hc D_hc/S^2)^c4",
          "t",
          "c0",
          {"c1", "c2", "c3", "c4"},
          {"v_p", "d_p", "c_r", "c_hc", "t_hc", "D_hc", "S", "D_r", "D_f"},
          core_group_names,
          [](const Row& r) { return (r.at("D_r") - r.at("D_f")) / r.at("S"); },  // eq. (12)
          core_groups()};
  }
  throw FitError("unknown form");
}

}  // namespace

FormData build_form(PowerLawForm form, const Table& table) {
  const Spec s = spec(form);
  FormData out{s.equation, s.response, s.constant, s.exponents, {}, {}, {}};
  out.data.group_names = s.groups;
  out.data.groups.resize(s.groups.size());
  std::vector<std::string> missing;
  for (const auto& v : s.variables)
    if (table.column(v) < 0) missing.push_back(v);
  if (!missing.empty()) {
    std::string have;
    for (const auto& c : table.columns) have += (have.empty() ? "" : ", ") + c;
    throw FitError(fmt::format("the {} form needs the columns {}; missing: {} (the table has: {})",
                               s.response, fmt::join(s.variables, ", "), fmt::join(missing, ", "),
                               have));
  }
  for (std::size_t i = 0; i < table.rows.size(); ++i) {
    Row row;
    std::vector<std::string> absent;
    for (const auto& v : s.variables) {
      row[v] = table.number(i, table.column(v));
      if (!std::isfinite(row[v])) absent.push_back(v);
    }
    if (!absent.empty()) {
      out.excluded.push_back(
          fmt::format("{}: left out: no value for {}{}", table.labels[i], fmt::join(absent, ", "),
                      (std::find(absent.begin(), absent.end(), "D_r") != absent.end() ||
                       std::find(absent.begin(), absent.end(), "D_f") != absent.end())
                          ? " (not perforated?)"
                          : ""));
      continue;
    }
    const double y = s.y(row);
    if (!(y > 0)) {
      out.excluded.push_back(
          fmt::format("{}: left out: {} = {:.4g} is not positive, and a power law in log space "
                      "needs it to be",
                      table.labels[i], s.response, y));
      continue;
    }
    bool ok = true;
    for (std::size_t j = 0; j < s.g.size(); ++j)
      if (!(s.g[j](row) > 0)) {
        out.excluded.push_back(fmt::format("{}: left out: {} = {:.4g} is not positive",
                                           table.labels[i], s.groups[j], s.g[j](row)));
        ok = false;
        break;
      }
    if (!ok) continue;
    out.data.response.push_back(y);
    for (std::size_t j = 0; j < s.g.size(); ++j) out.data.groups[j].push_back(s.g[j](row));
    out.used.push_back(table.labels[i]);
  }
  return out;
}

}  // namespace hvi::analysis
