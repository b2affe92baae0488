// The [[material]] tables read into MaterialSettings: the models a material names, each model's
// parameters from the table or else from the library material, written back into the resolved
// scene; a parameter table for a model the material does not name is refused.
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <type_traits>

#include <fmt/format.h>

#include "cases/scene/scene_reading.hpp"
#include "mpm/materials/library.hpp"

namespace hvi::scene::reading {

namespace {

// Fills the parameters of one named model: each key from the scene if given, else from the library
// entry; a key neither gives is an error. Writes the values used back into the resolved table.
class ParameterSource {
 public:
  ParameterSource(toml::table& table, std::string path, const std::string& library, Checker& c)
      : table_(table), path_(std::move(path)), library_(library), c_(c) {}
  double get(const char* key, std::optional<double> library_value) {
    double v = 0.0;
    if (auto given = table_[key].value<double>()) {
      v = *given;
    } else if (library_value) {
      v = *library_value;
    } else {
      c_.error(path_,
               fmt::format("missing parameter '{}'{}", key,
                           library_.empty()
                               ? " (give it, or name a library material that has it)"
                               : fmt::format(" (library material '{}' has none)", library_)));
    }
    table_.insert_or_assign(key, v);
    return v;
  }

 private:
  toml::table& table_;
  std::string path_;
  const std::string& library_;
  Checker& c_;
};

template <class T, class F>
std::optional<double> from(const std::optional<T>& model, F field) {
  if (!model) return std::nullopt;
  return field(*model);
}

// One [[material]] table being read: a function per model, in the order the models act.
class MaterialReader {
 public:
  MaterialReader(toml::table& t, std::string path, MaterialSettings& m, const Scene& s, Checker& c)
      : t_(t), path_(std::move(path)), m_(m), h_(m.models), s_(s), c_(c) {
    lib_ = m.library.empty() ? nullptr : mpm::find_library_material(m.library);
    L_ = lib_ ? &lib_->parameters : nullptr;
  }

  void elasticity() {
    h_.shear_strength = m_.strength != "none";
    ParameterSource top(t_, path_, m_.library, c_);
    h_.density = top.get("density", L_ ? std::optional(L_->density) : std::nullopt);
    h_.youngs_modulus =
        top.get("youngs_modulus", L_ ? std::optional(L_->youngs_modulus) : std::nullopt);
    h_.poisson_ratio =
        top.get("poisson_ratio", L_ ? std::optional(L_->poisson_ratio) : std::nullopt);
  }

  void strength() {
    auto* jt =
        model_table("johnson_cook", m_.strength == "johnson-cook", "strength", "johnson-cook");
    if (!jt) return;
    ParameterSource p(*jt, path_ + ".johnson_cook", m_.library, c_);
    const auto& lj = L_ ? L_->johnson_cook : std::nullopt;
    materials::JohnsonCookStrength jc;
    jc.A = p.get("A", from(lj, [](auto& x) { return x.A; }));
    jc.B = p.get("B", from(lj, [](auto& x) { return x.B; }));
    jc.n = p.get("n", from(lj, [](auto& x) { return x.n; }));
    jc.C = p.get("C", from(lj, [](auto& x) { return x.C; }));
    jc.m = p.get("m", from(lj, [](auto& x) { return x.m; }));
    jc.melt_temperature =
        p.get("melt_temperature", from(lj, [](auto& x) { return x.melt_temperature; }));
    jc.room_temperature =
        p.get("room_temperature", from(lj, [](auto& x) { return x.room_temperature; }));
    jc.reference_strain_rate =
        p.get("reference_strain_rate",
              lj ? std::optional(lj->reference_strain_rate) : std::optional(1.0));
    if (!(jc.melt_temperature > jc.room_temperature))
      c_.error(path_ + ".johnson_cook.melt_temperature",
               "expected melt_temperature > room_temperature");
    h_.johnson_cook = jc;
  }

  // The registered equation of state the material names (materials/equation_of_state.hpp).
  void eos() {
    materials::for_each_equation_of_state([&](auto law) { read_eos(law); });
  }

  void viscosity() {
    auto* vt = model_table("bulk_viscosity", m_.viscosity == "bulk", "viscosity", "bulk");
    if (!vt) return;
    mpm::ArtificialViscosity av;
    av.linear = (*vt)["linear"].value<double>().value();
    av.quadratic = (*vt)["quadratic"].value<double>().value();
    av.length = s_.grid.cell_size;
    h_.viscosity = av;
  }

