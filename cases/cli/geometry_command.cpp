#include "cases/cli/geometry_command.hpp"

#include <chrono>
#include <fstream>

#include <fmt/format.h>

#include "cases/run/bodies.hpp"
#include "cases/run/run.hpp"
#include "geometry/surface.hpp"
#include "mpm/io/hdf5_file.hpp"

namespace hvi::driver {

namespace fs = std::filesystem;

namespace {

struct BuiltBody {
  geometry::TriangleMesh surface;
  geometry::SurfaceCheck check;
  geometry::SampleReport report;
  double mass = 0.0;
};

// All points of all bodies, in body order.
struct Points {
  std::vector<double> position, volume, mass, half_width;
  std::vector<std::int64_t> body, material;
};

std::string file_name(const std::string& body) {
  std::string name = body;
  for (char& c : name)
    if (c == '/' || c == '\\' || c == ' ') c = '_';
  return name;
}

void write_points(const fs::path& dir, const Points& p) {
  const std::size_t n = p.volume.size();
  {
    mpm::io::Hdf5File h5((dir / "points.h5").string(), mpm::io::Hdf5File::Mode::create);
    h5.write("position", p.position.data(), n, 3);
    h5.write("volume", p.volume.data(), n, 1);
    h5.write("mass", p.mass.data(), n, 1);
    h5.write("half_width", p.half_width.data(), n, 3);
    h5.write("body", p.body.data(), n, 1);
    h5.write("material", p.material.data(), n, 1);
  }
  std::string xml = fmt::format(
      "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n  <Grid Name=\"points\" "
      "GridType=\"Uniform\">\n"
      "   <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"{0}\" NodesPerElement=\"1\"/>\n"
      "   <Geometry GeometryType=\"XYZ\">\n    <DataItem Dimensions=\"{0} 3\" NumberType=\"Float\" "
      "Precision=\"8\" "
      "Format=\"HDF\">points.h5:/position</DataItem>\n   </Geometry>\n",
      n);
  const struct {
    const char* name;
    int components;
    bool integer;
  } fields[] = {{"volume", 1, false},
                {"mass", 1, false},
                {"half_width", 3, false},
                {"body", 1, true},
                {"material", 1, true}};
  for (const auto& f : fields)
    xml += fmt::format(
        "   <Attribute Name=\"{0}\" AttributeType=\"{1}\" Center=\"Node\">\n    <DataItem "
        "Dimensions=\"{2}\" "
        "NumberType=\"{3}\" Precision=\"8\" Format=\"HDF\">points.h5:/{0}</DataItem>\n   "
        "</Attribute>\n",
        f.name, f.components == 1 ? "Scalar" : "Vector",
        f.components == 1 ? fmt::format("{}", n) : fmt::format("{} 3", n),
        f.integer ? "Int" : "Float");
  xml += "  </Grid>\n </Domain>\n</Xdmf>\n";
  std::ofstream(dir / "points.xmf") << xml;
}

}  // namespace

int geometry_command(const scene::Scene& scene, const fs::path& out) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<BuiltBody> built(scene.bodies.size());
  Points points;
  // Build and sample everything before writing anything.
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const scene::BodySettings& body = scene.bodies[b];
    const auto solid = make_body_solid(scene, b);
    BuiltBody& bb = built[b];
    bb.surface = solid->surface();
    bb.check = geometry::check_surface(bb.surface);
    if (!bb.check.ok())
      throw std::runtime_error(
          fmt::format("body '{}': its surface is not a valid solid boundary: {}", body.name,
                      bb.check.problem()));
    const geometry::PointSet set = sample_body(scene, b, *solid, &bb.report);
    const double density = scene.materials[body.material].models.density;
    points.position.insert(points.position.end(), set.position.begin(), set.position.end());
    points.volume.insert(points.volume.end(), set.volume.begin(), set.volume.end());
    points.half_width.insert(points.half_width.end(), set.half_width.begin(), set.half_width.end());
    for (const double v : set.volume) {
      points.mass.push_back(density * v);
      bb.mass += density * v;
    }
    points.body.insert(points.body.end(), set.size(), static_cast<std::int64_t>(b));
    points.material.insert(points.material.end(), set.size(),
                           static_cast<std::int64_t>(body.material));
  }
  const double build_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  fs::create_directories(out);
  std::ofstream csv(out / "bodies.csv");
  csv << "body,material,points,refined_points,sampling,exact_volume_m3,sampled_volume_m3,sampled_"
         "over_exact_minus_1,"
         "mass_kg,surface_triangles\n";
  fmt::print("{:<16} {:>10} {:>10}  {:>13} {:>13} {:>10}  {:>12}  {}\n", "body", "points",
             "refined", "exact m^3", "sampled m^3", "s/e - 1", "mass kg", "surface");
  std::size_t total = 0;
  double total_mass = 0.0;
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const scene::BodySettings& body = scene.bodies[b];
    const BuiltBody& bb = built[b];
    const auto& r = bb.report;
    const double error = r.lattice_volume / r.exact_volume - 1;
    const char* sampling = r.point_type ? "point-type walls" : "lattice";
    geometry::write_stl(bb.surface, (out / (file_name(body.name) + ".stl")).string());
    fmt::print(
        "{:<16} {:>10} {:>10}  {:>13.6e} {:>13.6e} {:>+10.2e}  {:>12.6e}  closed, outward, no "
        "self-intersection "
        "({} triangles, {} m^3); {}\n",
        body.name, r.points, r.refined_points, r.exact_volume, r.lattice_volume, error, bb.mass,
        bb.check.triangles, fmt::format("{:.6e}", bb.check.volume), sampling);
    csv << fmt::format("{},{},{},{},{},{:.17g},{:.17g},{:.6e},{:.17g},{}\n", body.name,
                       scene.materials[body.material].name, r.points, r.refined_points, sampling,
                       r.exact_volume, r.lattice_volume, error, bb.mass, bb.check.triangles);
    total += r.points;
    total_mass += bb.mass;
  }
  write_points(out, points);
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  fmt::print(
      "{} points, {:.6g} kg; built and sampled in {:.2f} s, written in {:.2f} s; peak memory "
      "{:.0f} MB\n",
      total, total_mass, build_seconds, wall - build_seconds, peak_memory_bytes() / 1e6);
  fmt::print("output: {}  (<body>.stl, points.xmf for ParaView, bodies.csv)\n", out.string());
  return ExitCode::success;
}

}  // namespace hvi::driver
