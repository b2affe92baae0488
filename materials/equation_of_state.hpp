#pragma once
// The equations of state a material can name (`eos = "<name>"` in a scene). Each is a law of the
// form p = cold(rho) + B(rho) e, linear in the specific internal energy e at a fixed density, so
// that the energy equation and the pressure are solved together in closed form (HydroMaterial).
// A law is one struct in its own header that gives:
//   name, summary             its scene name and a few words on it ("eqs. 4-5")
//   table, doc                its parameter table and the table's description
//   parameters                the ModelParameters of that table, in order
//   from(rho0, values)        the law from its reference density and those parameters' values
//   values()                  its parameters' values again, in the same order
//   at(rho)                   an EosState at density rho
//   bulk_sound_speed_squared(state, p), reference_sound_speed()
// and is registered by adding it to the variant below: the scene's choice, its table, the
// reader, the library and the solver all follow from that one line.
#include <type_traits>
#include <variant>

#include "materials/mie_gruneisen.hpp"

namespace hvi::materials {

using EquationOfState = std::variant<MieGruneisen>;

// Calls f(std::type_identity<Law>{}) for each registered law, in order.
template <class F>
void for_each_equation_of_state(F&& f) {
  [&]<class... Laws>(std::type_identity<std::variant<Laws...>>) {
    (f(std::type_identity<Laws>{}), ...);
  }(std::type_identity<EquationOfState>{});
}

inline EosState state_at(const EquationOfState& eos, double rho) {
  return std::visit([rho](const auto& law) { return law.at(rho); }, eos);
}
inline double bulk_sound_speed_squared(const EquationOfState& eos, const EosState& state,
                                       double p) {
  return std::visit([&](const auto& law) { return law.bulk_sound_speed_squared(state, p); }, eos);
}
inline double bulk_sound_speed_squared(const EquationOfState& eos, double rho, double p) {
  return bulk_sound_speed_squared(eos, state_at(eos, rho), p);
}
// The sound speed at the reference state, m/s (for measures that scale by it).
inline double reference_sound_speed(const EquationOfState& eos) {
  return std::visit([](const auto& law) { return law.reference_sound_speed(); }, eos);
}
inline const char* name_of(const EquationOfState& eos) {
  return std::visit([](const auto& law) { return std::decay_t<decltype(law)>::name; }, eos);
}

}  // namespace hvi::materials