  void damage() {
    auto* dt =
        model_table("johnson_cook_damage", m_.damage == "johnson-cook", "damage", "johnson-cook");
    if (!dt) return;
    ParameterSource p(*dt, path_ + ".johnson_cook_damage", m_.library, c_);
    const auto& ld = L_ ? L_->damage : std::nullopt;
    materials::JohnsonCookDamage d;
    d.D1 = p.get("D1", from(ld, [](auto& x) { return x.D1; }));
    d.D2 = p.get("D2", from(ld, [](auto& x) { return x.D2; }));
    d.D3 = p.get("D3", from(ld, [](auto& x) { return x.D3; }));
    d.D4 = p.get("D4", from(ld, [](auto& x) { return x.D4; }));
    d.D5 = p.get("D5", from(ld, [](auto& x) { return x.D5; }));
    d.reference_strain_rate =
        p.get("reference_strain_rate",
              ld ? std::optional(ld->reference_strain_rate) : std::optional(1.0));
    if (m_.strength != "johnson-cook")
      c_.error(
          path_ + ".damage",
          "johnson-cook damage accumulates plastic strain: it needs strength = \"johnson-cook\"");
    h_.damage = d;
  }

  void damage_evolution() {
    auto* ft = model_table("fracture_energy", m_.damage_evolution == "fracture-energy",
                           "damage_evolution", "fracture-energy");
    if (!ft) return;
    ParameterSource p(*ft, path_ + ".fracture_energy", m_.library, c_);
    materials::FractureEnergy f;
    f.energy = p.get("energy", std::nullopt);
    f.band = s_.grid.cell_size;
    if (m_.damage != "johnson-cook")
      c_.error(path_ + ".damage_evolution",
               "a fracture energy takes over where damage initiates: it needs damage = "
               "\"johnson-cook\"");
    if (m_.eos == "none")
      c_.error(path_ + ".damage_evolution",
               "a fracture energy softens the equation of state's tension: it needs an eos (e.g. "
               "eos = \"mie-gruneisen\")");
    h_.fracture_energy = f;
  }

  void scatter() {
    auto* wt = model_table("weibull", m_.scatter == "weibull", "scatter", "weibull");
    if (!wt) return;
    ParameterSource p(*wt, path_ + ".weibull", m_.library, c_);
    materials::WeibullScatter w;
    w.modulus = p.get("modulus", std::nullopt);
    w.seed = static_cast<std::uint64_t>((*wt)["seed"].value<std::int64_t>().value());
    if (m_.damage != "johnson-cook" && m_.failure != "max-principal-stress")
      c_.error(path_ + ".scatter",
               "scatter acts on the Johnson-Cook failure strain and the max-principal-stress "
               "limit: it needs damage = \"johnson-cook\" or failure = \"max-principal-stress\"");
    h_.scatter = w;
  }

  void failure() {
    if (auto* ft = model_table("max_principal_stress", m_.failure == "max-principal-stress",
                               "failure", "max-principal-stress")) {
      ParameterSource p(*ft, path_ + ".max_principal_stress", m_.library, c_);
      h_.max_principal_stress = p.get("limit", L_ ? L_->max_principal_stress : std::nullopt);
    }
    if (auto* tt = model_table("tuler_butcher", m_.failure == "tuler-butcher", "failure",
                               "tuler-butcher")) {
      ParameterSource p(*tt, path_ + ".tuler_butcher", m_.library, c_);
      materials::TulerButcher tb;
      tb.threshold = p.get("threshold", L_ ? L_->max_principal_stress : std::nullopt);
      tb.exponent = (*tt)["exponent"].value<double>().value();
      tb.time = p.get("time", std::nullopt);
      h_.tuler_butcher = tb;
    }
  }

  void erosion() {
    if (auto* et = model_table("compression_erosion", m_.erosion == "compression", "erosion",
                               "compression"))
      h_.erosion = mpm::CompressionErosion{(*et)["min_volume_ratio"].value<double>().value()};
  }

