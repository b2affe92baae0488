#include "analysis/facesheet.hpp"

#include "analysis/clusters.hpp"

namespace hvi::analysis {

FacesheetResult measure_facesheet(const ParticleSet& set, std::int64_t body,
                                  const FacesheetOptions& options) {
  FacesheetResult out;
  const std::vector<std::size_t> intact = particles_of(set, body, true);
  out.intact = intact.size();
  out.attached = options.link_factor > 0
                     ? attached_clusters(set, intact, options.link_factor, options.view.spacing)
                     : intact;
  out.detached = out.intact - out.attached.size();
  const auto [x0, y0] = options.axis;
  if (out.attached.empty()) {  // nothing of the sheet is left: perforated, no hole to measure
    out.hole.perforated = out.hole.open = true;
    out.hole.rule = options.rule;
    out.hole.rotation = options.rotation;
    return out;
  }
  TopViewOptions view = options.view;
  view.include = options.axis;
  out.raster = top_view(set, out.attached, view);
  out.region = find_hole(out.raster, x0, y0);
  out.hole = measure_hole(out.raster, out.region, x0, y0, options.rule, options.rotation);
  return out;
}

}  // namespace hvi::analysis
