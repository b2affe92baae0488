#pragma once
// What geometry/ hands to the solver: plain points with the volume each one represents and the
// half-width of the region it stands for (for GIMP particle domains).
#include <cstddef>
#include <vector>

namespace hvi::geometry {

struct PointSet {
  std::vector<double> position;  // 3 per point, m
  std::vector<double> volume;    // m^3: the body's exact volume shared out (sampler.hpp)
  // 3 per point, m: half the point spacing along x, y, z. Lattice points: spacing / 2 on every
  // axis (finer in a refinement zone). Thin-wall points (one layer on the wall mid-surface, whose
  // volume is thickness x along-wall spacing x height spacing): the along-wall spacing / 2 in x
  // and y and the height spacing / 2 in z, never more than the coarse spacing / 2.
  std::vector<double> half_width;
  std::size_t size() const { return volume.size(); }
  double total_volume() const;
  void reserve(std::size_t n);
  void append(const PointSet& other);
};

}  // namespace hvi::geometry