  void heating() {
    if (auto* ht =
            model_table("adiabatic_heating", m_.heating == "adiabatic", "heating", "adiabatic")) {
      ParameterSource p(*ht, path_ + ".adiabatic_heating", m_.library, c_);
      mpm::AdiabaticHeating heat;
      heat.specific_heat = p.get("specific_heat", lib_ ? lib_->specific_heat : std::nullopt);
      heat.taylor_quinney = (*ht)["taylor_quinney"].value<double>().value();
      if (m_.strength != "johnson-cook")
        c_.error(path_ + ".heating",
                 "adiabatic heating comes from plastic work: it needs strength = \"johnson-cook\"");
      h_.heating = heat;
    }
    h_.initial_temperature = t_["initial_temperature"].value<double>().value_or(
        L_ ? L_->initial_temperature
           : (h_.johnson_cook ? h_.johnson_cook->room_temperature : 293.0));
    t_.insert_or_assign("initial_temperature", h_.initial_temperature);
  }

 private:
  template <class Law>
  void read_eos(std::type_identity<Law>) {
    auto* table = model_table(Law::table, m_.eos == Law::name, "eos", Law::name);
    if (!table) return;
    ParameterSource p(*table, path_ + "." + Law::table, m_.library, c_);
    const Law* library_law = L_ ? L_->template eos_as<Law>() : nullptr;
    std::array<double, Law::parameters.size()> values{};
    for (std::size_t i = 0; i < values.size(); ++i)
      values[i] = p.get(Law::parameters[i].key,
                        library_law ? std::optional(library_law->values()[i]) : std::nullopt);
    h_.eos = Law::from(h_.density, values);
  }

  // One parameter table per model: kept (and completed) for the named models, refused for the
  // others when the scene wrote it.
  toml::table* model_table(const char* key, bool named, const char* model_key,
                           const char* model_name) {
    const std::string table_path = path_ + "." + key;
    if (!named) {
      if (c_.v.locations.count(table_path))
        c_.error(table_path, fmt::format("parameters for a model the material does not name; set "
                                         "{} = \"{}\" or remove the table",
                                         model_key, model_name));
      t_.erase(key);
      return nullptr;
    }
    if (!t_[key].as_table()) t_.insert_or_assign(key, toml::table{});
    return t_[key].as_table();
  }

  toml::table& t_;
  const std::string path_;
  MaterialSettings& m_;
  mpm::HydroModels& h_;
  const Scene& s_;
  Checker& c_;
  const mpm::LibraryMaterial* lib_ = nullptr;
  const mpm::HydroModels* L_ = nullptr;
};

// A material whose reference wave speed is not a finite positive number (a modulus or an EOS
// constant near the largest double) would give no time step: refuse it here, not at step 0.
void check_wave_speed(const MaterialSettings& m, const std::string& path, Checker& c) {
  const mpm::HydroModels& h = m.models;
  if (!(h.density > 0) || !(h.youngs_modulus > 0)) return;  // reported where they are read
  const double speed = mpm::HydroMaterial(m.name, h).sound_speed(h.density, 0.0, /*failed=*/false);
  if (!(std::isfinite(speed) && speed > 0))
    c.error(path, fmt::format("its wave speed at the reference density is {} m/s: expected a "
                              "finite speed (check its moduli and equation-of-state constants)",
                              speed));
}

}  // namespace

void read_materials(toml::array& array, Scene& s, Checker& c) {
  for (std::size_t i = 0; i < array.size(); ++i) {
    toml::table& t = *array[i].as_table();
    const std::string path = element_path("material", t, i);
    MaterialSettings m;
    m.name = text(t, "name");
    for (const auto& other : s.materials)
      if (other.name == m.name)
        c.error(path + ".name", "a material of this name is already defined");
    m.library = t["library"].value_or(std::string{});
    m.strength = text(t, "strength");
    m.eos = text(t, "eos");
    m.viscosity = text(t, "viscosity");
    m.damage = text(t, "damage");
    m.damage_evolution = text(t, "damage_evolution");
    m.scatter = text(t, "scatter");
    m.failure = text(t, "failure");
    m.heating = text(t, "heating");
    m.erosion = text(t, "erosion");
    MaterialReader r(t, path, m, s, c);
    r.elasticity();
    r.strength();
    r.eos();
    r.viscosity();
    r.damage();
    r.damage_evolution();
    r.scatter();
    r.failure();
    r.erosion();
    r.heating();
    check_wave_speed(m, path, c);
    s.materials.push_back(m);
  }
}

}  // namespace hvi::scene::reading
