// Restart and output (mpm/io): a run resumed from a checkpoint ends bitwise identical to the
// uninterrupted run; snapshots hold the particles in id order, the XDMF index points at datasets
// that exist, and the same state always gives the same bytes.
#include <sys/resource.h>

#include <algorithm>
#include <csignal>
#include <fstream>
#include <iterator>
#include <numeric>
#include <optional>
#include <regex>
#include <set>
#include <tuple>

#include <gtest/gtest.h>

#include "mpm/io/checkpoint.hpp"
#include "mpm/io/energy_log.hpp"
#include "mpm/io/hdf5_file.hpp"
#include "mpm/io/snapshot_writer.hpp"
#include "mpm_test_helpers.hpp"

namespace hvi::mpm::test {
namespace {

namespace fs = std::filesystem;

constexpr int kSteps = 50;       // N
constexpr int kCheckpoint = 25;  // k: the cube is leaving (steps ~17-30), a reorder is due

SolverSettings settings_for(ShapeFunction shape, bool contact = false, bool ledger = false) {
  SolverSettings s;
  s.shape = shape;
  s.reorder_interval = 5;
  if (contact)
    s.contact = ContactSettings{{0, 1, 0}, 0.2, std::nullopt};  // the right sphere on its own field
  s.energy_ledger = ledger;
  return s;
}

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

struct RestartCase {
  ShapeFunction shape;
  bool populated;  // the fresh solver already holds the (uninitialised) scene particles
  const char* name;
  bool contact = false;  // with [contact]: its work is carried across the restart
  bool ledger = false;   // with the energy ledger: its totals are carried across the restart
};

// Names the case in test listings (instead of a byte dump of the struct).
void PrintTo(const RestartCase& c, std::ostream* os) {
  *os << c.name;
}

class Restart : public ::testing::TestWithParam<RestartCase> {};

TEST_P(Restart, ResumedRunIsBitwiseIdentical) {
  const RestartCase c = GetParam();
  TempDir dir(std::string("restart_") + c.name);
  const fs::path file = dir.path() / "checkpoint.h5";

  // Uninterrupted run on one thread, writing a checkpoint at step k; the resumed run uses two
  // (a restart on another machine), which must not matter either.
  std::optional<Threads> threads(std::in_place, 1);
  auto reference = small_scene(settings_for(c.shape, c.contact, c.ledger));
  // A field kept out of the snapshots (as a material's eos_pressure is) stays out after a resume.
  reference->particles().add_field("hidden_state", FieldKind::scalar, "1", 0.0, false);
  for (int k = 0; k < kSteps; ++k) {
    if (reference->step_count() == kCheckpoint)
      io::write_checkpoint(file, *reference, {{"next_snapshot", 0.125}, {"snapshots", 3.0}});
    reference->step();
  }
  ASSERT_TRUE(fs::exists(file));
  ASSERT_FALSE(fs::exists(file.string() + ".tmp"));

  // A fresh solver from the same set-up (not initialised), restored and continued to N.
  auto resumed = small_scene_solver(settings_for(c.shape, c.contact, c.ledger));
  // Populated: the scene's particles as a driver would create them before noticing the restart.
  if (c.populated) add_small_scene_bodies(*resumed);
  threads.emplace(2);
  const io::CheckpointExtras extras = io::read_checkpoint(file, *resumed);
  EXPECT_EQ(extras.at("next_snapshot"), 0.125);
  EXPECT_EQ(extras.at("snapshots"), 3.0);
  EXPECT_EQ(resumed->step_count(), kCheckpoint);
  while (resumed->step_count() < kSteps) resumed->step();

  // Bitwise: every field, the state and the ledger of removed material (which gained particles
  // both before and after the checkpoint).
  EXPECT_TRUE(identical_particles(reference->particles(), resumed->particles()));
  EXPECT_TRUE(identical_state(*reference, *resumed));
  EXPECT_GT(reference->removed().particles, 0);
  if (c.contact) {
    EXPECT_GT(reference->state().contact_work, 0.0);
  }
  if (c.ledger) {
    EXPECT_FALSE(reference->state().ledger.empty());
  }
  for (const auto& f : reference->particles().real_fields()) {
    if (f.scratch) continue;
    const auto& fields = resumed->particles().real_fields();
    const auto same =
        std::find_if(fields.begin(), fields.end(), [&](const auto& g) { return g.name == f.name; });
    ASSERT_NE(same, fields.end()) << f.name;
    EXPECT_EQ(same->output, f.output) << f.name;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Shapes, Restart,
    ::testing::Values(RestartCase{ShapeFunction::linear, false, "linear_empty"},
                      RestartCase{ShapeFunction::linear, true, "linear_populated"},
                      RestartCase{ShapeFunction::gimp, false, "gimp_empty"},
                      RestartCase{ShapeFunction::gimp, true, "gimp_populated"},
                      RestartCase{ShapeFunction::gimp, false, "gimp_contact", true},
                      RestartCase{ShapeFunction::gimp, false, "gimp_contact_ledger", true, true}),
    [](const ::testing::TestParamInfo<RestartCase>& info) { return std::string(info.param.name); });

// The removed-material ledger of the scene gains entries on both sides of the checkpoint, so the
// restart test above covers a ledger carried across the restart.
TEST(Restart, SceneRemovesParticlesAroundTheCheckpoint) {
  const Threads threads(1);  // ~1900 particles
  auto s = small_scene(settings_for(ShapeFunction::linear));
  while (s->step_count() < kCheckpoint) s->step();
  const auto before = s->removed().particles;
  while (s->step_count() < kSteps) s->step();
  EXPECT_GT(before, 0);
  EXPECT_GT(s->removed().particles, before);
}

// Lowers this process's file-size limit while it lives: a write past it fails with EFBIG, as a
// write to a full disk fails with ENOSPC, part-way through a file (SIGXFSZ is ignored meanwhile).
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    getrlimit(RLIMIT_FSIZE, &saved_);
    handler_ = std::signal(SIGXFSZ, SIG_IGN);
    rlimit lower = saved_;
    lower.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &lower);
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &saved_);
    std::signal(SIGXFSZ, handler_);
  }
  FileSizeLimit(const FileSizeLimit&) = delete;
  FileSizeLimit& operator=(const FileSizeLimit&) = delete;

 private:
  rlimit saved_{};
  void (*handler_)(int) = SIG_DFL;
};

