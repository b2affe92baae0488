// Unit parsing for scene files. A quantity is "<number> <unit expression>"; the unit expression is
// parsed by a small recursive-descent parser into a power of ten, a non-decimal factor (minutes,
// hours) and a dimension. Keeping the power of ten separate lets "0.5 mm" become exactly the
// double nearest to 5e-4 instead of accumulating rounding from repeated multiplications.
#include "cases/scene/units.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

namespace hvi::scene {
namespace {

// Dimensions of the derived units; not in dims:: because no scene key uses them directly.
constexpr Dim kForce{1, 1, -2, 0};
constexpr Dim kPower{2, 1, -3, 0};

// One unit symbol: its SI value is 10^decade * factor.
struct UnitDef {
  std::string_view symbol;
  int decade;
  double factor;
  Dim dim;
  bool prefixable;
};

constexpr std::array kUnits{
    UnitDef{"m", 0, 1.0, dims::length, true},
    UnitDef{"g", -3, 1.0, dims::mass, true},
    UnitDef{"s", 0, 1.0, dims::time, true},
    UnitDef{"K", 0, 1.0, dims::temperature, false},
    UnitDef{"N", 0, 1.0, kForce, true},
    UnitDef{"Pa", 0, 1.0, dims::pressure, true},
    UnitDef{"J", 0, 1.0, dims::energy, true},
    UnitDef{"W", 0, 1.0, kPower, true},
    UnitDef{"Hz", 0, 1.0, dims::rate, true},
    UnitDef{"bar", 5, 1.0, dims::pressure, true},
    UnitDef{"min", 0, 60.0, dims::time, false},
    UnitDef{"h", 0, 3600.0, dims::time, false},
    // Angles are dimensionless; SI is the radian.
    UnitDef{"deg", 0, std::numbers::pi / 180.0, dims::none, false},
    UnitDef{"rad", 0, 1.0, dims::none, false},
};

struct Prefix {
  std::string_view symbol;
  int decade;
};

// Micro is accepted as 'u', as the micro sign U+00B5 and as the Greek letter mu U+03BC, because
// keyboards and editors produce all three.
constexpr std::array kPrefixes{
    Prefix{"p", -12},       Prefix{"n", -9}, Prefix{"u", -6}, Prefix{"\xC2\xB5", -6},
    Prefix{"\xCE\xBC", -6}, Prefix{"m", -3}, Prefix{"c", -2}, Prefix{"k", 3},
    Prefix{"M", 6},         Prefix{"G", 9},  Prefix{"T", 12},
};

constexpr std::string_view kKnownUnits =
    "known units: m, g, s, K, degC, N, Pa, J, W, Hz, bar, min, h, deg, rad, with prefixes p n u µ "
    "m c k M G T, e.g. mm, km/s, g/cm^3, MPa, J/(kg K), 30 deg";

// Offset temperature unit: only meaningful as the whole unit of a value.
constexpr double kCelsiusOffset = 273.15;

bool is_celsius(std::string_view unit) {
  return unit == "degC" || unit ==
                               "\xC2\xB0"
                               "C";
}

// A unit expression evaluated so far: value = 10^decade * factor, dimension as plain ints so that
// intermediate products cannot overflow the int8 of Dim.
struct Scale {
  int decade = 0;
  double factor = 1.0;
  std::array<int, 4> exps{};

  void multiply(const Scale& other, int power) {
    decade += other.decade * power;
    factor *= std::pow(other.factor, power);
    for (std::size_t i = 0; i < exps.size(); ++i) exps[i] += other.exps[i] * power;
  }
};

Scale scale_of(const UnitDef& unit, int prefix_decade) {
  Scale s;
  s.decade = unit.decade + prefix_decade;
  s.factor = unit.factor;
  s.exps = {unit.dim.length, unit.dim.mass, unit.dim.time, unit.dim.temperature};
  return s;
}

// Resolves a symbol such as "km" or "Pa": an exact unit first (so "min" is minutes, not
// milli-inches), then a prefix followed by a prefixable unit.
std::optional<Scale> resolve_symbol(std::string_view symbol) {
  for (const UnitDef& unit : kUnits) {
    if (unit.symbol == symbol) return scale_of(unit, 0);
  }
  for (const Prefix& prefix : kPrefixes) {
    if (!symbol.starts_with(prefix.symbol)) continue;
    const std::string_view rest = symbol.substr(prefix.symbol.size());
    for (const UnitDef& unit : kUnits) {
      if (unit.prefixable && unit.symbol == rest) return scale_of(unit, prefix.decade);
    }
  }
  return std::nullopt;
}

bool is_space(char c) {
  return c == ' ' || c == '\t';
}
bool is_digit(char c) {
  return c >= '0' && c <= '9';
}
bool is_ascii_letter(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
}

std::string_view trim(std::string_view text) {
  while (!text.empty() && is_space(text.front())) text.remove_prefix(1);
  while (!text.empty() && (is_space(text.back()) || text.back() == '\n' || text.back() == '\r')) {
    text.remove_suffix(1);
  }
  return text;
}

// Recursive-descent parser of a unit expression:
//   product := term (operator term)*      operator: '*' '.' '·' '/' or whitespace
//   term    := ( '(' product ')' | symbol | '1' ) [ '^' integer ]
// A '/' divides by the next term only ("J/kg/K" = J kg^-1 K^-1). Multiplying after a division
// ("J/kg K") is rejected as ambiguous rather than guessed.
class UnitParser {
 public:
  explicit UnitParser(std::string_view unit) : text_(unit) {}

