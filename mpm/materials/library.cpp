#include "mpm/materials/library.hpp"

#include <array>

namespace hvi::mpm {
namespace {

constexpr double GPa = 1e9, MPa = 1e6, g_cm3 = 1e3;

// A metal as its source publishes it, in the units sources use. A new library material is one
// more row of `published_metals` below.
struct Metal {
  const char* name;
  const char* source;
  double density;         // g/cm^3
  double youngs_modulus;  // GPa
  double poisson_ratio;
  double room_temperature;                     // K: the initial temperature and Johnson-Cook's T_r
  std::array<double, 6> strength;              // Johnson-Cook A (MPa), B (MPa), n, C, m, T_melt (K)
  std::optional<std::array<double, 3>> shock;  // Mie-Gruneisen c0 (m/s), s, Gamma0
  std::optional<std::array<double, 5>> damage;  // Johnson-Cook D1..D5
  std::optional<double> max_principal_stress;   // sigma_max, MPa
  double specific_heat;                         // J/(kg K)
};

// The paper's aluminium alloys share the Johnson-Cook strength of its Tables 1 and 4, its
// Poisson ratio, shock slope and Gruneisen coefficient; they differ in density, modulus, sound
// speed and failure model.
Metal paper_aluminium(const char* name, const char* source, double rho, double E, double c0,
                      std::optional<std::array<double, 5>> damage,
                      std::optional<double> sigma_max) {
  const std::array<double, 6> strength{265, 426, 0.34, 0.015, 1.0, 775};
  const std::array<double, 3> shock{c0, 1.34, 2.0};
  return {name, source, rho, E, 0.33, 293, strength, shock, damage, sigma_max, 875};
}

// The experiment database's alloys: 2xxx with [S96]'s 2024 Hugoniot and [JC85]'s 2024-T351
// damage; 7xxx with [S96]'s 7075 Hugoniot; honeycomb foils as the paper's core (Table 1).
Metal aluminium_2xxx(const char* name, const char* source, double rho,
                     std::array<double, 6> strength) {
  return {name,
          source,
          rho,
          72.4,
          0.33,
          293,
          strength,
          std::array<double, 3>{5328, 1.338, 2.0},
          std::array<double, 5>{0.13, 0.13, -1.5, 0.011, 0.0},
          std::nullopt,
          875};
}
Metal aluminium_7xxx(const char* name, const char* source, std::array<double, 6> strength,
                     std::array<double, 5> damage) {
  return {name,   source,       2.80,     71,
          0.33,   293,          strength, std::array<double, 3>{5200, 1.36, 2.2},
          damage, std::nullopt, 848};
}
Metal aluminium_foil(const char* name, const char* source, double rho) {
  return {name,
          source,
          rho,
          70,
          0.33,
          293,
          {265, 426, 0.34, 0.015, 1.0, 775},
          std::array<double, 3>{5240, 1.34, 2.0},
          std::array<double, 5>{0.13, 0.13, -1.5, 0.011, 0.0},
          std::nullopt,
          900};
}

std::vector<Metal> published_metals() {
  using D = std::array<double, 5>;
  using Shock = std::array<double, 3>;
  constexpr auto none = std::nullopt;
  // clang-format off
  return {
      // Table 1 (validation models).
      paper_aluminium("Al2017", "paper Table 1 (projectile, validation)", 2.79, 73, 5328,
                      none, 1580),
      paper_aluminium("Al2024-T81", "paper Table 1 (facesheets, validation)", 2.77, 75, 5330,
                      none, 1500),
      paper_aluminium("Al5052-H19", "paper Table 1 (honeycomb core, validation)", 2.68, 73, 5240,
                      D{0.13, 0.13, -1.50, 0.011, 0.0}, none),
      // Table 4 (parameter-study models).
      paper_aluminium("Al6061", "paper Table 4 (projectile and facesheets, study)", 2.77, 75, 5350,
                      D{-0.77, 1.45, -0.47, 0.0, 1.6}, none),
      paper_aluminium("Al5052", "paper Table 4 (honeycomb core, study)", 2.68, 73, 5350,
                      D{0.13, 0.13, -1.50, 0.011, 0.0}, none),
      // OFHC copper and 4340 steel: Johnson & Cook (1983, 1985) strength and damage; Steinberg's
      // shock data.
      {"OFHC-Cu", "Johnson & Cook 1983/1985; Steinberg 1996 (Us-up)", 8.96, 124, 0.34, 293,
       {90, 292, 0.31, 0.025, 1.09, 1356}, Shock{3940, 1.49, 2.02},
       D{0.54, 4.89, -3.03, 0.014, 1.12}, none, 383},
      {"4340-steel", "Johnson & Cook 1983/1985; Steinberg 1996 (Us-up)", 7.83, 200, 0.29, 293,
       {792, 510, 0.26, 0.014, 1.03, 1793}, Shock{4578, 1.33, 1.67},
       D{0.05, 3.44, -2.12, 0.002, 0.61}, none, 477},
      // The experiment database's alloys (cases/experiments/). Sources:
      //   [JC83] Johnson & Cook, 7th Int. Symp. Ballistics (1983): 2024-T351 strength.
      //   [JC85] Johnson & Cook, Eng. Fract. Mech. 21 (1985) 31-48: 2024-T351 damage.
      //   [L00]  Lesuer, DOT/FAA/AR-00/25 (2000): 2024-T3 strength.
      //   [BJH09] Brar, Joshi & Harris, AIP Conf. Proc. 1195 (2009) 945: 7075-T6 and 7075-T651
      //          strength and damage.
      //   [S96]  Steinberg, UCRL-MA-106439 (1996): 2024 and 7075 Us-up and Gruneisen.
      // No Johnson-Cook set is published for 7075-T73, 2024-T81, 2017-T4, 5056-H39, 5754-H22,
      // 3003 or 1100: each takes the published set named in its source string, the nearest in
      // alloy and yield (docs/user/materials.md gives the yields it misses).
      aluminium_2xxx("AA2024-T3", "[L00] strength, [JC85] 2024-T351 damage, [S96] 2024 EOS", 2.77,
                     {369, 684, 0.73, 0.0083, 1.7, 775}),
      aluminium_2xxx("AA2024-T81", "no published set: [L00] 2024-T3 strength (A 369 MPa; T81 "
                     "yields at 450), [JC85] 2024-T351 damage, [S96] 2024 EOS", 2.77,
                     {369, 684, 0.73, 0.0083, 1.7, 775}),
      aluminium_2xxx("AA2017-T4", "no published set: [JC83] 2024-T351 strength (A 265 MPa; 2017-T4 "
                     "yields at 275), [JC85] 2024-T351 damage, [S96] 2024 EOS", 2.80,
                     {265, 426, 0.34, 0.015, 1.0, 775}),
      aluminium_7xxx("AA7075-T6", "[BJH09] 7075-T6 strength and damage, [S96] 7075 EOS",
                     {546, 674, 0.72, 0.059, 1.56, 750}, D{-0.068, 0.451, -0.952, 0.036, 0.697}),
      aluminium_7xxx("AA7075-T73", "no published set: [BJH09] 7075-T651 strength and damage "
                     "(A 527 MPa; T73 yields at 434), [S96] 7075 EOS",
                     {527, 676, 0.71, 0.017, 1.61, 750}, D{0.110, 0.573, -3.4446, 0.016, 1.099}),
      aluminium_foil("AA5056-H39", "no published set: [JC83]/[JC85] 2024-T351, as the paper's "
                     "core (Table 1), and its Al5052-H19 EOS", 2.64),
      aluminium_foil("AA5754-H22", "no published set: [JC83]/[JC85] 2024-T351 (A 265 MPa; "
                     "5754-H22 yields at 185), the paper's Al5052-H19 EOS", 2.67),
      aluminium_foil("AA3003", "no published set: [JC83]/[JC85] 2024-T351, as the paper's core "
                     "(Table 1), and its Al5052-H19 EOS", 2.73),
      aluminium_2xxx("AA1100", "99.9% aluminium projectiles; no published set: [JC83] 2024-T351 "
                     "strength (far above 1100's 34-117 MPa yield, which matters little above "
                     "6 km/s), [JC85] damage, [S96] 2024 EOS", 2.70,
                     {265, 426, 0.34, 0.015, 1.0, 775}),
      // 42CrMo4 steel of the DynELA/Abaqus Taylor-bar code-to-code benchmark (no EOS data: the
      // benchmark uses the elastic bulk response).
      {"42CrMo4", "DynELA/Abaqus Taylor-bar benchmark", 7.83, 206.9, 0.3, 293.15,
       {806, 614, 0.168, 0.0089, 1.1, 1813.15}, none, none, none, 460},
  };
  // clang-format on
}

LibraryMaterial to_si(const Metal& metal) {
  LibraryMaterial m;
  m.name = metal.name;
  m.source = metal.source;
  HydroModels& p = m.parameters;
  p.density = metal.density * g_cm3;
  p.youngs_modulus = metal.youngs_modulus * GPa;
  p.poisson_ratio = metal.poisson_ratio;
  p.initial_temperature = metal.room_temperature;
  const auto& [A, B, n, C, m_exponent, melt] = metal.strength;
  p.johnson_cook =
      JohnsonCookStrength{A * MPa, B * MPa, n, C, m_exponent, melt, metal.room_temperature, 1.0};
  if (metal.shock)
    p.eos = MieGruneisen{p.density, (*metal.shock)[0], (*metal.shock)[1], (*metal.shock)[2]};
  if (metal.damage) {
    const auto& [D1, D2, D3, D4, D5] = *metal.damage;
    p.damage = JohnsonCookDamage{D1, D2, D3, D4, D5};
  }
  if (metal.max_principal_stress) p.max_principal_stress = *metal.max_principal_stress * MPa;
  m.specific_heat = metal.specific_heat;
  return m;
}

std::vector<LibraryMaterial> make_library() {
  std::vector<LibraryMaterial> lib;
  for (const Metal& metal : published_metals()) lib.push_back(to_si(metal));
  return lib;
}

}  // namespace

const std::vector<LibraryMaterial>& material_library() {
  static const std::vector<LibraryMaterial> lib = make_library();
  return lib;
}

const LibraryMaterial* find_library_material(const std::string& name) {
  for (const auto& m : material_library())
    if (m.name == name) return &m;
  return nullptr;
}

}  // namespace hvi::mpm
