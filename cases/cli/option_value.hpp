#pragma once
// A command-line value with a unit ("0.5 mm", "4.5 km/s"), in SI, as scenes read values.
#include <string>

namespace hvi::driver {

// Of dimension `expect` (by name: "length", "velocity", ...) unless that is empty; a plain number
// is SI. `what` names the option in messages ("--point "), or is empty. Throws
// std::invalid_argument.
double si_value(const std::string& text, const std::string& expect, const std::string& what);

}  // namespace hvi::driver