  Scale parse() {
    Scale result = product();
    skip_spaces();
    if (!at_end()) throw unexpected();
    return result;
  }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;

  bool at_end() const { return pos_ >= text_.size(); }
  char peek() const { return at_end() ? '\0' : text_[pos_]; }
  bool next_is(std::string_view s) const { return text_.substr(pos_).starts_with(s); }

  bool skip_spaces() {
    const std::size_t start = pos_;
    while (!at_end() && is_space(peek())) ++pos_;
    return pos_ != start;
  }

  // Byte length of a letter at the current position (ASCII or micro/mu), 0 if none.
  std::size_t letter_length() const {
    if (is_ascii_letter(peek())) return 1;
    if (next_is("\xC2\xB5") || next_is("\xCE\xBC")) return 2;
    return 0;
  }

  UnitError unexpected() const {
    const std::string_view before = trim(text_.substr(0, pos_));
    // Show a whole UTF-8 character rather than a lone lead byte.
    std::size_t len = 1;
    const auto lead = static_cast<unsigned char>(peek());
    if (lead >= 0xF0)
      len = 4;
    else if (lead >= 0xE0)
      len = 3;
    else if (lead >= 0xC0)
      len = 2;
    const std::string_view what = text_.substr(pos_, len);
    if (before.empty())
      return UnitError(fmt::format("unexpected '{}' in unit \"{}\"", what, text_));
    return UnitError(
        fmt::format("unexpected '{}' after \"{}\" in unit \"{}\"", what, before, text_));
  }

  Scale product() {
    Scale result = term();
    bool divided = false;
    while (true) {
      const bool spaced = skip_spaces();
      if (at_end() || peek() == ')') break;
      char op = '\0';
      if (peek() == '*' || peek() == '.') {
        op = '*';
        ++pos_;
      } else if (next_is("\xC2\xB7")) {  // middle dot
        op = '*';
        pos_ += 2;
      } else if (peek() == '/') {
        op = '/';
        ++pos_;
      } else if (spaced) {
        op = '*';  // whitespace multiplies: "kg m^-3"
      } else {
        throw unexpected();
      }
      if (op == '*' && divided) {
        throw UnitError(fmt::format(
            "ambiguous unit \"{}\": a product after '/' is unclear; use parentheses as in "
            "\"J/(kg K)\" or repeat the '/' as in \"J/kg/K\"",
            text_));
      }
      skip_spaces();
      if (at_end()) {
        throw UnitError(fmt::format("unit \"{}\" ends with an operator; a unit is missing", text_));
      }
      const Scale next = term();
      result.multiply(next, op == '/' ? -1 : 1);
      divided = divided || op == '/';
    }
    return result;
  }

  Scale term() {
    Scale base;
    std::string_view written;  // for messages about the exponent
    const std::size_t start = pos_;
    if (peek() == '(') {
      ++pos_;
      skip_spaces();
      base = product();
      skip_spaces();
      if (peek() != ')') {
        throw UnitError(fmt::format("missing ')' in unit \"{}\"", text_));
      }
      ++pos_;
    } else if (peek() == '1' && !is_digit(pos_ + 1 < text_.size() ? text_[pos_ + 1] : '\0')) {
      ++pos_;  // the "1" of "1/s"
    } else if (letter_length() > 0) {
      base = symbol();
    } else {
      throw unexpected();
    }
    written = text_.substr(start, pos_ - start);
    const int power = exponent(written);
    Scale result;
    result.multiply(base, power);
    return result;
  }

