#pragma once
// A displacement probe read after a run, from what it wrote (hvi probe): for a point the scene did
// not name as a [[measure]] of kind "displacement", or one thought of later. It reads the point as
// the run's own probes do (probes.hpp), in the undeformed configuration:
//   - in a hybrid's far field (the point outside [far_field.zone] in plane): the nearest far-field
//     node, u = its displacement, from DIR/far_field/nodes_<step>.h5;
//   - with a zone that grows, from the first far-field snapshot in which a grown zone has taken
//     that node over (its lumped mass is 0): the points of the nearest point's body whose
//     undeformed positions X (the snapshots' reference_position) lie within one grid cell of the
//     point, u = mean (x_p - X_p), in the particle snapshot nearest in time;
//   - otherwise the particles of the nearest particle's body within one grid cell of the point in
//     the first snapshot, followed by id: u = mean (x_p - x_p^0) over those still in the model.
// So on a run's own probe point it gives the run's probes.csv values at the snapshot times (after
// a take-over to within the far field's displacement gradient over a cell: the run's probe goes
// on from its node's reading, this from the points' own X).
#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace hvi::driver {

struct ProbeReading {
  std::vector<std::array<double, 2>> rows;  // (time s, displacement component m) per snapshot
  std::string source;                       // what was read: the node, or how many points
};

// Throws std::invalid_argument when the run lacks what the point needs (snapshots, the far
// field's node files, reference positions), scene::SceneError for its resolved scene.
ProbeReading read_probe(const std::filesystem::path& run, const std::array<double, 3>& point,
                        int axis);

}  // namespace hvi::driver
