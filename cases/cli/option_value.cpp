#include "cases/cli/option_value.hpp"

#include <stdexcept>

#include <fmt/format.h>

#include "cases/scene/units.hpp"

namespace hvi::driver {

double si_value(const std::string& text, const std::string& expect, const std::string& what) {
  scene::Quantity q;
  try {
    q = scene::parse_quantity(text);
  } catch (const scene::UnitError& e) {
    throw std::invalid_argument(fmt::format("{}'{}': {}", what, text, e.what()));
  }
  if (!expect.empty() && !q.bare && scene::dimension_name(q.dim) != expect)
    throw std::invalid_argument(fmt::format("{}'{}': expected a {}, got {}", what, text, expect,
                                            scene::dimension_phrase(q.dim)));
  return q.si;
}

}  // namespace hvi::driver
