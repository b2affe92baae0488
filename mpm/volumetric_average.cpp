#include "mpm/volumetric_average.hpp"

#include <cstdint>

#include "mpm/types.hpp"

namespace hvi::mpm {

namespace {
constexpr const char* failed_field = "failed";  // declared by the failure models (0 intact)
}

NodeAverageSums VolumetricAverage::averaging(const Particles& P) {
  NodeAverageSums a;
  a.average.value = value_.data();
  a.average.group = P.body.data();
  a.average.groups = bodies_;
  a.average.skip = P.has_field(failed_field) ? P.field(failed_field).data() : nullptr;
  a.sums = &sums_;
  return a;
}

const NodeAverageSums& VolumetricAverage::mean_stress_sums(const Particles& P,
                                                           const ParticleBins& bins,
                                                           SparseGrid& grid,
                                                           const TransferContext& context) {
  const auto n = static_cast<std::int64_t>(P.size());
  value_.resize(P.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t p = 0; p < n; ++p) value_[p] = trace_sym(&P.stress[6 * p]) / 3.0;
  current_ = averaging(P);
  node_average_scatter(P, bins, grid, context, current_);
  return current_;
}

const NodeAverageSums& VolumetricAverage::dilatation_sums(const Particles& P) {
  value_.resize(P.size());
  current_ = averaging(P);
  return current_;
}

void VolumetricAverage::average_dilatation(Particles& P, const ParticleBins& bins,
                                           const SparseGrid& grid, const TransferContext& context) {
  node_average_gather(P, bins, grid, context, current_, average_);
  double* L = P.velocity_gradient.data();
  const NodeAverage& a = current_.average;
  // Only the points binned here: with contact, the other field's points are averaged on their own
  // grid.
  const auto binned = static_cast<std::int64_t>(bins.order.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t k = 0; k < binned; ++k) {
    const std::uint32_t p = bins.order[k];
    if (!a.counts(p)) continue;
    const double shift = (average_[p] - value_[p]) / 3.0;
    L[9 * p] += shift;
    L[9 * p + 4] += shift;
    L[9 * p + 8] += shift;
  }
}

}  // namespace hvi::mpm
