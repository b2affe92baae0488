// What ranks send each other (mpm/point_exchange.hpp): points packed on one rank and appended on
// another are the same points, field for field, also where the two declared their fields in
// another order; points of another field set are refused; group loads merge; exact sums add.
#include <bit>
#include <cstring>

#include <gtest/gtest.h>

#include "mpm/grid.hpp"
#include "mpm/point_exchange.hpp"

namespace hvi::mpm {
namespace {

void declare(Particles& P, bool reversed) {
  if (reversed) {
    P.add_field("damage", FieldKind::scalar, "");
    P.add_field("back_stress", FieldKind::sym_tensor, "Pa");
  } else {
    P.add_field("back_stress", FieldKind::sym_tensor, "Pa");
    P.add_field("damage", FieldKind::scalar, "");
  }
}

TEST(PointExchange, PackedPointsArriveFieldForFieldWhateverTheDeclarationOrder) {
  Particles from, to;
  declare(from, false);
  declare(to, true);
  for (int p = 0; p < 5; ++p) {
    const double x[3] = {0.1 * p, -0.2 * p, 0.3};
    from.append(x, 1e-9 * (p + 1), 2.7e-6 * (p + 1), p % 2, 1 - p % 2);
    from.id[p] = 100 + p;
    from.field("damage")[p] = 0.25 * p;
    for (int c = 0; c < 6; ++c) from.field("back_stress")[6 * p + c] = 1e6 * p + c;
    from.stress[6 * p + 3] = -1e9 * p;
    from.internal_energy[p] = 1e3 * p;
  }
  const double x0[3] = {9, 9, 9};
  to.append(x0, 1.0, 1.0, 0, 0);  // a point of its own, kept in front
  const std::vector<std::uint32_t> which{4, 1, 3};
  append_points(to, pack_points(from, which));
  ASSERT_EQ(to.size(), 4u);
  EXPECT_EQ(to.position[0], 9.0);
  for (std::size_t k = 0; k < which.size(); ++k) {
    const std::size_t p = which[k], q = k + 1;
    for (const auto& f : from.real_fields()) {
      if (f.scratch) continue;
      const int nc = components(f.kind);
      for (int c = 0; c < nc; ++c)
        EXPECT_EQ(std::bit_cast<std::uint64_t>((*f.data)[nc * p + c]),
                  std::bit_cast<std::uint64_t>(to.field(f.name)[nc * q + c]))
            << f.name << " of point " << from.id[p];
    }
    EXPECT_EQ(to.id[q], from.id[p]);
    EXPECT_EQ(to.body[q], from.body[p]);
    EXPECT_EQ(to.material[q], from.material[p]);
  }
  // Nothing to send is an empty message, and appends nothing.
  EXPECT_TRUE(pack_points(from, {}).empty());
  append_points(to, {});
  EXPECT_EQ(to.size(), 4u);
}

TEST(PointExchange, PointsOfAnotherFieldSetAreRefused) {
  Particles from, to;
  from.add_field("damage", FieldKind::scalar, "");
  to.add_field("damages", FieldKind::scalar, "");
  const double x[3] = {0, 0, 0};
  from.append(x, 1.0, 1.0, 0, 0);
  const std::vector<std::uint32_t> which{0};
  EXPECT_THROW(append_points(to, pack_points(from, which)), std::logic_error);
}

TEST(PointExchange, GroupOfABlockHalvesItsCoordinates) {
  EXPECT_EQ(group_of_block(SparseGrid::block_key(5, 2, 7)), SparseGrid::block_key(2, 1, 3));
  EXPECT_EQ(group_of_block(SparseGrid::block_key(0, 1, 4)), SparseGrid::block_key(0, 0, 2));
}

}  // namespace
}  // namespace hvi::mpm
