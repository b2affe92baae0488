#pragma once
// The paper's dimensional-analysis power laws (Section 6), each fitted with fit_power_law:
//   front, eq. (15):  (D_f - d_p) / d_p = a0 (v_p / c_f)^a1 (t_f / d_p)^a2
//   rear,  eq. (18):  D_r / d_p = b0 (v_p^2 / (c_r c_hc))^b1 (t_hc / d_p)^b2 (t_hc / D_hc)^b3
//                                    (t_hc D_hc / S^2)^b4
//   taper, eq. (21):  t = (D_r - D_f) / S (eq. 12) = c0 (same four groups)^c1..c4
// (the density and sound-speed ratios of eqs. (13), (16), (19) are 1 in the paper's problems and
// left out, as there). Each row of the table is one run, with columns named as the variables
// (v_p, d_p, t_f, c_f, D_f, c_r, c_hc, t_hc, D_hc, S, D_r) in any consistent units: the groups
// are dimensionless.
//
// A row that lacks a variable (an NP rear facesheet has no D_r) is left out with a note; so is a
// row whose response is not positive, since its logarithm does not exist: a front hole no larger
// than the projectile, or a taper t <= 0 (a rear hole no larger than the front one, i.e. a straight
// or narrowing channel). Such rows are reported, never silently clipped.
#include <string>
#include <vector>

#include "analysis/power_law_fit.hpp"
#include "analysis/table.hpp"

namespace hvi::analysis {

enum class PowerLawForm { front, rear, taper };

// "front" | "rear" | "taper"; throws FitError otherwise.
PowerLawForm parse_form(const std::string& name);

struct FormData {
  std::string equation;                // the law, in words, with the paper's number
  std::string response;                // e.g. "(D_f - d_p)/d_p"
  std::string constant;                // a0 | b0 | c0
  std::vector<std::string> exponents;  // a1, a2 | b1..b4 | c1..c4
  PowerLawData data;
  std::vector<std::string> used;      // labels of the rows fitted
  std::vector<std::string> excluded;  // one message per row left out
};

FormData build_form(PowerLawForm form, const Table& table);

}  // namespace hvi::analysis
