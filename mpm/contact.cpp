#include "mpm/contact.hpp"

#include "mpm/exact_sum.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace hvi::mpm {

BodyContact::BodyContact(const GridGeometry& geometry, ContactSettings settings)
    : settings_(std::move(settings)), grid_(geometry) {
  if (settings_.bond) bond_ = std::make_unique<BondInterface>(*settings_.bond);
}

const std::vector<std::uint8_t>& BodyContact::assign_fields(const Particles& P) {
  field_.resize(P.size());
  for (std::size_t p = 0; p < P.size(); ++p)
    field_[p] = settings_.impactor.at(static_cast<std::size_t>(P.body[p]));
  return field_;
}

namespace {

// Per owner block of `bins` (on `grid`): 1 if a block its particles reach is active in `other`,
// where the fields can meet. A normal is needed only there.
void owners_meeting(const ParticleBins& bins, const SparseGrid& grid, const SparseGrid& other,
                    std::vector<std::uint8_t>& out) {
  const auto owners = static_cast<std::int64_t>(bins.owner_count());
  out.assign(static_cast<std::size_t>(owners), 0);
#pragma omp parallel for schedule(static)
  for (std::int64_t b = 0; b < owners; ++b)
    for (const std::uint32_t reached : bins.neighbours[static_cast<std::size_t>(b)])
      if (other.find(grid.key(reached)) != SparseGrid::none) {
        out[static_cast<std::size_t>(b)] = 1;
        break;
      }
}

}  // namespace

void BodyContact::compute_normals(const Particles& P, const ParticleBins& bins0, SparseGrid& grid0,
                                  const TransferContext& context0,
                                  const TransferContext& context1) {
  // The impactor's field is small, the panel's large: each scatters only the blocks where they
  // meet.
  owners_meeting(bins0, grid0, grid_, meeting0_);
  owners_meeting(bins_, grid_, grid0, meeting1_);
  outward_normals(P, bins0, grid0, context0, normal0_, &meeting0_);
  outward_normals(P, bins_, grid_, context1, normal1_, &meeting1_);
}

namespace {

// The nodal velocity `which` of node n, and where a correction of it goes.
void velocity(const GridNode& n, NodalVelocity which, double* v) {
  for (int d = 0; d < 3; ++d)
    v[d] = which == NodalVelocity::start ? n.p[d]
           : which == NodalVelocity::end ? n.p[d] + n.f[d]
                                         : n.q[d];
}
GridNode::Vector corrected(const GridNode& n, NodalVelocity which) {
  return which == NodalVelocity::start ? n.p : which == NodalVelocity::end ? n.f : n.q;
}

}  // namespace