  Scale symbol() {
    const std::size_t start = pos_;
    for (std::size_t n = letter_length(); n > 0; n = letter_length()) pos_ += n;
    const std::string_view name = text_.substr(start, pos_ - start);
    if (name == "degC") {
      throw UnitError(
          "degC is an offset unit and must be the whole unit (\"20 degC\"); use K in compound "
          "units");
    }
    const std::optional<Scale> scale = resolve_symbol(name);
    if (!scale) throw UnitError(fmt::format("unknown unit '{}' ({})", name, kKnownUnits));
    // "m2" or "m-3": an exponent written without '^'.
    if (is_digit(peek()) || peek() == '-' || peek() == '+') {
      std::size_t end = pos_ + 1;
      while (end < text_.size() && is_digit(text_[end])) ++end;
      throw UnitError(fmt::format("malformed exponent in \"{}\": write {}^{}",
                                  text_.substr(start, end - start), name,
                                  text_.substr(pos_, end - pos_)));
    }
    return *scale;
  }

  // Optional "^<integer>" after a term; returns 1 when absent.
  int exponent(std::string_view base) {
    if (peek() != '^') return 1;
    ++pos_;
    const std::size_t start = pos_;
    if (peek() == '-' || peek() == '+') ++pos_;
    while (!at_end() && is_digit(peek())) ++pos_;
    std::string_view digits = text_.substr(start, pos_ - start);
    const bool fractional = peek() == '.' && pos_ + 1 < text_.size() && is_digit(text_[pos_ + 1]);
    if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
    int power = 0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), power);
    if (fractional || digits.empty() || ec != std::errc{} || end != digits.data() + digits.size() ||
        std::abs(power) > 12) {
      throw UnitError(fmt::format(
          "malformed exponent after \"{}^\" in unit \"{}\": expected a small integer as in "
          "m^2 or m^-3",
          base, text_));
    }
    return power;
  }
};

// Splits "<number><rest>" and parses the number. std::from_chars rejects a leading '+', and
// accepts "inf"/"nan", so the sign and the first character are checked here.
double parse_number(std::string_view text, std::string_view& rest) {
  std::size_t pos = 0;
  bool negative = false;
  if (pos < text.size() && (text[pos] == '+' || text[pos] == '-')) {
    negative = text[pos] == '-';
    ++pos;
  }
  const bool starts_numeric =
      pos < text.size() && (is_digit(text[pos]) ||
                            (text[pos] == '.' && pos + 1 < text.size() && is_digit(text[pos + 1])));
  if (!starts_numeric) {
    throw UnitError(fmt::format(
        "missing number: \"{}\" does not start with a number (write e.g. \"0.5 mm\")", text));
  }
  double value = 0.0;
  const char* first = text.data() + pos;
  const char* last = text.data() + text.size();
  const auto [end, ec] = std::from_chars(first, last, value);
  if (ec == std::errc::result_out_of_range) {
    throw UnitError(fmt::format("number in \"{}\" is out of range", text));
  }
  if (ec != std::errc{}) {
    throw UnitError(fmt::format("missing number: \"{}\" does not start with a number", text));
  }
  rest = text.substr(static_cast<std::size_t>(end - text.data()));
  return negative ? -value : value;
}

// value * 10^decade, dividing for negative decades so that exact powers of ten (up to 1e22) give
// correctly rounded results ("0.5 mm" -> 0.5 / 1000 == 5e-4).
double scale_decimal(double value, int decade) {
  if (decade == 0) return value;
  const double power = std::pow(10.0, std::abs(decade));
  return decade > 0 ? value * power : value / power;
}

Dim to_dim(const std::array<int, 4>& e) {
  for (int x : e) {
    if (x < std::numeric_limits<std::int8_t>::min() || x > std::numeric_limits<std::int8_t>::max())
      throw UnitError("unit exponent out of range");
  }
  return Dim{static_cast<std::int8_t>(e[0]), static_cast<std::int8_t>(e[1]),
             static_cast<std::int8_t>(e[2]), static_cast<std::int8_t>(e[3])};
}

struct NamedDim {
  Dim dim;
  std::string_view name;
  std::string_view unit;
  std::string_view example;
};