// A disk that fills during a long run: the checkpoint write that fails keeps the last checkpoint
// to the byte (the run resumes from it) and leaves no partial file holding space; a snapshot that
// fails leaves no truncated file for a measurement to read, nor an index entry pointing at it.
TEST(Restart, FailedWritesLeaveNoPartialFiles) {
  const Threads threads(1);  // ~1900 particles
  TempDir dir("failed_writes");
  const fs::path file = dir.path() / "checkpoint.h5";
  auto s = small_scene(settings_for(ShapeFunction::linear));
  io::write_checkpoint(file, *s, {});
  const std::string last = read_file(file);
  ASSERT_GT(last.size(), 100000u);
  io::SnapshotWriter writer(dir.path());
  writer.write(*s);
  const std::string index = read_file(dir.path() / "particles.xmf");
  s->step();
  {
    const FileSizeLimit limit(last.size() / 2);  // the first datasets fit, a later one does not
    EXPECT_THROW(io::write_checkpoint(file, *s, {}), io::Hdf5Error);
    EXPECT_THROW(writer.write(*s), io::Hdf5Error);
  }
  EXPECT_EQ(read_file(file), last);
  EXPECT_FALSE(fs::exists(file.string() + ".tmp"));
  EXPECT_EQ(
      std::distance(fs::directory_iterator(dir.path() / "snapshots"), fs::directory_iterator()), 1);
  EXPECT_EQ(read_file(dir.path() / "particles.xmf"), index);
}

