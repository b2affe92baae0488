#pragma once
// The bond between a honeycomb core and its facesheets (issue #83): an interface of its own. A
// real panel's walls are glued to the sheets by an adhesive fillet that lets go under load, where
// one velocity field would weld them for good. With a bond the core moves on a velocity field of
// its own (contact.hpp's field 1) and is tied to the sheets, no slip and no separation, where its
// points at the sheets are still bonded; where a bond's traction exceeds its strength it breaks,
// and from then on the fields meet there by contact, free to separate, with the sheet's normal
// from the geometry (a wall thinner than a cell has no useful mass gradient).
//
// The interface points are the core's points within a point spacing of a facesheet. Each carries
// its share a_p of the bonded area (the strip of the bond's width under its wall), the unit
// normal n_p pointing from the core into the sheet, and whether it is still bonded. At a node I
// both fields reach, the bond's area is A_I = sum_p a_p N_I(x_p) over the bonded points, and the
// tie is the contact correction that removes the whole relative velocity w = v1 - v0:
//   dv1 = -(m0 / M) w,  dv0 = (m1 / M) w,   the force on the core  F_I = -(m0 m1 / M) w / dt.
// A point takes the share a_p N_Ip / A_I of each node's force, so its traction is
//   t_p = sum_I N_Ip F_I / A_I,   sigma_n = t_p . n_p (tension > 0),   tau = |t_p - sigma_n n_p|,
// (exact for a flat bond whatever the point's place in its cell: a node the sheet does not reach
// carries area but no force), and its bond breaks for good when
//   (max(sigma_n, 0) / S_n)^2 + (tau / S_s)^2 >= 1    (the quadratic rule of cohesive zones).
// Each rank knows every interface point (a few thousand, gathered each step), so the node areas
// are summed in id order alike on every rank: bitwise for any thread and rank count.
#include <cstdint>
#include <vector>

#include "mpm/communicator.hpp"
#include "mpm/grid.hpp"
#include "mpm/particles.hpp"
#include "mpm/shape_functions.hpp"

namespace hvi::mpm {

struct BondSettings {
  double normal_strength = 0.0;  // S_n, Pa
  double shear_strength = 0.0;   // S_s, Pa
};

// One node of a point's stencil: its place in a grid's storage (block * 64 + local) and weight.
struct NodeWeight {
  std::size_t node;
  double N;
};
// The nodes of nonzero weight of a point at x (GIMP half-widths a, m) that `grid` holds, in a
// fixed order.
void stencil_on(const SparseGrid& grid, ShapeFunction shape, const double* x, const double* a,
                std::vector<NodeWeight>& out);

namespace bond_field {
constexpr const char* area = "bond_area";      // a_p, m^2 (0 off the interface)
constexpr const char* normal = "bond_normal";  // n_p, from the core into the sheet
constexpr const char* bonded = "bonded";       // 1 bonded, 0 broken
}  // namespace bond_field

class BondInterface {
 public:
  explicit BondInterface(BondSettings settings) : settings_(settings) {}

  // Declares the interface fields (every point; 0 off the interface).
  static void declare_fields(Particles& particles);

  // Before the step's contact corrections: every rank's interface points, and on field 1's grid
  // (`grid1`, this step's blocks) the bonded area and the sheet's normal at each node.
  void prepare(const Particles& particles, const SparseGrid& grid1, ShapeFunction shape,
               const std::vector<double>* half_width, Communicator* comm);

  // Per node of grid1 (b * 64 + l): the bonded area A_I and the unit normal of the interface
  // there (both 0 where no interface point reaches; the normal is of every interface point, the
  // area of the bonded ones).
  double area(std::size_t node) const { return area_[node]; }
  const double* normal(std::size_t node) const { return &normal_[3 * node]; }
  bool interface(std::size_t node) const { return any_[node] != 0; }
  // The force on the core a tie took at node (b * 64 + l) in the step's end correction, N.
  double* force(std::size_t node) { return &force_[3 * node]; }

  // After the end correction: breaks the bonds of this rank's points whose traction exceeds the
  // strength. Returns how many broke.
  std::int64_t break_overloaded(Particles& particles, const SparseGrid& grid1, ShapeFunction shape,
                                const std::vector<double>* half_width);

  const BondSettings& settings() const { return settings_; }
  std::size_t bytes() const;

 private:
  // An interface point as every rank sees it.
  struct Point {
    std::int64_t id;
    double x[3], a[3];  // position, GIMP half-widths (m)
    double area, n[3];
    bool bonded;
  };
  BondSettings settings_;
  std::vector<Point> points_;  // interface points of every rank, by id
  std::vector<NodeWeight> stencil_;
  std::vector<double> area_, normal_, force_;
  std::vector<std::uint8_t> any_;
};

}  // namespace hvi::mpm
