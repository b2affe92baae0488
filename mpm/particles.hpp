#pragma once
// Material points as a struct of arrays: one contiguous array per field, components of a field
// interleaved per particle (position[3*p + d]). Core fields always exist; a material adds the
// state fields it declares (plastic strain, damage, temperature, ...) so a scene that does not ask
// for a model allocates none of its state.
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace hvi::mpm {

// How a field is laid out and shown in ParaView.
enum class FieldKind { scalar, vector, tensor, sym_tensor };
int components(FieldKind kind);

// A named per-particle field of doubles.
struct RealField {
  std::string name;
  FieldKind kind = FieldKind::scalar;
  std::string unit;      // SI unit, for output metadata
  bool output = true;    // written to snapshots
  bool scratch = false;  // recomputed every step: not reordered, not checkpointed, not written
  std::vector<double>* data = nullptr;
};

struct IntField {
  std::string name;
  std::vector<std::int64_t>* data = nullptr;
};

class Particles {
 public:
  Particles();
  Particles(const Particles&) = delete;
  Particles& operator=(const Particles&) = delete;
  Particles(Particles&&) = delete;

  std::size_t size() const { return mass.size(); }

  // Core fields. Units SI; tensors row-major, symmetric tensors in Tensor6 order (xx xy xz yy yz
  // zz).
  std::vector<double> position;         // 3 per particle, m
  std::vector<double> velocity;         // 3, m/s
  std::vector<double> mass;             // kg
  std::vector<double> volume0;          // reference volume, m^3
  std::vector<double> volume;           // current volume V = det(F) V0, m^3
  std::vector<double> stress;           // 6, Cauchy stress, Pa (tension positive)
  std::vector<double> internal_energy;  // specific internal energy, J/kg
  // Scratch, valid within one step only.
  std::vector<double> velocity_gradient;  // 9, 1/s, L_ij = dv_i/dx_j at the start-of-step position
  std::vector<double> grid_velocity;      // 3, m/s: sum_I N_I v_I (positions move with it, MUSL)
  // Identity.
  std::vector<std::int64_t> id;        // stable id given at creation
  std::vector<std::int64_t> body;      // index into the scene's bodies
  std::vector<std::int64_t> material;  // index into the scene's materials

  // Declares an extra state field (idempotent for the same name and kind); returns its storage,
  // sized to the current particle count and filled with `initial`.
  std::vector<double>& add_field(const std::string& name, FieldKind kind, const std::string& unit,
                                 double initial = 0.0, bool output = true);
  bool has_field(const std::string& name) const;
  std::vector<double>& field(const std::string& name);
  const std::vector<double>& field(const std::string& name) const;

  // Every field, core and extra, for generic operations (reorder, erase, output, checkpoint).
  const std::vector<RealField>& real_fields() const { return real_fields_; }
  const std::vector<IntField>& int_fields() const { return int_fields_; }

  // Appends one particle at rest, undeformed (volume = volume0), unstressed; returns its index.
  std::size_t append(const double x[3], double volume_value, double mass_value,
                     std::int64_t body_index, std::int64_t material_index);
  // New particles are zero in every field: the caller sets at least position, mass, volume0 and
  // volume (equal to volume0 for an undeformed particle).
  void resize(std::size_t n);

  // Reorders every non-scratch field: new particle k is old particle order[k].
  void reorder(std::span<const std::uint32_t> order);
  // Removes the particles at `removed` (ascending indices). The particles are taken as groups of
  // consecutive runs, `group_sizes` long (a solver's materials), which stay contiguous and in their
  // order: each group's last particles move into its gaps, so it costs a few moves per removed
  // particle instead of a pass over every field, and the order inside a group changes.
  void erase(std::span<const std::uint32_t> removed, std::span<const std::size_t> group_sizes);

  // Bytes held by all per-particle arrays (capacity), for the memory report.
  std::size_t bytes() const;

 private:
  void register_core_fields();
  std::vector<RealField> real_fields_;
  std::vector<IntField> int_fields_;
  // Extra fields own their storage here; std::deque-like stability via unique_ptr.
  std::vector<std::unique_ptr<std::vector<double>>> extra_storage_;
};

}  // namespace hvi::mpm
