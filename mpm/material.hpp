#pragma once
// The material interface. One material = one class that declares the per-particle state it needs
// and updates stress and specific internal energy for a contiguous group of particles. The solver
// calls it once per material group and step (no virtual call per particle), so a material's loop
// is a tight loop over its own particles.
#include <cmath>
#include <cstdint>
#include <string>

#include "mpm/exact_sum.hpp"
#include "mpm/particles.hpp"

namespace hvi::mpm {

class PhaseTimer;

// Particles [begin, end) of one material (the solver keeps each material's particles contiguous).
struct ParticleRange {
  std::size_t begin = 0, end = 0;
  std::size_t size() const { return end - begin; }
};

struct StressContext {
  double dt = 0.0;
  double time = 0.0;  // at the start of the step
  std::int64_t step = 0;
  PhaseTimer* timer = nullptr;  // for materials that time their sub-models
};

struct StressUpdate {
  double max_signal_speed = 0.0;   // max over the group of (sound speed + |v|), m/s
  std::int64_t bad_particle = -1;  // lowest index of a particle in an invalid state, or -1
  const char* problem = nullptr;   // what was invalid ("non-positive volume", "non-finite stress")

  // The result over a group: its largest signal speed, and `problem` at `first_bad` unless that
  // is INT64_MAX (no particle was invalid).
  static StressUpdate of(double max_signal_speed, std::int64_t first_bad, const char* problem) {
    StressUpdate result;
    result.max_signal_speed = max_signal_speed;
    if (first_bad != INT64_MAX) {
      result.bad_particle = first_bad;
      result.problem = problem;
    }
    return result;
  }
};

class Material {
 public:
  explicit Material(std::string name) : name_(std::move(name)) {}
  virtual ~Material() = default;
  const std::string& name() const { return name_; }

  // Adds the state fields this material needs to the particles (once, before the first step).
  virtual void declare_fields(Particles& /*particles*/) const {}
  // Initial state of this material's particles (fields already declared).
  virtual void initialise(Particles& /*particles*/, ParticleRange /*range*/) const {}
  // Max over the group of (sound speed + |v|) in the current state, m/s.
  virtual double max_signal_speed(const Particles& particles, ParticleRange range) const = 0;
  // Updates Cauchy stress, volume (advance_volume) and specific internal energy over one step,
  // given the velocity gradient. Times its own phases on context.timer, one per model, so the
  // timing table shows exactly the models a scene names.
  virtual StressUpdate update_stress(Particles& particles, ParticleRange range,
                                     const StressContext& context) const = 0;
  // Adds the energy dissipated so far in the group (plastic work, viscous heating, J) to `sum`,
  // term by term, so that the total over materials and ranks is exact. Part of the internal
  // energy: the recoverable (strain) part is internal - dissipated.
  virtual void add_dissipated_energy(const Particles& /*particles*/, ParticleRange /*range*/,
                                     ExactSum& /*sum*/) const {}
  // Reference density, kg/m^3 (to give sampled points their mass).
  virtual double reference_density() const = 0;

 private:
  std::string name_;
};

// Advances particle p's volume over the step, V_n+1 = det(I + dt L) V_n: the volume change of
// the deformation-gradient update F_n+1 = (I + dt L) F_n (F itself is not stored; hydrocode
// materials need only the volume). Shared by all materials so they integrate volume alike.
struct VolumeChange {
  double before, after;  // m^3
};
inline VolumeChange advance_volume(Particles& particles, std::size_t p, double dt) {
  const double* L = &particles.velocity_gradient[9 * p];
  const double a = 1 + dt * L[0], b = dt * L[1], c = dt * L[2];
  const double d = dt * L[3], e = 1 + dt * L[4], f = dt * L[5];
  const double g = dt * L[6], h = dt * L[7], i = 1 + dt * L[8];
  const double det = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g);
  const double before = particles.volume[p];
  particles.volume[p] = det * before;
  return {before, det * before};
}

// Helper shared by materials: |v| of particle p.
inline double speed(const Particles& particles, std::size_t p) {
  const double* v = &particles.velocity[3 * p];
  return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

}  // namespace hvi::mpm
