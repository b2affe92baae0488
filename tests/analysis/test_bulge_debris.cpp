// Bulge of a rear facesheet (largest displacement along the impact direction, matched by id) and
// the debris cloud behind it, on small synthetic sets with answers computed by hand.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include <gtest/gtest.h>

#include "analysis/bulge.hpp"
#include "analysis/clusters.hpp"
#include "analysis/debris.hpp"
#include "synthetic.hpp"

namespace hvi::analysis {
namespace {

constexpr double mm = 1e-3;
constexpr double h = 0.1 * mm;

// A 4 x 4 mm rear sheet (2 layers) pushed along -z by a Gaussian bump A exp(-r^2 / w^2): the bulge
// is A exp(-r_min^2 / w^2), r_min the distance of the nearest lattice column to the axis
// (h / sqrt(2)). The current set is shuffled: the match is by id, not by position in the arrays.
// A failed particle thrown far (5 mm) is left out with the other failed ones, and an intact chip
// 3 mm behind the sheet is left out as detached (attached_clusters).
TEST(Bulge, GaussianBumpMatchedById) {
  const double A = 0.3 * mm, w = 1 * mm;
  const ParticleData initial = test::plate(2 * mm, h, 2, {}, false, 0, -10 * mm);
  ParticleData current = copy_of(initial.view());
  for (std::size_t p = 0; p < current.size(); ++p) {
    const double r2 = current.position[3 * p] * current.position[3 * p] +
                      current.position[3 * p + 1] * current.position[3 * p + 1];
    current.position[3 * p + 2] -= A * std::exp(-r2 / (w * w));
  }
  current.failed[7] = 1;
  current.position[3 * 7 + 2] -= 5 * mm;
  current.position[3 * 8 + 2] -= 3 * mm;  // an intact chip, torn off
  // Shuffle the current arrays.
  std::vector<std::size_t> order(current.size());
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), std::mt19937(42));
  ParticleData shuffled;
  for (const std::size_t p : order) {
    shuffled.position.insert(shuffled.position.end(), current.position.begin() + 3 * p,
                             current.position.begin() + 3 * p + 3);
    shuffled.id.push_back(current.id[p]);
    shuffled.body.push_back(0);
    shuffled.failed.push_back(current.failed[p]);
    shuffled.spacing.push_back(h);
  }
  const auto intact = particles_of(shuffled.view(), 0, true);
  const auto attached = attached_clusters(shuffled.view(), intact, 1.75, 0);
  EXPECT_EQ(attached.size(), current.size() - 2);
  const Bulge b = rear_bulge(initial.view(), shuffled.view(), attached, {0, 0, -1});
  const double expected = A * std::exp(-(h * h / 2) / (w * w));
  EXPECT_NEAR(b.displacement, expected, 1e-15);  // the same arithmetic: round-off only
  EXPECT_EQ(b.unmatched, 0u);
  EXPECT_NEAR(std::hypot(b.position[0], b.position[1]), h / std::sqrt(2.0), 1e-15);
  // Every intact particle, detached or not: the chip's 3 mm on top of its share of the bump.
  EXPECT_NEAR(rear_bulge(initial.view(), shuffled.view(), intact, {0, 0, -1}).displacement,
              initial.position[3 * 8 + 2] - current.position[3 * 8 + 2], 1e-15);
}

// Debris behind a rear face at z = -10 mm (its back surface; d = -z): particles more than one
// spacing behind it are counted, of any body, except the excluded sheet particles. Known set:
// 3 particles at 0.5, 2 and 4 mm behind, 1, 3 and 0.5 mm off the axis, and one only 0.05 mm behind
// (inside the threshold).
TEST(Debris, MassAndExtents) {
  ParticleData p;
  auto add = [&](double x, double y, double z, double m, std::int64_t body) {
    p.position.insert(p.position.end(), {x, y, z});
    p.velocity.insert(p.velocity.end(), {10.0 * body, 20.0, -100.0});  // |v|^2 = 10400 + 100 body^2
    p.id.push_back(static_cast<std::int64_t>(p.id.size()));
    p.body.push_back(body);
    p.mass.push_back(m);
  };
  const double back = -10 * mm;
  add(1 * mm, 0, back - 0.5 * mm, 1e-6, 0);
  add(0, 3 * mm, back - 2 * mm, 2e-6, 1);
  add(0.3 * mm, 0.4 * mm, back - 4 * mm, 3e-6, 2);
  add(0, 0, back - 0.05 * mm, 5e-6, 1);       // within one spacing of the face: not debris
  add(0, 0, back + 1 * mm, 7e-6, 0);          // in front of the face
  add(0, 0.5 * mm, back - 1 * mm, 11e-6, 3);  // the sheet's own bulge: excluded
  DebrisOptions o;
  o.axis_point = {0, 0, 0};
  o.direction = {0, 0, -2};  // normalised inside
  o.back_face = -back;       // (x - a) . d of the back surface
  o.threshold = h;
  const std::vector<std::size_t> sheet{5};
  const Debris d = debris_cloud(p.view(), o, sheet);
  EXPECT_EQ(d.particles, 3u);
  EXPECT_NEAR(d.mass, 6e-6, 1e-18);
  EXPECT_NEAR(d.axial_extent, 4 * mm, 1e-12);
  EXPECT_NEAR(d.radial_extent, 3 * mm, 1e-12);
  // 1/2 m |v|^2 of the three: bodies 0, 1, 2 with 1, 2 and 3 ug.
  const double ke = 0.5 * (1e-6 * 10400 + 2e-6 * 10500 + 3e-6 * 10800);
  EXPECT_NEAR(d.kinetic_energy, ke, 1e-15);

  // A half model (y >= 0 here) mirrored across y = 0: twice the mass, the same extents.
  const ParticleData whole = mirrored(p.view(), {.x = std::nullopt, .y = 0.0}, 100);
  const std::vector<std::size_t> sheets{5, 5 + p.size()};
  const Debris dw = debris_cloud(whole.view(), o, sheets);
  EXPECT_EQ(dw.particles, 6u);
  EXPECT_NEAR(dw.mass, 12e-6, 1e-18);
  EXPECT_NEAR(dw.axial_extent, 4 * mm, 1e-12);
  EXPECT_NEAR(dw.radial_extent, 3 * mm, 1e-12);
  EXPECT_NEAR(dw.kinetic_energy, 2 * ke, 1e-15);       // the images move mirrored, as fast
  EXPECT_EQ(whole.velocity[3 * p.size() + 1], -20.0);  // v_y of the first image, across y = 0
}