// The HDF references of an XDMF index: (dimensions, file, dataset) per DataItem.
using XmfItem = std::tuple<std::string, std::string, std::string>;
std::multiset<XmfItem> xmf_items(const std::string& xmf) {
  const std::regex item(R"re(<DataItem Dimensions="([\d ]+)"[^>]*>([^:<]+):/([^<]+)</DataItem>)re");
  std::multiset<XmfItem> items;
  for (auto it = std::sregex_iterator(xmf.begin(), xmf.end(), item); it != std::sregex_iterator();
       ++it)
    items.insert({(*it)[1], (*it)[2], (*it)[3]});
  return items;
}

TEST(Snapshots, XdmfIndexAndIdOrder) {
  const Threads threads(1);  // ~1900 particles
  TempDir dir("snapshots");
  auto s = small_scene(settings_for(ShapeFunction::gimp));
  io::SnapshotWriter writer(dir.path());
  writer.write(*s);
  for (int k = 0; k < 20; ++k) s->step();  // arrays are now reordered (steps 5, 10, 15)
  writer.write(*s);
  EXPECT_EQ(writer.count(), 2u);

  // Every HDF dataset the index names exists with the advertised shape.
  const std::string xmf = read_file(dir.path() / "particles.xmf");
  const std::regex item(
      R"(<DataItem Dimensions="(\d+)(?: (\d+))?"[^>]*>([^:<]+):/([^<]+)</DataItem>)");
  std::set<std::string> files, names;
  int items = 0;
  for (auto it = std::sregex_iterator(xmf.begin(), xmf.end(), item); it != std::sregex_iterator();
       ++it) {
    const auto& m = *it;
    const std::string path = m[3], name = m[4];
    files.insert(path);
    names.insert(name);
    ++items;
    ASSERT_TRUE(fs::exists(dir.path() / path)) << path;
    io::Hdf5File h5((dir.path() / path).string(), io::Hdf5File::Mode::read);
    ASSERT_TRUE(h5.has_dataset(name)) << path << ":/" << name;
    const auto [rows, columns] = h5.shape(name);
    EXPECT_EQ(std::to_string(rows), m[1].str()) << name;
    EXPECT_EQ(m[2].matched ? m[2].str() : "1", std::to_string(columns)) << name;
  }
  EXPECT_EQ(files, (std::set<std::string>{"snapshots/particles_000000.h5",
                                          "snapshots/particles_000001.h5"}));
  for (const char* n : {"position", "velocity", "stress", "mass", "id", "density", "pressure"})
    EXPECT_TRUE(names.count(n)) << n;
  EXPECT_FALSE(names.count("gimp_half_width"));  // not an output field
  EXPECT_GT(items, 20);
  EXPECT_NE(xmf.find("<Time Value="), std::string::npos);

  // The second snapshot holds the current particles in id order.
  io::Hdf5File h5((dir.path() / io::SnapshotWriter::file_name(1)).string(),
                  io::Hdf5File::Mode::read);
  EXPECT_EQ(h5.read_integer_attribute("step"), 20);
  EXPECT_EQ(h5.read_double_attribute("time"), s->time());
  const Particles& P = s->particles();
  std::vector<std::size_t> order(P.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return P.id[a] < P.id[b]; });
  EXPECT_FALSE(std::is_sorted(P.id.begin(), P.id.end()));  // the write really had to sort
  const std::vector<double> x = h5.read_doubles("position");
  const std::vector<std::int64_t> id = h5.read_integers("id");
  ASSERT_EQ(x.size(), 3 * P.size());
  ASSERT_EQ(id.size(), P.size());
  for (std::size_t k = 0; k < P.size(); ++k) {
    ASSERT_EQ(id[k], P.id[order[k]]);
    for (int d = 0; d < 3; ++d)
      ASSERT_EQ(x[3 * k + d], P.position[3 * order[k] + d]);  // exact copy
  }
}

