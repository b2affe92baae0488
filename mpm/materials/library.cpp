#include "mpm/materials/library.hpp"

namespace hvi::mpm {
namespace {

constexpr double GPa = 1e9, MPa = 1e6, g_cm3 = 1e3;

// The paper's aluminium alloys share the Johnson-Cook strength parameters of its Tables 1 and 4.
JohnsonCookStrength paper_aluminium_strength() {
  JohnsonCookStrength jc;
  jc.A = 265 * MPa;
  jc.B = 426 * MPa;
  jc.n = 0.34;
  jc.C = 0.015;
  jc.m = 1.0;
  jc.melt_temperature = 775;
  jc.room_temperature = 293;
  return jc;
}

LibraryMaterial paper_aluminium(const char* name, const char* source, double rho, double E,
                                double c0, std::optional<JohnsonCookDamage> damage,
                                std::optional<double> sigma_max) {
  LibraryMaterial m;
  m.name = name;
  m.source = source;
  HydroModels& p = m.parameters;
  p.density = rho * g_cm3;
  p.youngs_modulus = E * GPa;
  p.poisson_ratio = 0.33;
  p.initial_temperature = 293;
  p.johnson_cook = paper_aluminium_strength();
  p.eos = MieGruneisen{p.density, c0, 1.34, 2.0};
  p.damage = damage;
  if (sigma_max) p.max_principal_stress = *sigma_max * MPa;
  m.specific_heat = 875;
  return m;
}

JohnsonCookDamage jc_damage(double D1, double D2, double D3, double D4, double D5) {
  JohnsonCookDamage d;
  d.D1 = D1;
  d.D2 = D2;
  d.D3 = D3;
  d.D4 = D4;
  d.D5 = D5;
  return d;
}

std::vector<LibraryMaterial> make_library() {
  std::vector<LibraryMaterial> lib;
  // Table 1 (validation models).
  lib.push_back(paper_aluminium("Al2017", "paper Table 1 (projectile, validation)", 2.79, 73, 5328,
                                std::nullopt, 1580));
  lib.push_back(paper_aluminium("Al2024-T81", "paper Table 1 (facesheets, validation)", 2.77, 75,
                                5330, std::nullopt, 1500));
  lib.push_back(paper_aluminium("Al5052-H19", "paper Table 1 (honeycomb core, validation)", 2.68,
                                73, 5240, jc_damage(0.13, 0.13, -1.50, 0.011, 0.0), std::nullopt));
  // Table 4 (parameter-study models).
  lib.push_back(paper_aluminium("Al6061", "paper Table 4 (projectile and facesheets, study)", 2.77,
                                75, 5350, jc_damage(-0.77, 1.45, -0.47, 0.0, 1.6), std::nullopt));
  lib.push_back(paper_aluminium("Al5052", "paper Table 4 (honeycomb core, study)", 2.68, 73, 5350,
                                jc_damage(0.13, 0.13, -1.50, 0.011, 0.0), std::nullopt));
  {
    // OFHC copper: Johnson & Cook (1983, 1985) strength and damage; Steinberg's shock data.
    LibraryMaterial m;
    m.name = "OFHC-Cu";
    m.source = "Johnson & Cook 1983/1985; Steinberg 1996 (Us-up)";
    HydroModels& p = m.parameters;
    p.density = 8.96 * g_cm3;
    p.youngs_modulus = 124 * GPa;
    p.poisson_ratio = 0.34;
    p.johnson_cook = JohnsonCookStrength{90 * MPa, 292 * MPa, 0.31, 0.025, 1.09, 1356, 293, 1.0};
    p.eos = MieGruneisen{p.density, 3940, 1.49, 2.02};
    p.damage = jc_damage(0.54, 4.89, -3.03, 0.014, 1.12);
    m.specific_heat = 383;
    lib.push_back(m);
  }
  {
    // 4340 steel: Johnson & Cook (1983, 1985); Steinberg's shock data.
    LibraryMaterial m;
    m.name = "4340-steel";
    m.source = "Johnson & Cook 1983/1985; Steinberg 1996 (Us-up)";
    HydroModels& p = m.parameters;
    p.density = 7.83 * g_cm3;
    p.youngs_modulus = 200 * GPa;
    p.poisson_ratio = 0.29;
    p.johnson_cook = JohnsonCookStrength{792 * MPa, 510 * MPa, 0.26, 0.014, 1.03, 1793, 293, 1.0};
    p.eos = MieGruneisen{p.density, 4578, 1.33, 1.67};
    p.damage = jc_damage(0.05, 3.44, -2.12, 0.002, 0.61);
    m.specific_heat = 477;
    lib.push_back(m);
  }
  {
    // 42CrMo4 steel of the DynELA/Abaqus Taylor-bar code-to-code benchmark (no EOS data: the
    // benchmark uses the elastic bulk response).
    LibraryMaterial m;
    m.name = "42CrMo4";
    m.source = "DynELA/Abaqus Taylor-bar benchmark";
    HydroModels& p = m.parameters;
    p.density = 7830;
    p.youngs_modulus = 206.9 * GPa;
    p.poisson_ratio = 0.3;
    p.initial_temperature = 293.15;
    p.johnson_cook =
        JohnsonCookStrength{806 * MPa, 614 * MPa, 0.168, 0.0089, 1.1, 1813.15, 293.15, 1.0};
    m.specific_heat = 460;
    lib.push_back(m);
  }
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
