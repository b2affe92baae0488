#pragma once
// Physical quantities with units, as written in scene files: "0.5 mm", "4.5 km/s", "10 us",
// "2.77 g/cm^3", "265 MPa", "875 J/(kg K)", "20 degC". Everything inside hvi is SI; this is the
// only place where other units exist.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

namespace hvi::scene {

// A physical dimension as integer exponents of the SI base units m, kg, s, K.
struct Dim {
  std::int8_t length = 0, mass = 0, time = 0, temperature = 0;
  friend constexpr bool operator==(Dim, Dim) = default;
};

namespace dims {
inline constexpr Dim none{};
inline constexpr Dim length{1, 0, 0, 0};
inline constexpr Dim area{2, 0, 0, 0};
inline constexpr Dim volume{3, 0, 0, 0};
inline constexpr Dim mass{0, 1, 0, 0};
inline constexpr Dim time{0, 0, 1, 0};
inline constexpr Dim temperature{0, 0, 0, 1};
inline constexpr Dim velocity{1, 0, -1, 0};
inline constexpr Dim acceleration{1, 0, -2, 0};
inline constexpr Dim rate{0, 0, -1, 0};  // strain rate, frequency
inline constexpr Dim density{-3, 1, 0, 0};
inline constexpr Dim pressure{-1, 1, -2, 0};  // stress, modulus
inline constexpr Dim energy{2, 1, -2, 0};
inline constexpr Dim specific_energy{2, 0, -2, 0};  // J/kg
inline constexpr Dim specific_heat{2, 0, -2, -1};   // J/(kg K)
inline constexpr Dim fracture_energy{0, 1, -2, 0};  // J/m^2, energy per unit area of crack
}  // namespace dims

// A value converted to SI together with the dimension its unit expressed.
struct Quantity {
  double si = 0.0;
  Dim dim{};
  bool bare = false;  // no unit written: a plain number, which a scene reads as SI
};

// Thrown by parse_quantity with a message that says what was wrong with the text
// (not where: the caller knows the file, line and key).
struct UnitError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Parses "<number> <unit expression>". The unit expression is a product of unit factors separated
// by '*', '/', '.', or a space, each factor optionally raised to an integer power with '^'
// ("m/s^2", "kg m^-3", "J/(kg K)"). Units: m, g, s, K, degC (offset, only alone), N, Pa, J, W, Hz,
// bar, min, h, the dimensionless angle units deg and rad (SI: rad), and SI prefixes
// (p n u µ m c k M G T) on m, g, s, N, Pa, J, W, Hz, bar.
// A bare number without unit is dimensionless. Throws UnitError on malformed text or an unknown
// unit.
Quantity parse_quantity(std::string_view text);

// Human name of a dimension, e.g. "length", "velocity", "pressure", or the SI expression
// ("m^2 kg s^-1") for dimensions without a name.
std::string dimension_name(Dim d);

// The SI unit of a dimension written as a unit expression ("m", "m/s", "Pa", "kg/m^3", ...).
std::string si_unit(Dim d);

// An example of a valid value for the dimension, for error messages ("0.5 mm", "4.5 km/s").
std::string example_value(Dim d);

// The dimension as a noun phrase with its article, for messages: "a length", "an acceleration",
// "a dimensionless number", "a quantity in m^2 kg s^-1".
std::string dimension_phrase(Dim d);

}  // namespace hvi::scene
