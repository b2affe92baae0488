#include "mpm/io/snapshot_writer.hpp"

#include <algorithm>
#include <fstream>
#include <numeric>
#include <sstream>

#include <fmt/format.h>

#include "mpm/io/hdf5_file.hpp"
#include "mpm/io/id_slabs.hpp"

namespace hvi::mpm::io {

namespace fs = std::filesystem;

SnapshotWriter::SnapshotWriter(fs::path run_directory, const SharedFileAccess* shared)
    : directory_(std::move(run_directory)), shared_(shared) {}

fs::path SnapshotWriter::temporary(const fs::path& file) {
  return file.string() + ".tmp";
}

std::string SnapshotWriter::file_name(std::size_t index) {
  return fmt::format("snapshots/particles_{:06d}.h5", index);
}

std::map<std::size_t, fs::path> SnapshotWriter::files(const fs::path& run_directory) {
  std::map<std::size_t, fs::path> out;
  const fs::path dir = run_directory / "snapshots";
  if (!fs::is_directory(dir)) return out;
  for (const auto& f : fs::directory_iterator(dir)) {
    const std::string name = f.path().filename().string();  // particles_NNNNNN.h5
    if (name.size() != 19 || !name.starts_with("particles_") || !name.ends_with(".h5")) continue;
    const std::string digits = name.substr(10, 6);
    if (digits.find_first_not_of("0123456789") == std::string::npos)
      out.emplace(std::stoul(digits), f.path());
  }
  return out;
}

namespace {

constexpr int derived_fields = 4;  // density, pressure, von Mises stress, volume ratio

using Datasets =
    std::vector<std::pair<std::string, std::pair<int, bool>>>;  // (components, integer)

// Writes the snapshot datasets of `solver` to `path`, each rank its rows with `shared`
// (collective); then one rank adds the attributes. Returns the datasets in order and the number of
// points.
std::pair<Datasets, std::size_t> write_datasets(const fs::path& path, const Solver& solver,
                                                const SharedFileAccess* shared) {
  const Particles& P = solver.particles();
  const std::size_t n = P.size();
  const IdSlabs slabs(P, shared ? solver.communicator() : nullptr);
  const Hdf5File::Rows rows = slabs.rows();
  Datasets datasets;
  {
    Hdf5File file(path.string(), Hdf5File::Mode::create, shared);
    file.write_rows("position", slabs.gather(P.position, 3).data(), rows, 3);
    for (const RealField* f : by_name(P, [](const RealField& f) { return f.output; })) {
      const int nc = components(f->kind);
      file.write_rows(f->name, slabs.gather(*f->data, nc).data(), rows,
                      static_cast<std::size_t>(nc));
    }
    for (const auto& f : P.real_fields())  // listed as declared (the index's order)
      if (f.output && !f.scratch) datasets.push_back({f.name, {components(f.kind), false}});
    // Derived fields a hydrocode user expects to plot.
    std::vector<double> density(n), pressure(n), mises(n), ratio(n);
    for (std::size_t p = 0; p < n; ++p) {
      density[p] = P.mass[p] / P.volume[p];
      pressure[p] = -trace_sym(&P.stress[6 * p]) / 3.0;
      mises[p] = von_mises(&P.stress[6 * p]);
      ratio[p] = P.volume[p] / P.volume0[p];
    }
    for (const auto& [name, data] :
         {std::pair{"density", &density}, std::pair{"pressure", &pressure},
          std::pair{"von_mises_stress", &mises}, std::pair{"volume_ratio", &ratio}}) {
      file.write_rows(name, slabs.gather(*data, 1).data(), rows, 1);
      datasets.push_back({name, {1, false}});
    }
    for (const auto& f : P.int_fields()) {
      file.write_rows(f.name, slabs.gather(*f.data).data(), rows, 1);
      datasets.push_back({f.name, {1, true}});
    }
    file.close();
  }
  if (solver.rank() == 0) {
    Hdf5File file(path.string(), Hdf5File::Mode::append);
    file.write_attribute("time", solver.time());
    file.write_attribute("step", static_cast<std::int64_t>(solver.step_count()));
    // The dataset order, so that a resumed run can rebuild the same index.
    std::string names;
    for (const auto& a : datasets) names += (names.empty() ? "" : ",") + a.first;
    file.write_attribute("fields", names);
    file.close();
  }
  return {datasets, rows.total};
}

}  // namespace

void write_snapshot_file(const fs::path& path, const Solver& solver,
                         const SharedFileAccess* shared) {
  write_datasets(path, solver, shared);
}

std::size_t snapshot_bytes_per_particle(const Particles& P) {
  std::size_t values = 3 + derived_fields + P.int_fields().size();  // position, derived, integers
  for (const auto& f : P.real_fields())
    if (f.output && !f.scratch) values += static_cast<std::size_t>(components(f.kind));
  return 8 * values;
}

void SnapshotWriter::write(const Solver& solver) {
  Entry entry{file_name(next_index_), solver.time(), solver.step_count(), 0, {}};
  fs::create_directories(directory_ / "snapshots");
  // The other ranks of a shared file join in (their driver's write_snapshot_file()).
  if (shared_) solver.announce_write(static_cast<double>(next_index_));
  // Written aside and renamed once complete, as the checkpoint is: a snapshot listed by files()
  // is whole, so `hvi measure` may read a run that is still writing them.
  const fs::path path = directory_ / entry.file;
  const auto [datasets, points] = write_datasets(temporary(path), solver, shared_);
  for (const auto& [name, shape] : datasets)
    entry.attributes.push_back({name, shape.first, shape.second});
  entry.particles = points;
  fs::rename(temporary(path), path);
  entries_.push_back(std::move(entry));
  ++next_index_;
  // The index first lists only what stays, then the files go (ParaView never sees a missing one).
  std::vector<fs::path> dropped;
  while (keep_newest_ > 0 && entries_.size() > keep_newest_ + 1) {
    dropped.push_back(directory_ / entries_[1].file);
    entries_.erase(entries_.begin() + 1);
  }
  write_index();
  for (const auto& f : dropped) fs::remove(f);
}

void SnapshotWriter::resume(std::int64_t last_step) {
  entries_.clear();
  next_index_ = 0;
  // By index: a directory pruned by hand (snapshots deleted to save space) keeps its numbering,
  // and new snapshots never overwrite kept ones.
  for (const auto& [index, path] : files(directory_)) {
    bool keep = false;
    {
      Hdf5File file(path.string(), Hdf5File::Mode::read);
      const std::int64_t step = file.read_integer_attribute("step");
      if (step <= last_step && (entries_.empty() || step >= entries_.back().step)) {
        Entry e{file_name(index),
                file.read_double_attribute("time"),
                step,
                file.shape("position").first,
                {}};
        std::stringstream names(file.read_string_attribute("fields"));
        for (std::string name; std::getline(names, name, ',');) {
          const bool integer = name == "id" || name == "body" || name == "material";
          e.attributes.push_back({name, static_cast<int>(file.shape(name).second), integer});
        }
        entries_.push_back(std::move(e));
        next_index_ = index + 1;
        keep = true;
      }
    }
    if (!keep) fs::remove(path);
  }
  // A snapshot the interrupted run did not finish writing.
  if (fs::is_directory(directory_ / "snapshots"))
    for (const auto& f : fs::directory_iterator(directory_ / "snapshots"))
      if (f.path().extension() == ".tmp") fs::remove(f.path());
  write_index();
}

namespace {
const char* attribute_type(int components) {
  switch (components) {
    case 3:
      return "Vector";
    case 6:
      return "Tensor6";
    case 9:
      return "Tensor";
    default:
      return "Scalar";
  }
}
}  // namespace

void SnapshotWriter::write_index() const {
  std::string xml =
      "<?xml version=\"1.0\" ?>\n"
      "<Xdmf Version=\"3.0\">\n <Domain>\n"
      "  <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const auto& e : entries_) {
    xml += fmt::format("   <Grid Name=\"step_{}\" GridType=\"Uniform\">\n", e.step);
    xml += fmt::format("    <Time Value=\"{:.17g}\"/>\n", e.time);
    xml += fmt::format(
        "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"{}\" "
        "NodesPerElement=\"1\"/>\n",
        e.particles);
    xml += fmt::format(
        "    <Geometry GeometryType=\"XYZ\">\n     <DataItem Dimensions=\"{} 3\" "
        "NumberType=\"Float\" "
        "Precision=\"8\" Format=\"HDF\">{}:/position</DataItem>\n    </Geometry>\n",
        e.particles, e.file);
    for (const auto& a : e.attributes) {
      const std::string dims = a.components == 1 ? fmt::format("{}", e.particles)
                                                 : fmt::format("{} {}", e.particles, a.components);
      xml += fmt::format(
          "    <Attribute Name=\"{}\" AttributeType=\"{}\" Center=\"Node\">\n     <DataItem "
          "Dimensions=\"{}\" NumberType=\"{}\" Precision=\"8\" Format=\"HDF\">{}:/{}</DataItem>\n"
          "    </Attribute>\n",
          a.name, attribute_type(a.components), dims, a.integer ? "Int" : "Float", e.file, a.name);
    }
    xml += "   </Grid>\n";
  }
  xml += "  </Grid>\n </Domain>\n</Xdmf>\n";
  const fs::path tmp = directory_ / "particles.xmf.tmp";
  {
    std::ofstream out(tmp);
    out << xml;
  }
  fs::rename(tmp, directory_ / "particles.xmf");
}

}  // namespace hvi::mpm::io
