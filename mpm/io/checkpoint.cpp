#include "mpm/io/checkpoint.hpp"

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "mpm/io/hdf5_file.hpp"
#include "mpm/io/id_slabs.hpp"

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
  const std::size_t n = solver.point_count();  // on every rank
  std::size_t values = P.int_fields().size() * n;
  for (const auto& f : P.real_fields())
    if (!f.scratch) values += static_cast<std::size_t>(components(f.kind)) * n;
  for (auto* c : solver.couplings())
    for (const auto& [name, data] : c->state()) values += data.size();
  return 8 * values;
}

namespace {

// The datasets: each rank its rows of every field, in id order (collective with `shared`).
void write_particles(const fs::path& tmp, const Solver& solver, const SharedFileAccess* shared) {
  const Particles& P = solver.particles();
  const IdSlabs slabs(P, shared ? solver.communicator() : nullptr);
  const Hdf5File::Rows rows = slabs.rows();
  Hdf5File file(tmp.string(), Hdf5File::Mode::create, shared);
  file.checksum_datasets();  // a damaged checkpoint is refused on resume, not read wrong
  for (const RealField* f : by_name(P, [](const RealField&) { return true; })) {
    const int nc = components(f->kind);
    file.write_rows("field_" + f->name, slabs.gather(*f->data, nc).data(), rows,
                    static_cast<std::size_t>(nc));
  }
  for (const auto& f : P.int_fields())
    file.write_rows("int_" + f.name, slabs.gather(*f.data).data(), rows, 1);
  // The couplings' state is the same on every rank: the first writes it.
  for (auto* c : solver.couplings())
    for (const auto& [name, data] : c->state())
      file.write_rows(coupled_prefix + name, data.data(),
                      {0, solver.rank() == 0 ? data.size() : 0, data.size()}, 1);
  file.close();
}

// The attributes, by rank 0 alone: the fields' kinds and order, the solver state, the extras.
void write_attributes(const fs::path& tmp, const Solver& solver, const CheckpointExtras& extras) {
  Hdf5File file(tmp.string(), Hdf5File::Mode::append);
  std::string order;  // the fields in the order they were declared, which the snapshots follow
  for (const auto& f : solver.particles().real_fields()) {
    if (f.scratch) continue;
    file.write_attribute(kind_prefix + f.name, static_cast<std::int64_t>(f.kind));
    file.write_attribute(output_prefix + f.name, static_cast<std::int64_t>(f.output));
    order += (order.empty() ? "" : ",") + f.name;
  }
  file.write_attribute(field_order, order);
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
  file.write_attribute("ledger_size", static_cast<std::int64_t>(s.ledger.size()));
  for (std::size_t k = 0; k < s.ledger.size(); ++k)
    file.write_attribute("ledger_" + std::to_string(k), s.ledger[k]);
  for (int d = 0; d < 3; ++d)
    file.write_attribute("removed_momentum_" + std::to_string(d), s.removed.momentum[d]);
  for (const auto& [key, value] : extras) file.write_attribute(extra_prefix + key, value);
  file.close();
}

}  // namespace

fs::path checkpoint_temporary(const fs::path& path) {
  return path.string() + ".tmp";
}

void write_checkpoint(const fs::path& path, const Solver& solver, const CheckpointExtras& extras,
                      const SharedFileAccess* shared) {
  // Written aside and renamed over the last checkpoint only once complete: a write that fails
  // (a full disk) leaves the last checkpoint to resume from (Hdf5File removes the partial one).
  if (shared) solver.announce_write(checkpoint_file);  // the other ranks write their rows
  write_particles(checkpoint_temporary(path), solver, shared);
  if (solver.rank() != 0) return;
  write_attributes(checkpoint_temporary(path), solver, extras);
  fs::rename(checkpoint_temporary(path), path);
}

CheckpointExtras read_checkpoint(const fs::path& path, Solver& solver) {
  Hdf5File file(path.string(), Hdf5File::Mode::read);
  Particles& P = solver.particles();
  // Each rank of a run spread over ranks reads its share of the rows (the first step sends
  // each point to the rank of its block group).
  const std::size_t all = file.shape("int_id").first;
  const auto rank = static_cast<std::size_t>(solver.rank());
  const auto ranks = static_cast<std::size_t>(solver.ranks());
  const std::size_t first = all * rank / ranks, n = all * (rank + 1) / ranks - first;
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
      data = file.read_doubles(name, first, n);
    } else if (name.rfind("int_", 0) == 0) {
      const std::string field = name.substr(4);
      for (const auto& f : P.int_fields())
        if (f.name == field) *f.data = file.read_integers(name, first, n);
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
  if (file.has_attribute("ledger_size"))
    for (std::int64_t k = 0; k < file.read_integer_attribute("ledger_size"); ++k)
      s.ledger.push_back(file.read_double_attribute("ledger_" + std::to_string(k)));
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