// A measurement mirrors only the particles it reads: the images of a listed subset are exactly
// the full mirrored set's rows for those particles (positions, ids, velocities, every field), in
// the set's order, and each field holds exactly their size (a quarter model's 4 copies of the
// model's points are the measure's largest allocation).
TEST(Mirror, ASubsetGivesTheFullImagesOfItsParticles) {
  const ParticleData plate = test::plate(1 * mm, h, 2, {}, false, 0, 0.0);
  ParticleData p = test::cut(plate.view(), true, true);  // the quarter x, y > 0, with spacings
  for (std::size_t k = 0; k < p.size(); ++k) {
    p.velocity.insert(p.velocity.end(), {1.0 + k, 2.0 * k, -3.0});
    p.half_width.insert(p.half_width.end(), {h / 2, h / 2, h / 2});
  }
  const MirrorPlanes planes{.x = 0.0, .y = 0.0};
  const std::int64_t stride = 1000;
  const ParticleData full = mirrored(p.view(), planes, stride);
  const std::vector<std::size_t> subset{1, 4, 5, p.size() - 1};
  const ParticleData part = mirrored(p.view(), planes, stride, subset);
  ASSERT_EQ(part.size(), 4 * subset.size());
  for (std::size_t image = 0; image < 4; ++image)
    for (std::size_t i = 0; i < subset.size(); ++i) {
      const std::size_t a = image * subset.size() + i, b = image * p.size() + subset[i];
      EXPECT_EQ(part.id[a], full.id[b]);
      EXPECT_EQ(part.id[a], p.id[subset[i]] + static_cast<std::int64_t>(image) * stride);
      EXPECT_EQ(part.body[a], full.body[b]);
      EXPECT_EQ(part.mass[a], full.mass[b]);
      EXPECT_EQ(part.volume[a], full.volume[b]);
      EXPECT_EQ(part.failed[a], full.failed[b]);
      EXPECT_EQ(part.spacing[a], full.spacing[b]);
      for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(part.position[3 * a + c], full.position[3 * b + c]);
        EXPECT_EQ(part.velocity[3 * a + c], full.velocity[3 * b + c]);
        EXPECT_EQ(part.half_width[3 * a + c], full.half_width[3 * b + c]);
      }
    }
  // Image 3 is mirrored across both planes: x and y and their velocities change sign.
  const std::size_t last = 3 * subset.size();
  EXPECT_EQ(part.position[3 * last], -p.position[3 * subset[0]]);
  EXPECT_EQ(part.position[3 * last + 1], -p.position[3 * subset[0] + 1]);
  EXPECT_EQ(part.velocity[3 * last + 1], -p.velocity[3 * subset[0] + 1]);
  for (const ParticleData* d : {&full, &part}) {
    EXPECT_EQ(d->position.capacity(), d->position.size());
    EXPECT_EQ(d->velocity.capacity(), d->velocity.size());
    EXPECT_EQ(d->half_width.capacity(), d->half_width.size());
    EXPECT_EQ(d->id.capacity(), d->id.size());
    EXPECT_EQ(d->body.capacity(), d->body.size());
    EXPECT_EQ(d->mass.capacity(), d->mass.size());
    EXPECT_EQ(d->volume.capacity(), d->volume.size());
    EXPECT_EQ(d->failed.capacity(), d->failed.size());
    EXPECT_EQ(d->spacing.capacity(), d->spacing.size());
  }
}

}  // namespace
}  // namespace hvi::analysis
