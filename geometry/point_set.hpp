#pragma once
// What geometry/ hands to the solver: plain points with the volume each one represents.
#include <vector>

namespace hvi::geometry {

struct PointSet {
  std::vector<double> position;  // 3 per point, m
  std::vector<double> volume;    // m^3
  std::size_t size() const { return volume.size(); }
  double total_volume() const;
};

}  // namespace hvi::geometry
