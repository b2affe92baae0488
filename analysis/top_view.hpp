#pragma once
// The top view of a facesheet: its intact material projected along z onto a raster of square
// pixels. Projecting the whole thickness makes an empty pixel a through-path: a line along z that
// meets no intact material of the sheet (paper Fig. 13, "top views of the front and the rear
// facesheets").
//
// A particle stands for the square footprint of its point spacing h (or 2 x its GIMP half-widths
// when they are known); a pixel is material when its centre lies in some footprint. The default
// raster pixel is h_min / 4 (h_min the finest spacing among the particles): the edge of a
// footprint, and so the hole boundary, is placed to within half a pixel.
#include <cstdint>
#include <span>
#include <vector>

#include "analysis/particle_set.hpp"

namespace hvi::analysis {

struct Raster {
  double x0 = 0, y0 = 0;  // lower-left corner of pixel (0, 0), m
  double cell = 0;        // pixel edge, m
  int nx = 0, ny = 0;
  double spacing = 0;                  // the finest footprint edge among the particles, m
  double closing_radius = 0;           // of the gap closing applied, m
  std::vector<std::uint8_t> material;  // nx * ny, pixel (i, j) at j * nx + i; 1: material

  std::size_t index(int i, int j) const { return static_cast<std::size_t>(j) * nx + i; }
  bool contains(int i, int j) const { return i >= 0 && j >= 0 && i < nx && j < ny; }
  // The pixel holding the point (x, y) (it may lie outside the raster).
  std::array<int, 2> pixel_of(double x, double y) const;
};

struct TopViewOptions {
  double resolution = 0;  // pixel edge, m; 0: a quarter of the finest footprint
  double spacing = 0;  // footprint edge, m, for a set without per-particle spacing or half-widths
  // Closing radius of the material, as a fraction of the finest spacing: gaps narrower than twice
  // this open between intact particles that the flow has pulled apart (the footprints do not
  // stretch with the material) and are not holes. 0.375 fills gaps below 0.75 h (to within a
  // pixel: the disc is a set of whole pixel offsets) and keeps a missing column of one particle
  // (a gap of h). The closing also rounds the hole's convex corners, moving a corner of angle
  // 90 deg by at most (sqrt(2) - 1) x the radius. 0: no closing.
  double gap_closing = 0.375;
  // A point the raster must cover (the impact axis), so that a hole wider than what is left of
  // the sheet still starts on the raster and measures as open (its sizes lower bounds).
  std::optional<std::array<double, 2>> include;
};

// Footprint half-widths (x, y) of particle p, m.
std::array<double, 2> footprint_half_width(const ParticleSet& set, std::size_t p,
                                           const TopViewOptions& options);

// The raster of the footprints of `particles` (indices into `set`), with an empty margin of a few
// pixels (wider than the closing radius) around them, closed with options.gap_closing.
Raster top_view(const ParticleSet& set, std::span<const std::size_t> particles,
                const TopViewOptions& options);

// Morphological closing of the material by a disc of `radius` (m): dilation then erosion by the
// pixel offsets (di, dj) with (di^2 + dj^2) cell^2 <= radius^2. Outside the raster counts as empty.
void close_material(Raster& raster, double radius);

}  // namespace hvi::analysis
