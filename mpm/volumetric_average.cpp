#include "mpm/volumetric_average.hpp"

#include <cstdint>

#include "mpm/types.hpp"

namespace hvi::mpm {

namespace {
constexpr const char* failed_field = "failed";  // declared by the failure models (0 intact)
}

NodeAverage VolumetricAverage::averaging(const Particles& P) const {
  NodeAverage a;
  a.value = value_.data();
  a.group = P.body.data();
  a.groups = bodies_;
  a.skip = P.has_field(failed_field) ? P.field(failed_field).data() : nullptr;
  return a;
}

const std::vector<double>& VolumetricAverage::mean_stress_shift(const Particles& P, const ParticleBins& bins,
                                                                SparseGrid& grid, const TransferContext& context) {
  const auto n = static_cast<std::int64_t>(P.size());
  value_.resize(P.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t p = 0; p < n; ++p) value_[p] = trace_sym(&P.stress[6 * p]) / 3.0;
  const NodeAverage a = averaging(P);
  node_average(P, bins, grid, context, a, sums_, average_);
  shift_.resize(P.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t p = 0; p < n; ++p)
    shift_[p] = a.counts(p) ? average_[p] - value_[p] : 0.0;
  return shift_;
}

void VolumetricAverage::average_dilatation(Particles& P, const ParticleBins& bins, SparseGrid& grid,
                                           const TransferContext& context) {
  const auto n = static_cast<std::int64_t>(P.size());
  value_.resize(P.size());
  double* L = P.velocity_gradient.data();
#pragma omp parallel for schedule(static)
  for (std::int64_t p = 0; p < n; ++p) value_[p] = L[9 * p] + L[9 * p + 4] + L[9 * p + 8];
  const NodeAverage a = averaging(P);
  node_average(P, bins, grid, context, a, sums_, average_);
  // Only the points binned here: with contact, the other field's points are averaged on their own grid.
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
