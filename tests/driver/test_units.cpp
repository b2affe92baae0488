// Unit parsing of scene values: every conversion the scene files use, and the error messages for
// each way the text can be wrong.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "cases/scene/units.hpp"

namespace hvi::scene {
namespace {

// Checks value (to 1e-12 relative) and dimension of a parsed quantity.
void expect_quantity(std::string_view text, double si, Dim dim) {
  SCOPED_TRACE(std::string(text));
  const Quantity q = parse_quantity(text);
  EXPECT_NEAR(q.si, si, 1e-12 * std::abs(si));
  EXPECT_EQ(q.dim, dim) << "got " << dimension_name(q.dim);
}

// The UnitError message for a text, or "" when it parses.
std::string unit_error(std::string_view text) {
  try {
    parse_quantity(text);
  } catch (const UnitError& e) {
    return e.what();
  }
  return "";
}

TEST(Units, LengthTimeVelocity) {
  EXPECT_EQ(parse_quantity("0.5 mm").si, 5e-4);  // exact: the power of ten is applied once
  expect_quantity("0.5 mm", 5e-4, dims::length);
  expect_quantity("4.5 km/s", 4500.0, dims::velocity);
  expect_quantity("-4.5 km/s", -4500.0, dims::velocity);
  expect_quantity("10 us", 1e-5, dims::time);
  expect_quantity("10 \xC2\xB5s", 1e-5, dims::time);  // micro sign
  expect_quantity("10 \xCE\xBCs", 1e-5, dims::time);  // Greek mu
  expect_quantity("3 ns", 3e-9, dims::time);
  expect_quantity("2 min", 120.0, dims::time);
  expect_quantity("1.5 h", 5400.0, dims::time);
  expect_quantity("1 m/s^2", 1.0, dims::acceleration);
  expect_quantity("2 cm", 0.02, dims::length);
}

TEST(Units, DensityPressureEnergy) {
  expect_quantity("2.77 g/cm^3", 2770.0, dims::density);
  expect_quantity("2770 kg m^-3", 2770.0, dims::density);
  expect_quantity("2770 kg*m^-3", 2770.0, dims::density);
  expect_quantity("2770 kg.m^-3", 2770.0, dims::density);
  expect_quantity("265 MPa", 265e6, dims::pressure);
  expect_quantity("73 GPa", 73e9, dims::pressure);
  expect_quantity("1 bar", 1e5, dims::pressure);
  expect_quantity("2 kbar", 2e8, dims::pressure);
  expect_quantity("1 N/m^2", 1.0, dims::pressure);
  expect_quantity("875 J/(kg K)", 875.0, dims::specific_heat);
  expect_quantity("875 J/kg/K", 875.0, dims::specific_heat);
  expect_quantity("0.875 kJ / (kg K)", 875.0, dims::specific_heat);
  expect_quantity("5 MJ/kg", 5e6, dims::specific_energy);
  expect_quantity("1 W s", 1.0, dims::energy);
}

TEST(Units, RatesTemperatureAndPlainNumbers) {
  expect_quantity("1e3 1/s", 1000.0, dims::rate);
  expect_quantity("1000 s^-1", 1000.0, dims::rate);
  expect_quantity("50 Hz", 50.0, dims::rate);
  expect_quantity("293 K", 293.0, dims::temperature);
  expect_quantity("20 degC", 293.15, dims::temperature);
  expect_quantity(
      "-20 \xC2\xB0"
      "C",
      253.15, dims::temperature);
  expect_quantity("1.5", 1.5, dims::none);
  expect_quantity("  0.5 mm  ", 5e-4, dims::length);
  expect_quantity("+2e-3 m", 2e-3, dims::length);
  expect_quantity(".5 m", 0.5, dims::length);
  expect_quantity("5e-4m", 5e-4, dims::length);
}

// Angles (the honeycomb pattern's rotation, a surface's placement) are dimensionless; SI: rad.
TEST(Units, Angles) {
  expect_quantity("30 deg", std::acos(-1.0) / 6, dims::none);
  expect_quantity("-90 deg", -std::acos(-1.0) / 2, dims::none);
  expect_quantity("0.5 rad", 0.5, dims::none);
  EXPECT_NE(unit_error("30 mdeg"), "");  // no prefixes on angle units
}

TEST(Units, UnknownUnitListsKnownUnits) {
  const std::string message = unit_error("3 furlong");
  EXPECT_NE(message.find("unknown unit 'furlong'"), std::string::npos) << message;
  EXPECT_NE(message.find("known units: m, g, s"), std::string::npos) << message;
  EXPECT_NE(unit_error("1 T").find("unknown unit 'T'"), std::string::npos);
  EXPECT_NE(unit_error("1 mK").find("unknown unit 'mK'"), std::string::npos);  // K takes no prefix
}

TEST(Units, MissingNumber) {
  EXPECT_NE(unit_error("mm").find("missing number"), std::string::npos) << unit_error("mm");
  EXPECT_NE(unit_error("inf m").find("missing number"), std::string::npos);
  EXPECT_NE(unit_error("").find("empty value"), std::string::npos);
  EXPECT_NE(unit_error("   ").find("empty value"), std::string::npos);
}

TEST(Units, MalformedExponent) {
  for (const char* text : {"1 m^", "1 m^x", "1 m^1.5", "1 m^-"}) {
    EXPECT_NE(unit_error(text).find("malformed exponent"), std::string::npos)
        << text << ": " << unit_error(text);
  }
  const std::string message = unit_error("1 m2");
  EXPECT_NE(message.find("malformed exponent in \"m2\": write m^2"), std::string::npos) << message;
  EXPECT_NE(unit_error("1 m-3").find("write m^-3"), std::string::npos) << unit_error("1 m-3");
}

TEST(Units, TrailingGarbageAndStructure) {
  const std::string message = unit_error("0.5 mm)");
  EXPECT_NE(message.find("unexpected ')' after \"mm\""), std::string::npos) << message;
  EXPECT_NE(unit_error("0.5 mm 3").find("unexpected '3'"), std::string::npos)
      << unit_error("0.5 mm 3");
  EXPECT_NE(unit_error("1 J/(kg K").find("missing ')'"), std::string::npos);
  EXPECT_NE(unit_error("1 m/").find("ends with an operator"), std::string::npos);
  EXPECT_NE(unit_error("1.5.3 m").find("unexpected '.'"), std::string::npos)
      << unit_error("1.5.3 m");
}

TEST(Units, AmbiguousProductAfterDivisionIsRejected) {
  const std::string message = unit_error("875 J/kg K");
  EXPECT_NE(message.find("ambiguous"), std::string::npos) << message;
  EXPECT_NE(message.find("J/(kg K)"), std::string::npos) << message;
}

TEST(Units, CelsiusOnlyAsWholeUnit) {
  const std::string message = unit_error("20 degC/s");
  EXPECT_NE(message.find("degC is an offset unit"), std::string::npos) << message;
}

TEST(Units, DimensionNamesUnitsAndExamples) {
  EXPECT_EQ(dimension_name(dims::length), "length");
  EXPECT_EQ(dimension_name(dims::velocity), "velocity");
  EXPECT_EQ(dimension_name(dims::density), "density");
  EXPECT_EQ(dimension_name(dims::pressure), "pressure");
  EXPECT_EQ(dimension_name(dims::time), "time");
  EXPECT_EQ(dimension_name(dims::specific_heat), "specific heat");
  EXPECT_EQ(dimension_name(dims::specific_energy), "specific energy");
  EXPECT_EQ(dimension_name(Dim{2, 1, -1, 0}), "m^2 kg s^-1");
  EXPECT_EQ(si_unit(dims::length), "m");
  EXPECT_EQ(si_unit(dims::velocity), "m/s");
  EXPECT_EQ(si_unit(dims::density), "kg/m^3");
  EXPECT_EQ(si_unit(dims::pressure), "Pa");
  EXPECT_EQ(si_unit(dims::specific_heat), "J/(kg K)");
  EXPECT_EQ(si_unit(dims::rate), "1/s");
  EXPECT_EQ(si_unit(Dim{2, 1, -1, -1}), "m^2 kg/(s K)");
  EXPECT_EQ(example_value(dims::length), "0.5 mm");
  EXPECT_EQ(example_value(dims::velocity), "4.5 km/s");
  EXPECT_EQ(example_value(dims::time), "10 us");
  EXPECT_EQ(example_value(dims::density), "2.77 g/cm^3");
  EXPECT_EQ(example_value(dims::pressure), "265 MPa");
  EXPECT_EQ(example_value(dims::temperature), "293 K");
  EXPECT_EQ(example_value(dims::specific_heat), "875 J/(kg K)");
  EXPECT_EQ(example_value(dims::none), "0.5");
  EXPECT_EQ(dimension_phrase(dims::length), "a length");
  EXPECT_EQ(dimension_phrase(dims::acceleration), "an acceleration");
}

// Every dimension constant has a name, and its SI unit and example parse back to it, so messages
// never suggest text the parser rejects.
TEST(Units, UnitsAndExamplesRoundTrip) {
  const Dim all[] = {dims::none,          dims::length,
                     dims::area,          dims::volume,
                     dims::mass,          dims::time,
                     dims::temperature,   dims::velocity,
                     dims::acceleration,  dims::rate,
                     dims::density,       dims::pressure,
                     dims::energy,        dims::specific_energy,
                     dims::specific_heat, Dim{2, 1, -1, -1}};
  for (const Dim d : all) {
    SCOPED_TRACE(dimension_name(d));
    EXPECT_FALSE(dimension_name(d).empty());
    EXPECT_EQ(parse_quantity(example_value(d)).dim, d);
    if (d == dims::none) continue;
    const Quantity unit = parse_quantity("1 " + si_unit(d));
    EXPECT_EQ(unit.dim, d);
    EXPECT_DOUBLE_EQ(unit.si, 1.0);
  }
}

}  // namespace
}  // namespace hvi::scene