TEST(Snapshots, SameStateGivesSameBytes) {
  const Threads threads(1);  // ~1900 particles
  TempDir dir("snapshot_bytes");
  auto s = small_scene(settings_for(ShapeFunction::linear));
  for (int k = 0; k < 7; ++k) s->step();
  io::SnapshotWriter a(dir.path() / "a"), b(dir.path() / "b");
  a.write(*s);
  b.write(*s);
  const std::string fa = read_file(dir.path() / "a" / io::SnapshotWriter::file_name(0));
  const std::string fb = read_file(dir.path() / "b" / io::SnapshotWriter::file_name(0));
  EXPECT_GT(fa.size(), 1000u);
  EXPECT_TRUE(fa == fb) << "snapshot files differ (" << fa.size() << " vs " << fb.size()
                        << " bytes)";
  EXPECT_EQ(read_file(dir.path() / "a" / "particles.xmf"),
            read_file(dir.path() / "b" / "particles.xmf"));
  // Checkpoints likewise.
  io::write_checkpoint(dir.path() / "c1.h5", *s, {});
  io::write_checkpoint(dir.path() / "c2.h5", *s, {});
  EXPECT_TRUE(read_file(dir.path() / "c1.h5") == read_file(dir.path() / "c2.h5"));
  // What a run announces it will write (the disk it needs): the datasets' bytes, which the files
  // exceed only by their HDF5 metadata (measured 6.1 and 6.7 kB here, for 333 and 288 kB of data;
  // bound 32 kB).
  const double snapshot =
      static_cast<double>(io::snapshot_bytes_per_particle(s->particles()) * s->particles().size());
  const double checkpoint = static_cast<double>(io::checkpoint_bytes(*s));
  EXPECT_GE(static_cast<double>(fa.size()), snapshot);
  EXPECT_LT(static_cast<double>(fa.size()), snapshot + 32e3);
  const auto c = static_cast<double>(fs::file_size(dir.path() / "c1.h5"));
  EXPECT_GE(c, checkpoint);
  EXPECT_LT(c, checkpoint + 32e3);
}

}  // namespace
}  // namespace hvi::mpm::test

