#pragma once
// Drives a material directly, without a grid: a few particles with a prescribed velocity gradient,
// stepped through Material::update_stress the way the solver does (F, and so the volume, advance
// with det(I + dt L) inside the material).
#include <memory>

#include "mpm/material.hpp"
#include "mpm/particles.hpp"

namespace hvi::test {

struct MaterialPoint {
  mpm::Particles particles;
  const mpm::Material& material;
  mpm::ParticleRange range{0, 1};

  MaterialPoint(const mpm::Material& m, double volume = 1e-9) : material(m) {
    const double x[3] = {0, 0, 0};
    particles.append(x, volume, m.reference_density() * volume, 0, 0);
    m.declare_fields(particles);
    m.initialise(particles, range);
  }
  // One step with velocity gradient L (row-major, L_ij = dv_i/dx_j).
  mpm::StressUpdate step(const double* L, double dt) {
    for (int c = 0; c < 9; ++c) particles.velocity_gradient[c] = L[c];
    return material.update_stress(particles, range, {dt, 0.0, 0, nullptr});
  }
  const double* stress() const { return particles.stress.data(); }
  double field(const char* name) const { return particles.field(name)[0]; }
};

}  // namespace hvi::test
