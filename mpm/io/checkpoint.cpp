#include "mpm/io/checkpoint.hpp"

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "mpm/io/hdf5_file.hpp"

namespace hvi::mpm::io {

namespace fs = std::filesystem;

namespace {
const std::string kind_prefix = "kind:";      // attribute kind:<name> = FieldKind
const std::string output_prefix = "output:";  // attribute output:<name> = 1 if snapshots hold it
const std::string extra_prefix = "extra:";
const std::string coupled_prefix = "coupled_";  // datasets of the couplings' state
const std::string field_order = "field_order";  // attribute: the fields' names in declaration order
}  // namespace

std::size_t checkpoint_bytes(const Solver& solver) {
  const Particles& P = solver.particles();
  std::size_t values = P.int_fields().size() * P.size();
  for (const auto& f : P.real_fields())
    if (!f.scratch) values += static_cast<std::size_t>(components(f.kind)) * P.size();
  for (auto* c : solver.couplings())
    for (const auto& [name, data] : c->state()) values += data.size();
  return 8 * values;
}

void write_checkpoint(const fs::path& path, const Solver& solver, const CheckpointExtras& extras) {
  // Written aside and renamed over the last checkpoint only once complete: a write that fails
  // (a full disk) leaves the last checkpoint to resume from (Hdf5File removes the partial one).
  const fs::path tmp = path.string() + ".tmp";
  {
    Hdf5File file(tmp.string(), Hdf5File::Mode::create);
    file.checksum_datasets();  // a damaged checkpoint is refused on resume, not read wrong
    const Particles& P = solver.particles();
    const std::size_t n = P.size();
    std::string order;  // the fields in the order they were declared, which the snapshots follow
    for (const auto& f : P.real_fields()) {
      if (f.scratch) continue;
      const int nc = components(f.kind);
      file.write("field_" + f.name, f.data->data(), n, nc);
      file.write_attribute(kind_prefix + f.name, static_cast<std::int64_t>(f.kind));
      file.write_attribute(output_prefix + f.name, static_cast<std::int64_t>(f.output));
      order += (order.empty() ? "" : ",") + f.name;
    }
    file.write_attribute(field_order, order);
    for (const auto& f : P.int_fields()) file.write("int_" + f.name, f.data->data(), n, 1);
    const SolverState& s = solver.state();
    file.write_attribute("time", s.time);
    file.write_attribute("step", static_cast<std::int64_t>(s.step));
    file.write_attribute("next_dt", s.next_dt);
    file.write_attribute("first_dt", s.first_dt);
    file.write_attribute("removed_particles", static_cast<std::int64_t>(s.removed.particles));
    file.write_attribute("removed_mass", s.removed.mass);
    file.write_attribute("removed_kinetic", s.removed.kinetic);
    file.write_attribute("removed_internal", s.removed.internal);
    file.write_attribute("contact_work", s.contact_work);
    for (int d = 0; d < 3; ++d)
      file.write_attribute("removed_momentum_" + std::to_string(d), s.removed.momentum[d]);
    for (const auto& [key, value] : extras) file.write_attribute(extra_prefix + key, value);
    for (auto* c : solver.couplings())
      for (const auto& [name, data] : c->state())
        file.write(coupled_prefix + name, data.data(), data.size(), 1);
    file.close();
  }
  fs::rename(tmp, path);
}

CheckpointExtras read_checkpoint(const fs::path& path, Solver& solver) {
  Hdf5File file(path.string(), Hdf5File::Mode::read);
  Particles& P = solver.particles();
  const std::size_t n = file.shape("int_id").first;
  P.resize(n);
  // Fields the models declare only once they run are declared here, in the order the checkpoint
  // lists them (HDF5 lists its datasets alphabetically), so a resumed run's snapshots hold their
  // fields in the same order as an uninterrupted run's, to the byte.
  std::vector<std::string> names;
  if (file.has_attribute(field_order)) {
    std::stringstream list(file.read_string_attribute(field_order));
    for (std::string f; std::getline(list, f, ',');) names.push_back("field_" + f);
  }
  for (const auto& name : file.dataset_names())
    if (name.rfind("field_", 0) != 0 || std::find(names.begin(), names.end(), name) == names.end())
      names.push_back(name);
  for (const auto& name : names) {
    if (name.rfind("field_", 0) == 0) {
      const std::string field = name.substr(6);
      const auto kind = static_cast<FieldKind>(file.read_integer_attribute(kind_prefix + field));
      // A field the snapshots did not hold (e.g. eos_pressure) stays out of them after a resume.
      const bool output = file.has_attribute(output_prefix + field)
                              ? file.read_integer_attribute(output_prefix + field) != 0
                              : field != "gimp_half_width";
      std::vector<double>& data =
          P.has_field(field) ? P.field(field) : P.add_field(field, kind, "", 0.0, output);
      data = file.read_doubles(name);
    } else if (name.rfind("int_", 0) == 0) {
      const std::string field = name.substr(4);
      for (const auto& f : P.int_fields())
        if (f.name == field) *f.data = file.read_integers(name);
    }
  }
  SolverState s;
  s.time = file.read_double_attribute("time");
  s.step = file.read_integer_attribute("step");
  s.next_dt = file.read_double_attribute("next_dt");
  s.first_dt = file.read_double_attribute("first_dt");
  s.removed.particles = file.read_integer_attribute("removed_particles");
  s.removed.mass = file.read_double_attribute("removed_mass");
  s.removed.kinetic = file.read_double_attribute("removed_kinetic");
  s.removed.internal = file.read_double_attribute("removed_internal");
  if (file.has_attribute("contact_work"))
    s.contact_work = file.read_double_attribute("contact_work");
  for (int d = 0; d < 3; ++d)
    s.removed.momentum[d] = file.read_double_attribute("removed_momentum_" + std::to_string(d));
  for (auto* c : solver.couplings())
    for (const auto& [name, data] : c->state()) {
      if (!file.has_dataset(coupled_prefix + name))
        throw Hdf5Error(path.string() + " holds no " + name +
                        ": it was written by a run without this coupled model");
      const std::vector<double> saved = file.read_doubles(coupled_prefix + name);
      if (saved.size() != data.size())
        throw Hdf5Error(path.string() + ": " + name + " has " + std::to_string(saved.size()) +
                        " values, this scene's " + std::to_string(data.size()));
      std::copy(saved.begin(), saved.end(), data.begin());
    }
  solver.restore(s);
  CheckpointExtras extras;
  for (const auto& name : file.attribute_names())
    if (name.rfind(extra_prefix, 0) == 0)
      extras[name.substr(extra_prefix.size())] = file.read_double_attribute(name);
  return extras;
}

}  // namespace hvi::mpm::io