namespace hvi::mpm::test {
namespace {

// A resumed run keeps the snapshots up to the restart step, deletes later ones and rebuilds the
// same index entries (same datasets and dimensions; the order of attributes may differ).
TEST(Snapshots, ResumeKeepsEarlierSnapshots) {
  const Threads threads(1);  // ~1900 particles
  TempDir dir("snapshot_resume");
  auto s = small_scene(settings_for(ShapeFunction::linear));
  std::string index_after_two;
  {
    io::SnapshotWriter w(dir.path());
    for (int k = 0; k < 3; ++k) {
      if (k > 0)
        for (int j = 0; j < 10; ++j) s->step();
      w.write(*s);  // steps 0, 10, 20
      if (k == 1) index_after_two = read_file(dir.path() / "particles.xmf");
    }
  }
  // A snapshot is written aside and renamed once whole, so what a run killed while writing one
  // leaves is a .tmp file: never listed (a measure of a running run reads whole snapshots only),
  // and removed by the resume.
  const fs::path unfinished = dir.path() / (io::SnapshotWriter::file_name(3) + ".tmp");
  std::ofstream(unfinished) << "half a snapshot";
  EXPECT_EQ(io::SnapshotWriter::files(dir.path()).size(), 3u);
  io::SnapshotWriter resumed(dir.path());
  resumed.resume(10);
  EXPECT_EQ(resumed.count(), 2u);
  EXPECT_FALSE(fs::exists(unfinished));
  EXPECT_TRUE(fs::exists(dir.path() / io::SnapshotWriter::file_name(1)));
  EXPECT_FALSE(fs::exists(dir.path() / io::SnapshotWriter::file_name(2)));
  const std::string index = read_file(dir.path() / "particles.xmf");
  EXPECT_EQ(xmf_items(index), xmf_items(index_after_two));
  EXPECT_EQ(index.find("particles_000002"), std::string::npos);
  // Both index versions carry the same times, exactly.
  const std::regex time(R"re(<Time Value="([^"]+)"/>)re");
  auto times = [&](const std::string& x) {
    std::vector<std::string> t;
    for (auto it = std::sregex_iterator(x.begin(), x.end(), time); it != std::sregex_iterator();
         ++it)
      t.push_back((*it)[1]);
    return t;
  };
  EXPECT_EQ(times(index), times(index_after_two));
  resumed.write(*s);  // numbering continues at 2
  EXPECT_TRUE(fs::exists(dir.path() / io::SnapshotWriter::file_name(2)));

  // Snapshots 0 and 1 deleted by hand (to save space), then resumed at step 20: the kept
  // snapshot 2 keeps its number and the next one is 3, not 0.
  fs::remove(dir.path() / io::SnapshotWriter::file_name(0));
  fs::remove(dir.path() / io::SnapshotWriter::file_name(1));
  io::SnapshotWriter pruned(dir.path());
  pruned.resume(20);
  EXPECT_EQ(pruned.count(), 1u);
  pruned.write(*s);
  EXPECT_FALSE(fs::exists(dir.path() / io::SnapshotWriter::file_name(0)));
  EXPECT_TRUE(fs::exists(dir.path() / io::SnapshotWriter::file_name(2)));
  EXPECT_TRUE(fs::exists(dir.path() / io::SnapshotWriter::file_name(3)));
  const std::string pruned_index = read_file(dir.path() / "particles.xmf");
  EXPECT_EQ(pruned_index.find("particles_000000"), std::string::npos);
  EXPECT_NE(pruned_index.find("particles_000003"), std::string::npos);
}

// energy.csv of a resumed run keeps the rows up to the restart step.
TEST(EnergyLogFile, ResumeKeepsRowsUpToStep) {
  const Threads threads(1);  // ~1900 particles
  TempDir dir("energy_log");
  const fs::path file = dir.path() / "energy.csv";
  auto s = small_scene(settings_for(ShapeFunction::linear));
  {
    io::EnergyLog log(file);
    for (int k = 0; k < 6; ++k) {
      log.write(*s, s->energy());
      s->step();
    }
  }
  const std::string full = read_file(file);
  { io::EnergyLog log(file, 3); }
  const std::string kept = read_file(file);
  // Header + rows of steps 0..3, byte-identical to the start of the full log.
  EXPECT_EQ(std::count(kept.begin(), kept.end(), '\n'), 5);
  EXPECT_EQ(full.compare(0, kept.size(), kept), 0);
  EXPECT_EQ(kept.rfind(io::EnergyLog::header(), 0), 0u);
}

TEST(Hdf5File, ErrorsSayWhyTheSystemRefused) {
  // A full disk ended a 90-minute run with only "cannot write dataset": the message now carries
  // the operating system's reason, which HDF5's file driver records.
  const std::string path = "/nonexistent_hvi_directory/snapshot.h5";
  try {
    io::Hdf5File file(path, io::Hdf5File::Mode::create);
    FAIL() << "created " << path;
  } catch (const io::Hdf5Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("cannot create file in '" + path + "'"), std::string::npos) << message;
    EXPECT_NE(message.find(": No such file or directory"), std::string::npos) << message;
  }
  // A full disk: /dev/full takes the open and refuses every write with ENOSPC.
  try {
    io::Hdf5File file("/dev/full", io::Hdf5File::Mode::create);
    FAIL() << "wrote to /dev/full";
  } catch (const io::Hdf5Error& e) {
    EXPECT_NE(std::string(e.what()).find(": No space left on device"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace hvi::mpm::test
