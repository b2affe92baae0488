#pragma once
// One facesheet measured as in the paper's Fig. 13: its intact, still attached particles
// (clusters.hpp) in top view (top_view.hpp), the hole at the impact point (hole.hpp) and its sizes
// (hole_geometry.hpp).
#include <array>
#include <cstdint>
#include <vector>

#include "analysis/hole.hpp"
#include "analysis/hole_geometry.hpp"
#include "analysis/top_view.hpp"

namespace hvi::analysis {

struct FacesheetOptions {
  std::array<double, 2> axis{};  // impact point (x0, y0), m
  DiameterRule rule = DiameterRule::two_chords;
  double rotation = 0;  // of the measurement directions, rad
  TopViewOptions view;
  double link_factor = 1.75;  // 0: keep every intact particle, attached or not
};

struct FacesheetResult {
  HoleGeometry hole;
  std::vector<std::size_t>
      attached;              // the sheet's intact attached particles (indices into the set)
  std::size_t intact = 0;    // intact particles of the body
  std::size_t detached = 0;  // of which left out as detached pieces
  Raster raster;
  Hole region;
};

FacesheetResult measure_facesheet(const ParticleSet& set, std::int64_t body,
                                  const FacesheetOptions& options);

}  // namespace hvi::analysis