double BodyContact::apply(SparseGrid& grid0, NodalVelocity which, double dt) {
  const auto blocks = static_cast<std::int64_t>(grid_.block_count());
  const std::size_t nodes = grid_.block_count() * SparseGrid::block_size;
  const bool remapped = which == NodalVelocity::remapped;
  if (which == NodalVelocity::end || in_contact_.size() != nodes) {
    in_contact_.assign(nodes, 0);
    tied_.assign(nodes, 0);
  }
  block_work_.assign(static_cast<std::size_t>(blocks), 0.0);
  const double mu = settings_.friction;
#pragma omp parallel for schedule(static)
  for (std::int64_t b = 0; b < blocks; ++b) {
    const std::uint32_t b0 = grid0.find(grid_.key(static_cast<std::uint32_t>(b)));
    if (b0 == SparseGrid::none) continue;
    double work = 0.0;
    for (int l = 0; l < SparseGrid::block_size; ++l) {
      const GridNode n1 = grid_.node(static_cast<std::uint32_t>(b), l);
      const GridNode n0 = grid0.node(b0, l);
      const double m0 = n0.mass, m1 = n1.mass;
      if (m0 <= 0.0 || m1 <= 0.0) continue;
      // Nodes are numbered block by block, 64 a block (the normals' order).
      const std::size_t node1 =
          static_cast<std::size_t>(b) * SparseGrid::block_size + static_cast<std::size_t>(l);
      if (remapped && !in_contact_[node1]) continue;
      double v0[3], v1[3];
      velocity(n0, which, v0);
      velocity(n1, which, v1);
      const double M = m0 + m1;
      // Bonded: tied, the whole relative velocity removed (the remapped velocity where the end's
      // was tied), the end's force on the core kept for the bond's tractions.
      if (bond_ && bond_->area(node1) > 0.0 && (!remapped || tied_[node1])) {
        const GridNode::Vector c0 = corrected(n0, which), c1 = corrected(n1, which);
        for (int d = 0; d < 3; ++d) {
          const double w = v1[d] - v0[d];
          c0[d] += (m1 / M) * w;
          c1[d] -= (m0 / M) * w;
          if (which == NodalVelocity::end) bond_->force(node1)[d] = -(m0 * m1 / M) * w / dt;
        }
        if (which == NodalVelocity::end) in_contact_[node1] = tied_[node1] = 1;
        continue;
      }
      // The normal: at the bond's interface the sheet's, from the geometry; elsewhere from g_k
      // of the node (transfers.hpp: three arrays of 64 per block).
      const auto normal = [&](const std::vector<double>& g, std::size_t block, int d) {
        return g[(3 * block + static_cast<std::size_t>(d)) * SparseGrid::block_size +
                 static_cast<std::size_t>(l)];
      };
      double n[3];
      const bool interface = bond_ && bond_->interface(node1);
      for (int d = 0; d < 3; ++d)
        n[d] =
            interface ? bond_->normal(node1)[d]
                      : normal(normal1_, static_cast<std::size_t>(b), d) - normal(normal0_, b0, d);
      const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      if (!(length > 0.0)) continue;
      for (double& c : n) c /= length;
      // In the relative velocity w = v1 - v0, which stays well conditioned when one field's mass at
      // the node is a GIMP tail many orders below the other's: v1 - v_cm = (m0 / M) w.
      double w[3], wn = 0.0;
      for (int d = 0; d < 3; ++d) {
        w[d] = v1[d] - v0[d];
        wn += w[d] * n[d];
      }
      // Separating (or sliding along the surface): no contact, except that the remapped velocity of
      // a node in contact this step follows the end velocity's condition whichever its sign.
      if (!remapped && !(wn > 0.0)) continue;
      if (which == NodalVelocity::end) in_contact_[node1] = 1;
      double tangent[3], t_length = 0.0;
      for (int d = 0; d < 3; ++d) {
        tangent[d] = w[d] - wn * n[d];
        t_length += tangent[d] * tangent[d];
      }
      t_length = std::sqrt(t_length);
      const double t_change = t_length > 0.0 ? std::min(mu * std::fabs(wn), t_length) : 0.0;
      const double slip = t_length > 0.0 ? t_change / t_length : 0.0;
      // dw: the change of the relative velocity; field 1 takes m0 / M of it, field 0 m1 / M.
      const GridNode::Vector c0 = corrected(n0, which), c1 = corrected(n1, which);
      for (int d = 0; d < 3; ++d) {
        const double dw = -wn * n[d] - slip * tangent[d];
        c0[d] -= (m1 / M) * dw;
        c1[d] += (m0 / M) * dw;
      }
      // Friction heat: the friction impulse (m0 m1 / M) dw_t times the slip it leaves, |w_t| -
      // dw_t.
      if (which == NodalVelocity::end) work += (m0 * m1 / M) * t_change * (t_length - t_change);
    }
    block_work_[static_cast<std::size_t>(b)] = work;
  }
  ExactSum total;  // the same for any thread count and any numbering of the blocks
  for (const double w : block_work_) total += w;
  return total.value();
}

std::size_t BodyContact::bytes() const {
  return grid_.bytes() + bins_.bytes() + field_.capacity() + in_contact_.capacity() +
         tied_.capacity() + (bond_ ? bond_->bytes() : 0) + meeting0_.capacity() +
         meeting1_.capacity() +
         (normal0_.capacity() + normal1_.capacity() + block_work_.capacity()) * sizeof(double);
}

}  // namespace hvi::mpm
