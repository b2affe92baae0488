#include "mpm/bond.hpp"

#include <algorithm>
#include <cmath>

namespace hvi::mpm {

void BondInterface::declare_fields(Particles& P) {
  P.add_field(bond_field::area, FieldKind::scalar, "m^2");
  P.add_field(bond_field::normal, FieldKind::vector, "1");
  P.add_field(bond_field::bonded, FieldKind::scalar, "1");
}

namespace {

// The 1D weights of a point at s (cells) with half-width a (cells): nodes i0 .. i0 + n - 1.
int axis_weights(ShapeFunction shape, double s, double a, int& i0, double* N) {
  double dN[3];
  if (shape == ShapeFunction::linear) {
    i0 = LinearShape::lowest(s, a);
    LinearShape::weights(s, i0, a, N, dN);
    return LinearShape::width;
  }
  i0 = GimpShape::lowest(s, a);
  GimpShape::weights(s, i0, a, N, dN);
  return GimpShape::width;
}

}  // namespace

void stencil_on(const SparseGrid& grid, ShapeFunction shape, const double* x, const double* a,
                std::vector<NodeWeight>& out) {
  out.clear();
  const GridGeometry& g = grid.geometry();
  int i0[3], n[3];
  double N[3][3];
  for (int d = 0; d < 3; ++d)
    n[d] = axis_weights(shape, (x[d] - g.origin[d]) / g.cell_size, a[d] / g.cell_size, i0[d], N[d]);
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        const double w = N[0][i] * N[1][j] * N[2][k];
        if (!(w > 0.0)) continue;
        const int gi = i0[0] + i, gj = i0[1] + j, gk = i0[2] + k;
        const std::uint32_t b = grid.find(SparseGrid::key_of_node(gi, gj, gk));
        if (b == SparseGrid::none) continue;
        const auto o = grid.block_origin(b);
        out.push_back({static_cast<std::size_t>(b) * SparseGrid::block_size +
                           static_cast<std::size_t>(local_node(gi - o[0], gj - o[1], gk - o[2])),
                       w});
      }
}

namespace {

// A point's GIMP half-widths (m): its field's, else half its cube's edge (as the solver's).
void half_widths(const Particles& P, std::size_t p, const std::vector<double>* half_width,
                 double* a) {
  for (int d = 0; d < 3; ++d)
    a[d] = half_width ? (*half_width)[3 * p + d] : 0.5 * std::cbrt(P.volume0[p]);
}

constexpr int packed = 12;  // id, x, a, area, n, bonded

}  // namespace

void BondInterface::prepare(const Particles& P, const SparseGrid& grid1, ShapeFunction shape,
                            const std::vector<double>* half_width, Communicator* comm) {
  // This rank's interface points, then every rank's, in id order.
  const auto& area = P.field(bond_field::area);
  const auto& normal = P.field(bond_field::normal);
  const auto& bonded = P.field(bond_field::bonded);
  std::vector<double> mine;
  for (std::size_t p = 0; p < P.size(); ++p) {
    if (!(area[p] > 0.0)) continue;
    double a[3];
    half_widths(P, p, half_width, a);
    mine.push_back(static_cast<double>(P.id[p]));
    for (int d = 0; d < 3; ++d) mine.push_back(P.position[3 * p + d]);
    for (int d = 0; d < 3; ++d) mine.push_back(a[d]);
    mine.push_back(area[p]);
    for (int d = 0; d < 3; ++d) mine.push_back(normal[3 * p + d]);
    mine.push_back(bonded[p]);
  }
  std::vector<std::vector<double>> all;
  if (comm && comm->size() > 1)
    all = comm->all_gather(mine);
  else
    all.push_back(std::move(mine));
  points_.clear();
  for (const auto& from : all)
    for (std::size_t k = 0; k + packed <= from.size(); k += packed) {
      Point q{};
      q.id = static_cast<std::int64_t>(from[k]);
      for (int d = 0; d < 3; ++d) {
        q.x[d] = from[k + 1 + d];
        q.a[d] = from[k + 4 + d];
        q.n[d] = from[k + 8 + d];
      }
      q.area = from[k + 7];
      q.bonded = from[k + 11] > 0.0;
      points_.push_back(q);
    }
  std::sort(points_.begin(), points_.end(),
            [](const Point& a, const Point& b) { return a.id < b.id; });
  // The node sums, point by point in id order: the same bits on every rank.
  const std::size_t nodes = grid1.block_count() * SparseGrid::block_size;
  area_.assign(nodes, 0.0);
  normal_.assign(3 * nodes, 0.0);
  force_.assign(3 * nodes, 0.0);
  any_.assign(nodes, 0);
  for (const Point& q : points_) {
    stencil_on(grid1, shape, q.x, q.a, stencil_);
    for (const NodeWeight& w : stencil_) {
      any_[w.node] = 1;
      if (q.bonded) area_[w.node] += q.area * w.N;
      for (int d = 0; d < 3; ++d) normal_[3 * w.node + d] += q.area * w.N * q.n[d];
    }
  }
  for (std::size_t i = 0; i < nodes; ++i) {
    double* n = &normal_[3 * i];
    const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (length > 0.0)
      for (int d = 0; d < 3; ++d) n[d] /= length;
  }
}

std::int64_t BondInterface::break_overloaded(Particles& P, const SparseGrid& grid1,
                                             ShapeFunction shape,
                                             const std::vector<double>* half_width) {
  const auto& area = P.field(bond_field::area);
  const auto& normal = P.field(bond_field::normal);
  auto& bonded = P.field(bond_field::bonded);
  const double Sn = settings_.normal_strength, Ss = settings_.shear_strength;
  std::int64_t broken = 0;
  for (std::size_t p = 0; p < P.size(); ++p) {
    if (!(area[p] > 0.0) || !(bonded[p] > 0.0)) continue;
    double a[3], t[3] = {0.0, 0.0, 0.0};
    half_widths(P, p, half_width, a);
    stencil_on(grid1, shape, &P.position[3 * p], a, stencil_);
    for (const NodeWeight& w : stencil_) {
      if (!(area_[w.node] > 0.0)) continue;
      for (int d = 0; d < 3; ++d) t[d] += w.N * force_[3 * w.node + d] / area_[w.node];
    }
    const double* n = &normal[3 * p];
    const double sn = t[0] * n[0] + t[1] * n[1] + t[2] * n[2];
    double tau2 = 0.0;
    for (int d = 0; d < 3; ++d) tau2 += (t[d] - sn * n[d]) * (t[d] - sn * n[d]);
    const double tension = std::max(sn, 0.0);
    if ((tension * tension) / (Sn * Sn) + tau2 / (Ss * Ss) >= 1.0) {
      bonded[p] = 0.0;
      ++broken;
    }
  }
  return broken;
}

std::size_t BondInterface::bytes() const {
  return points_.capacity() * sizeof(Point) + stencil_.capacity() * sizeof(NodeWeight) +
         (area_.capacity() + normal_.capacity() + force_.capacity()) * sizeof(double) +
         any_.capacity();
}

}  // namespace hvi::mpm