// Names, SI units and examples for the dimensions scene keys use. Units must be parseable by
// parse_quantity (tests check the round trip).
constexpr std::array kNamedDims{
    NamedDim{dims::none, "dimensionless number", "", "0.5"},
    NamedDim{dims::length, "length", "m", "0.5 mm"},
    NamedDim{dims::area, "area", "m^2", "1 mm^2"},
    NamedDim{dims::volume, "volume", "m^3", "1 cm^3"},
    NamedDim{dims::mass, "mass", "kg", "1 g"},
    NamedDim{dims::time, "time", "s", "10 us"},
    NamedDim{dims::temperature, "temperature", "K", "293 K"},
    NamedDim{dims::velocity, "velocity", "m/s", "4.5 km/s"},
    NamedDim{dims::acceleration, "acceleration", "m/s^2", "9.81 m/s^2"},
    NamedDim{dims::rate, "rate", "1/s", "1e3 1/s"},
    NamedDim{dims::density, "density", "kg/m^3", "2.77 g/cm^3"},
    NamedDim{dims::pressure, "pressure", "Pa", "265 MPa"},
    NamedDim{dims::energy, "energy", "J", "1 J"},
    NamedDim{dims::specific_energy, "specific energy", "J/kg", "1 MJ/kg"},
    NamedDim{dims::specific_heat, "specific heat", "J/(kg K)", "875 J/(kg K)"},
    NamedDim{dims::fracture_energy, "fracture energy", "J/m^2", "20 kJ/m^2"},
    NamedDim{kForce, "force", "N", "1 N"},
    NamedDim{kPower, "power", "W", "1 W"},
};

const NamedDim* find_named(Dim d) {
  for (const NamedDim& named : kNamedDims) {
    if (named.dim == d) return &named;
  }
  return nullptr;
}

constexpr std::array<std::string_view, 4> kBaseSymbols{"m", "kg", "s", "K"};

std::array<int, 4> exponents(Dim d) {
  return {d.length, d.mass, d.time, d.temperature};
}

std::string power_of(std::string_view symbol, int e) {
  return e == 1 ? std::string(symbol) : fmt::format("{}^{}", symbol, e);
}

}  // namespace

Quantity parse_quantity(std::string_view text) {
  const std::string_view trimmed = trim(text);
  if (trimmed.empty()) {
    throw UnitError("empty value: expected a number with a unit such as \"0.5 mm\"");
  }
  std::string_view rest;
  const double number = parse_number(trimmed, rest);
  const std::string_view unit = trim(rest);
  if (unit.empty()) return Quantity{number, dims::none, true};
  if (is_celsius(unit)) return Quantity{number + kCelsiusOffset, dims::temperature};

  const Scale scale = UnitParser(unit).parse();
  return Quantity{scale_decimal(number, scale.decade) * scale.factor, to_dim(scale.exps)};
}

std::string dimension_name(Dim d) {
  if (const NamedDim* named = find_named(d)) return std::string(named->name);
  // "m^2 kg s^-1": every base unit with its exponent, in the order m kg s K.
  const std::array<int, 4> e = exponents(d);
  std::vector<std::string> parts;
  for (std::size_t i = 0; i < e.size(); ++i) {
    if (e[i] != 0) parts.push_back(power_of(kBaseSymbols[i], e[i]));
  }
  return fmt::format("{}", fmt::join(parts, " "));
}

std::string si_unit(Dim d) {
  if (const NamedDim* named = find_named(d)) return std::string(named->unit);
  // "m kg/(s^2 K)": positive powers over negative ones, parenthesized when more than one.
  const std::array<int, 4> e = exponents(d);
  std::vector<std::string> numerator, denominator;
  for (std::size_t i = 0; i < e.size(); ++i) {
    if (e[i] > 0) numerator.push_back(power_of(kBaseSymbols[i], e[i]));
    if (e[i] < 0) denominator.push_back(power_of(kBaseSymbols[i], -e[i]));
  }
  const std::string top = numerator.empty() ? "1" : fmt::format("{}", fmt::join(numerator, " "));
  if (denominator.empty()) return top;
  if (denominator.size() == 1) return fmt::format("{}/{}", top, denominator.front());
  return fmt::format("{}/({})", top, fmt::join(denominator, " "));
}

std::string example_value(Dim d) {
  if (const NamedDim* named = find_named(d)) return std::string(named->example);
  return "1 " + si_unit(d);
}

std::string dimension_phrase(Dim d) {
  const NamedDim* named = find_named(d);
  if (!named) return "a quantity in " + si_unit(d);
  const bool vowel = std::string_view("aeiou").find(named->name.front()) != std::string_view::npos;
  return fmt::format("{} {}", vowel ? "an" : "a", named->name);
}

}  // namespace hvi::scene
