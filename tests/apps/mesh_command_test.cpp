#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>

#include <boost/test/unit_test.hpp>
#include <nlohmann/json.hpp>

#include "meshing/core/mesh_checker.h"
#include "meshing/inputs/mesh_io.h"
#include "symbolic/surface.h"
#include "tests/apps/run_delmesh.h"
#include "tests/meshing/check_fixture.h"
#include "tests/meshing/mesh_io_vtp_reader.h"

using namespace delmesh::test;

namespace {

//! The statistics without their measurements: every key whose name begins with "seconds", at any
//! depth, and the peak memory.
nlohmann::json without_timings(nlohmann::json j) {
  if (!j.is_object()) return j;
  nlohmann::json kept = nlohmann::json::object();
  for (auto it = j.begin(); it != j.end(); ++it)
    if (it.key().rfind("seconds", 0) != 0 && it.key() != "peak_memory_bytes")
      kept[it.key()] = without_timings(it.value());
  return kept;
}

//! Reads a mesh written by `delmesh mesh` as a triangle soup (a partial mesh need not be a
//! 2-manifold) and checks it.
delmesh::MeshReport read_and_check(const std::filesystem::path& path, delmesh::TriangleSoup& soup) {
  BOOST_REQUIRE_NO_THROW(soup = delmesh::read_triangle_soup(path.string()));
  return delmesh::check_mesh(soup.points, soup.triangles);
}

//! Meshes `surface` with `seed` and checks the file against the statistics and the catalog's
//! topology (`components`, `genus`, from `delmesh surfaces --json`).
void check_topology_for_seed(const std::string& surface, const std::string& phase, int seed, int components,
                             const std::vector<int>& genus) {
  TempDir dir;
  const RunResult r = run_delmesh({"mesh", "--surface", surface, "--phase", phase, "--seed", std::to_string(seed),
                                   "--quiet", "--out", "m.off", "--stats", "m.json"},
                                  dir.path);
  BOOST_TEST_CONTEXT(surface << " seed " << seed) {
    BOOST_TEST(r.exit_code == 0, r.err);
    const nlohmann::json stats = nlohmann::json::parse(read_text(dir / "m.json"));
    check_complete(stats);
    delmesh::TriangleSoup soup;
    const auto report = read_and_check(dir / "m.off", soup);
    BOOST_TEST(report.components == components);
    BOOST_TEST(report.has_topology(genus), report);
    BOOST_TEST(stats.at("genus_per_component").get<std::vector<int>>() == genus);
    check_oriented_output(stats, soup.points, soup.triangles);
  }
}

//! Files of the scratch directory other than the runner's own.
std::vector<std::string> files_in(const TempDir& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir.path)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(mesh_command)

BOOST_AUTO_TEST_CASE(lambda_out_of_range_is_invalid_input) {
  for (const char* lambda : {"0", "-0.1", "0.34", "0.3333333333333333", "1", "nan", "inf"}) {
    require_invalid_input(run_delmesh({"mesh", "--surface", "sphere", "--lambda", lambda}), "lambda");
  }
}

BOOST_AUTO_TEST_CASE(bad_options_are_invalid_input) {
  require_invalid_input(run_delmesh({"mesh", "--surface", "no_such_surface"}), "no_such_surface");
  require_invalid_input(run_delmesh({"mesh", "--expr", "x^2+y^2+z^2-1"}), "--box");
  require_invalid_input(run_delmesh({"mesh", "--expr", "x^2+y^^2", "--box", "-2,2,-2,2,-2,2"}));
  require_invalid_input(run_delmesh({"mesh", "--expr", "x^2+y^2+q-1", "--box", "-2,2,-2,2,-2,2"}), "q");
  require_invalid_input(run_delmesh({"mesh", "--expr", "x^0.5+y^2+z^2-1", "--box", "-2,2,-2,2,-2,2"}));
  require_invalid_input(run_delmesh({"mesh", "--expr", "x^2+y^2+z^2-1", "--box", "-2,2,-2,2,2,-2"}));
  require_invalid_input(run_delmesh({"mesh"}));
  require_invalid_input(run_delmesh({"mesh", "--surface", "sphere", "--out", "sphere.stp"}), ".stp");
  require_invalid_input(run_delmesh({"mesh", "--surface", "sphere", "--out", "no/such/dir/sphere.off"}), "--out");
  require_invalid_input(run_delmesh({"mesh", "--surface", "sphere", "--phase", "everything"}), "--phase");
  require_invalid_input(run_delmesh({"mesh", "--surface", "sphere", "--solver", "newton"}), "--solver");
  require_invalid_input(run_delmesh({"mesh", "--surface", "sphere", "--size-bound", "0"}), "--size-bound");
  require_invalid_input(run_delmesh({"mesh", "--surface", "sphere", "--max-distance", "0"}), "--max-distance");
  require_invalid_input(run_delmesh({"mesh", "--surface", "sphere", "--max-distance", "0.01", "--phase", "topology"}),
                        "--max-distance");
  require_invalid_input(run_delmesh({"mesh", "--surface", "sphere", "--time-limit", "-1"}), "--time-limit");
  require_invalid_input(run_delmesh({"mesh", "--surface", "sphere", "--max-points", "0"}), "--max-points");
  require_invalid_input(run_delmesh({"mesh", "--surface", "sphere", "--threads", "-1"}), "--threads");
}

// Every implicit run reports the gradient-flow certificate of its output; --max-distance makes
// the bound a requirement of a complete run.
BOOST_AUTO_TEST_CASE(the_distance_certificate_is_in_the_statistics) {
  TempDir dir;
  const RunResult plain = run_delmesh({"mesh", "--surface", "sphere", "--out", "a.off", "--stats", "a.json"}, dir.path);
  BOOST_TEST_REQUIRE(plain.exit_code == 0, plain.err);
  const nlohmann::json a = nlohmann::json::parse(read_text(dir / "a.json"));
  BOOST_TEST(a["distance"]["status"] == "certified");
  BOOST_TEST(a["distance"]["max_distance"].is_null());
  BOOST_TEST(plain.err.find("distance to the surface <=") != std::string::npos, plain.err);
  const RunResult bounded = run_delmesh(
      {"mesh", "--surface", "sphere", "--max-distance", "0.005", "--out", "b.off", "--stats", "b.json"}, dir.path);
  BOOST_TEST_REQUIRE(bounded.exit_code == 0, bounded.err);
  const nlohmann::json b = nlohmann::json::parse(read_text(dir / "b.json"));
  check_complete(b);
  BOOST_TEST(b["distance"]["status"] == "certified");
  BOOST_TEST(b["distance"]["hausdorff_upper_bound"].get<double>() <= 0.005);
  BOOST_TEST(a["distance"]["hausdorff_upper_bound"].get<double>() > 0.005);
  BOOST_TEST(b["vertices"].get<int>() > a["vertices"].get<int>());
}

// Progress written to a file (not a terminal): the header, then plain lines, the refinement's at
// most one per 5 s (apps/progress_line.h), each with points, rate and elapsed seconds and without
// the internal queue names; the distance certificate is announced.
BOOST_AUTO_TEST_CASE(progress_in_a_file_is_plain_and_sparse) {
  TempDir dir;
  const RunResult r = run_delmesh(
      {"mesh", "--surface", "torus", "--size-bound", "0.02", "--out", "t.off", "--stats", "t.json"}, dir.path);
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  const double seconds = nlohmann::json::parse(read_text(dir / "t.json"))["seconds"].get<double>();
  std::istringstream lines(r.err);
  std::size_t refinement_lines = 0;
  bool header = false, announced = false;
  for (std::string line; std::getline(lines, line);) {
    BOOST_TEST(line.find('\r') == std::string::npos);
    BOOST_TEST(line.find("queued") == std::string::npos, line);
    header = header || line.rfind("delmesh: meshing torus", 0) == 0;
    announced = announced || line.find("certifying the distance") != std::string::npos;
    if (line.find(" points/s, ") != std::string::npos) {
      ++refinement_lines;
      BOOST_TEST((line.rfind("delmesh: topology: ", 0) == 0 || line.rfind("delmesh: geometry: ", 0) == 0), line);
    }
  }
  BOOST_TEST(header);
  BOOST_TEST(announced);
  BOOST_TEST(refinement_lines >= 1u, r.err);
  BOOST_TEST(refinement_lines <= 1 + seconds / 5, r.err);
}

BOOST_AUTO_TEST_CASE(input_mesh_is_validated_then_remeshed) {
  TempDir dir;
  write_text(dir / "octahedron.off", octahedron_off);
  write_text(dir / "corrupt.off", "OFF\n6 8 0\n1 0 0\nbroken\n");
  require_invalid_input(run_delmesh({"mesh", "--input-mesh", "missing.off"}, dir.path));
  require_invalid_input(run_delmesh({"mesh", "--input-mesh", "corrupt.off"}, dir.path));
  require_invalid_input(run_delmesh({"mesh", "--input-mesh", "octahedron.off", "--surface", "sphere"}, dir.path));
  require_invalid_input(run_delmesh({"mesh", "--input-mesh", "octahedron.off", "--certify"}, dir.path), "--certify");
  require_invalid_input(run_delmesh({"mesh", "--input-mesh", "octahedron.off", "--max-distance", "0.1"}, dir.path),
                        "--max-distance");
  require_invalid_input(run_delmesh({"mesh", "--input-mesh", "octahedron.off", "--min-spacing", "-1"}, dir.path),
                        "--min-spacing");
  // The octahedron's cone vertices and creases cannot be made smooth: without the crease rule of
  // the sharp features (--no-features), Smooth refinement reaches the default floor (0.1 of the
  // median edge), the mesh is written and the run is uncertified.
  const RunResult r = run_delmesh({"mesh", "--input-mesh", "octahedron.off", "--no-features", "--quiet"}, dir.path);
  BOOST_TEST(r.exit_code == 5, r.err);
  const nlohmann::json stats = nlohmann::json::parse(read_text(dir / "octahedron_remeshed.json"));
  BOOST_TEST(stats["status"] == "uncertified");
  BOOST_TEST(stats["min_spacing"]["reached"] == true);
  BOOST_TEST(std::abs(stats["min_spacing"]["value"].get<double>() - 0.1 * std::sqrt(2.0)) < 1e-15);
  BOOST_TEST(stats["min_spacing"]["witnesses_below"].get<std::size_t>() > 0u);
  BOOST_TEST(stats["solver"]["backend"] == "mesh");
  BOOST_TEST(stats["input_mesh"]["genus_per_component"] == nlohmann::json::array({0}));
  BOOST_TEST(read_text(dir / "octahedron.off") == octahedron_off);  // the input is not replaced
  delmesh::TriangleSoup soup;
  const auto report = read_and_check(dir / "octahedron_remeshed.off", soup);
  BOOST_TEST(report.vertices == stats["vertices"].get<std::size_t>());
}

// A torus of 48 × 12 quadrilaterals (OFF faces of four vertices): the polygons are triangulated,
// and its creases are flat enough (15° and 30° between neighbouring quads) for DelMesh to finish
// above the floor with the torus's topology.
BOOST_AUTO_TEST_CASE(polygon_input_mesh_is_remeshed) {
  TempDir dir;
  const int n = 48, m = 12;
  std::ostringstream off;
  off.precision(17);
  off << "OFF\n" << n * m << ' ' << n * m << " 0\n";
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const double u = 2 * M_PI * i / n, v = 2 * M_PI * j / m, rho = 1 + 0.4 * std::cos(v);
      off << rho * std::cos(u) << ' ' << rho * std::sin(u) << ' ' << 0.4 * std::sin(v) << '\n';
    }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j)
      off << "4 " << i * m + j << ' ' << (i + 1) % n * m + j << ' ' << (i + 1) % n * m + (j + 1) % m << ' '
          << i * m + (j + 1) % m << '\n';
  write_text(dir / "quads.off", off.str());
  const RunResult r = run_delmesh({"mesh", "--input-mesh", "quads.off", "--quiet"}, dir.path);
  BOOST_TEST(r.exit_code == 0, r.err);
  const nlohmann::json stats = nlohmann::json::parse(read_text(dir / "quads_remeshed.json"));
  BOOST_TEST(stats["status"] == "complete");
  BOOST_TEST(stats["input_mesh"]["genus_per_component"] == nlohmann::json::array({1}));
  BOOST_TEST(stats["input_mesh"]["polygons_triangulated"] == n * m);
  BOOST_TEST(stats["input_mesh"]["triangles"] == 2 * n * m);
  BOOST_TEST(stats["genus_per_component"] == nlohmann::json::array({1}));
  delmesh::TriangleSoup soup;
  BOOST_TEST(read_and_check(dir / "quads_remeshed.off", soup).has_topology({1}));
}

// --out by extension: binary STL, and VTK XML PolyData whose point data "Normals" are the unit
// normals grad E/|grad E| at the vertices (compared here with GiNaC's evaluation of the exact
// gradient); a remeshed input mesh has no normals.
BOOST_AUTO_TEST_CASE(stl_and_vtp_outputs) {
  TempDir dir;
  const std::string expr = "x**2 + 2*y**2 + 3*z**2 - 1 + sin(x)*z/5";
  const RunResult r = run_delmesh({"mesh", "--expr", expr, "--box", "-2,2,-2,2,-2,2", "--quiet", "--out", "e.vtp",
                                   "--stats", "e.json"},
                                  dir.path);
  BOOST_TEST(r.exit_code == 0, r.err);
  const nlohmann::json stats = nlohmann::json::parse(read_text(dir / "e.json"));
  const VtpFile vtp = read_vtp((dir / "e.vtp").string());
  BOOST_TEST(vtp.points == stats["vertices"].get<std::size_t>());
  BOOST_TEST(vtp.polys == stats["triangles"].get<std::size_t>());
  const std::vector<double>& P = vtp.arrays.at("Points");
  const std::vector<double>& N = vtp.arrays.at("Normals");
  BOOST_REQUIRE(P.size() == 3 * vtp.points);
  BOOST_REQUIRE(N.size() == 3 * vtp.points);
  const delmesh::Surface surface = delmesh::Surface::parse(expr);
  double worst = 0;
  for (std::size_t i = 0; i < vtp.points; ++i) {
    const GiNaC::lst at{delmesh::coordinate_x() == GiNaC::numeric(P[3 * i]),
                        delmesh::coordinate_y() == GiNaC::numeric(P[3 * i + 1]),
                        delmesh::coordinate_z() == GiNaC::numeric(P[3 * i + 2])};
    std::array<double, 3> g{};
    for (int k = 0; k < 3; ++k) g[k] = GiNaC::ex_to<GiNaC::numeric>(surface.gradient()[k].subs(at).evalf()).to_double();
    const double length = std::hypot(g[0], g[1], g[2]);
    for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(N[3 * i + k] - g[k] / length));
  }
  BOOST_TEST(worst <= 1e-12);

  const RunResult stl = run_delmesh({"mesh", "--surface", "sphere", "--quiet", "--out", "s.STL", "--stats", "s.json"}, dir.path);
  BOOST_TEST(stl.exit_code == 0, stl.err);
  const nlohmann::json sphere = nlohmann::json::parse(read_text(dir / "s.json"));
  BOOST_TEST(std::filesystem::file_size(dir / "s.STL") == 84 + 50 * sphere["triangles"].get<std::size_t>());

  write_text(dir / "octahedron.off", octahedron_off);
  const RunResult remeshed =
      run_delmesh({"mesh", "--input-mesh", "octahedron.off", "--no-features", "--quiet", "--out", "o.vtp"}, dir.path);
  BOOST_TEST(remeshed.exit_code == 5, remeshed.err);
  const VtpFile o = read_vtp((dir / "o.vtp").string());
  BOOST_TEST(o.polys > 0u);
  BOOST_TEST(o.arrays.count("Normals") == 0u);
  BOOST_TEST(o.arrays.count("certified_distance") == 0u);
}

// The .vtp of a run whose gradient-flow certificate certified the mesh carries certified_distance:
// one finite bound per vertex, at least the vertex's exact distance to the torus (core radius 1,
// tube radius 0.4: |sqrt((sqrt(x^2+y^2) - 1)^2 + z^2) - 0.4|) and at most the certificate's
// Hausdorff bound.  A run stopped before the certificate, and a remeshed input mesh, have none.
BOOST_AUTO_TEST_CASE(vtp_carries_the_certified_distance_of_each_vertex) {
  TempDir dir;
  const RunResult r =
      run_delmesh({"mesh", "--surface", "torus", "--quiet", "--out", "t.vtp", "--stats", "t.json"}, dir.path);
  BOOST_TEST(r.exit_code == 0, r.err);
  const nlohmann::json stats = nlohmann::json::parse(read_text(dir / "t.json"));
  BOOST_REQUIRE(stats["distance"]["status"] == "certified");
  const double hausdorff = stats["distance"]["hausdorff_upper_bound"].get<double>();
  const VtpFile vtp = read_vtp((dir / "t.vtp").string());
  const std::vector<double>& P = vtp.arrays.at("Points");
  BOOST_REQUIRE(vtp.arrays.count("certified_distance") == 1u);
  const std::vector<double>& D = vtp.arrays.at("certified_distance");
  BOOST_REQUIRE(D.size() == vtp.points);
  BOOST_REQUIRE(P.size() == 3 * vtp.points);
  std::size_t below_exact = 0, above_hausdorff = 0, not_finite = 0;
  double least = std::numeric_limits<double>::infinity(), most = 0;
  for (std::size_t i = 0; i < vtp.points; ++i) {
    const double x = P[3 * i], y = P[3 * i + 1], z = P[3 * i + 2];
    const double exact = std::abs(std::hypot(std::hypot(x, y) - 1.0, z) - 0.4);
    if (!std::isfinite(D[i])) ++not_finite;
    if (!(D[i] >= exact)) ++below_exact;
    if (!(D[i] <= hausdorff)) ++above_hausdorff;
    least = std::min(least, D[i]);
    most = std::max(most, D[i]);
  }
  BOOST_TEST(not_finite == 0u);
  BOOST_TEST(below_exact == 0u);
  BOOST_TEST(above_hausdorff == 0u);
  BOOST_TEST(least > 0);
  BOOST_TEST(most <= hausdorff);

  // Stopped by --max-points: no certificate, no array (and the normals are still there).
  const RunResult stopped = run_delmesh(
      {"mesh", "--surface", "torus", "--quiet", "--max-points", "20", "--out", "s.vtp", "--stats", "s.json"}, dir.path);
  BOOST_TEST(stopped.exit_code == 3, stopped.err);
  const nlohmann::json stopped_stats = nlohmann::json::parse(read_text(dir / "s.json"));
  BOOST_TEST(stopped_stats["distance"]["status"] != "certified");
  const VtpFile s = read_vtp((dir / "s.vtp").string());
  BOOST_TEST(s.arrays.count("certified_distance") == 0u);
  BOOST_TEST(s.arrays.count("Normals") == 1u);

  // The torus as binary STL is read back as an indexed closed mesh by check and by --input-mesh;
  // the remeshed .vtp has no certified_distance.
  const RunResult stl = run_delmesh({"mesh", "--surface", "torus", "--quiet", "--out", "t.stl", "--stats", "u.json"}, dir.path);
  BOOST_TEST(stl.exit_code == 0, stl.err);
  const RunResult checked = run_delmesh({"check", "t.stl", "--json"}, dir.path);
  BOOST_TEST(checked.exit_code == 0, checked.err);
  const nlohmann::json report = nlohmann::json::parse(checked.out);
  BOOST_TEST(report["vertices"].get<std::size_t>() == vtp.points);
  BOOST_TEST(report["closed_manifold"].get<bool>());
  const RunResult remeshed =
      run_delmesh({"mesh", "--input-mesh", "t.stl", "--quiet", "--out", "r.vtp", "--stats", "r.json"}, dir.path);
  BOOST_TEST((remeshed.exit_code == 0 || remeshed.exit_code == 5), remeshed.err);
  const VtpFile remeshed_vtp = read_vtp((dir / "r.vtp").string());
  BOOST_TEST(remeshed_vtp.polys > 0u);
  BOOST_TEST(remeshed_vtp.arrays.count("certified_distance") == 0u);
}

BOOST_AUTO_TEST_CASE(a_failing_run_leaves_existing_outputs_untouched) {
  TempDir dir;
  write_text(dir / "keep.off", octahedron_off);
  write_text(dir / "keep.json", "{\"previous\": true}\n");
  const std::vector<std::string> outputs{"--out", "keep.off", "--stats", "keep.json", "--quiet"};
  auto with_outputs = [&](std::vector<std::string> args) {
    args.insert(args.end(), outputs.begin(), outputs.end());
    return args;
  };
  require_invalid_input(run_delmesh(with_outputs({"mesh", "--surface", "no_such_surface"}), dir.path));
  require_invalid_input(run_delmesh(with_outputs({"mesh", "--surface", "sphere", "--lambda", "0.5"}), dir.path));
  // A singular surface (a cone) is rejected by the mesher's input checks.
  require_invalid_input(
      run_delmesh(with_outputs({"mesh", "--expr", "x^2+y^2-z^2", "--box", "-1,1,-1,1,-1,1"}), dir.path));
  BOOST_TEST(read_text(dir / "keep.off") == octahedron_off);
  BOOST_TEST(read_text(dir / "keep.json") == "{\"previous\": true}\n");
  BOOST_TEST((files_in(dir) == std::vector<std::string>{"keep.json", "keep.off"}));  // no temporaries left
}

BOOST_AUTO_TEST_CASE(invalid_surfaces_are_rejected_with_one_error_line) {
  // Leaves its box; empty in its box; singular (the cone's apex).
  require_invalid_input(run_delmesh({"mesh", "--surface", "sphere", "--box", "-0.5,1.5,-1.5,1.5,-1.5,1.5"}));
  require_invalid_input(run_delmesh({"mesh", "--expr", "x^2+y^2+z^2-1", "--box", "2,3,2,3,2,3"}));
  require_invalid_input(run_delmesh({"mesh", "--expr", "x^2+y^2-z^2", "--box", "-1,1,-1,1,-1,1"}));
}

BOOST_AUTO_TEST_CASE(sphere_mesh_and_statistics_are_written) {
  TempDir dir;
  const RunResult r = run_delmesh({"mesh", "--surface", "sphere", "--quiet"}, dir.path);
  BOOST_TEST(r.exit_code == 0, r.err);
  BOOST_TEST(r.err.empty(), r.err);
  BOOST_REQUIRE(std::filesystem::exists(dir / "sphere.off"));
  BOOST_REQUIRE(std::filesystem::exists(dir / "sphere.json"));
  const nlohmann::json stats = nlohmann::json::parse(read_text(dir / "sphere.json"));
  for (const char* key : {"status", "lambda", "vertices", "triangles", "components", "euler_characteristic",
                          "genus_per_component", "closed_manifold", "orientable", "min_angle_deg",
                          "max_radius_edge_ratio", "max_roughness_rad", "bounds", "insertions", "solver",
                          "height_direction", "seconds"}) {
    BOOST_TEST(stats.contains(key), key);
  }
  check_complete(stats);
  // The process's peak resident memory: at least the program and its libraries (a few MiB).
  BOOST_TEST(stats.at("peak_memory_bytes").get<std::uint64_t>() > (std::uint64_t{1} << 20));
  delmesh::TriangleSoup soup;
  (void)read_and_check(dir / "sphere.off", soup);
  check_oriented_output(stats, soup.points, soup.triangles);
  // The independent checker, from the file alone.
  const RunResult check = run_delmesh({"check", "sphere.off", "--lambda", "0.06", "--json"}, dir.path);
  BOOST_TEST(check.exit_code == 0, check.out);
  const nlohmann::json report = nlohmann::json::parse(check.out);
  BOOST_TEST((report.at("genus_per_component").get<std::vector<int>>() == std::vector<int>{0}));
  BOOST_TEST(report.at("manifold").get<bool>());
  BOOST_TEST(report.at("orientable").get<bool>());
  BOOST_TEST(report.at("vertices").get<std::size_t>() == stats.at("vertices").get<std::size_t>());
}

BOOST_AUTO_TEST_CASE(progress_and_the_uncovered_lambda_warning_go_to_stderr) {
  TempDir dir;
  const RunResult r = run_delmesh(
      {"mesh", "--surface", "sphere", "--phase", "topology", "--lambda", "0.1", "--out", "s.ply", "--stats", "-"},
      dir.path);
  BOOST_TEST(r.exit_code == 0, r.err);
  BOOST_TEST(r.err.find("warning:") != std::string::npos);
  BOOST_TEST(r.err.find("Theorem 6.1") != std::string::npos);
  BOOST_TEST(r.err.find("delmesh:") != std::string::npos);  // progress
  BOOST_TEST(r.err.find("error:") == std::string::npos);
  const nlohmann::json stats = nlohmann::json::parse(r.out);  // --stats - prints to stdout
  BOOST_TEST(std::abs(stats.at("lambda").get<double>() - 0.1) < 1e-15);
  BOOST_TEST(std::filesystem::exists(dir / "s.ply"));
  BOOST_TEST(run_delmesh({"check", "s.ply"}, dir.path).exit_code == 0);
}

// The limit stops SampleTopology (8 points: the torus's 4 seeds and 4 more) or the geometric
// refinement (100 points; SampleTopology needs about 30).  Samples are inserted one at a time
// after the seeds, which go in together, so the run stops with exactly max(limit, seeds) samples.
// The partial mesh is readable, has the vertices and triangles the statistics report, and its
// vertices are samples.
BOOST_AUTO_TEST_CASE(a_point_limit_stops_with_exit_3_and_writes_the_partial_outputs) {
  for (std::size_t limit : {8, 100}) {
    TempDir dir;
    const RunResult r = run_delmesh(
        {"mesh", "--surface", "torus", "--max-points", std::to_string(limit), "--quiet", "--out", "t.obj"}, dir.path);
    BOOST_TEST(!r.signalled);
    BOOST_TEST(r.exit_code == 3, r.err);
    BOOST_REQUIRE(std::filesystem::exists(dir / "t.obj"));
    const nlohmann::json stats = nlohmann::json::parse(read_text(dir / "torus.json"));
    BOOST_TEST(stats.at("status").get<std::string>() == "point_limit");
    const auto points = stats.at("points").get<std::size_t>();
    const auto seeds = stats.at("insertions").at("seeds").get<std::size_t>();
    BOOST_TEST(points == std::max(limit, seeds), "limit " << limit);
    delmesh::TriangleSoup soup;
    const auto report = read_and_check(dir / "t.obj", soup);
    BOOST_TEST(report.vertices == stats.at("vertices").get<std::size_t>(), "limit " << limit);
    BOOST_TEST(report.triangles == stats.at("triangles").get<std::size_t>(), "limit " << limit);
    BOOST_TEST(report.vertices <= points, "limit " << limit);
    BOOST_TEST(report.unreferenced_vertices == 0u);
  }
}

BOOST_AUTO_TEST_CASE(a_time_limit_stops_with_exit_3_and_replaces_outputs_atomically) {
  TempDir dir;
  write_text(dir / "g.off", octahedron_off);
  // 2 s: long enough for the partial mesh to have triangles under the sanitizers on a loaded
  // machine (the oracle build alone can take 0.5 s there), far from genus2's time at 0.004
  // (more than the default 200 000 points, reached after about 13 s in a Release build).
  const RunResult r = run_delmesh({"mesh", "--surface", "genus2", "--size-bound", "0.004", "--time-limit", "2",
                                   "--quiet", "--out", "g.off", "--stats", "g.json"},
                                  dir.path);
  BOOST_TEST(!r.signalled);
  BOOST_TEST(r.exit_code == 3, r.err);
  BOOST_TEST(r.err.find("warning:") != std::string::npos);
  const nlohmann::json stats = nlohmann::json::parse(read_text(dir / "g.json"));
  BOOST_TEST(stats.at("status").get<std::string>() == "time_limit");
  BOOST_TEST(read_text(dir / "g.off") != octahedron_off);  // replaced by the partial mesh
  BOOST_TEST((files_in(dir) == std::vector<std::string>{"g.json", "g.off"}));
  BOOST_TEST(run_delmesh({"check", "g.off"}, dir.path).exit_code == 0);
  // It stopped at the first check after the deadline (a check takes milliseconds; the bound
  // leaves room for a loaded machine), far below the default point limit.
  const double seconds = stats.at("seconds").get<double>();
  BOOST_TEST(seconds >= 2);
  BOOST_TEST(seconds < 12);
  const auto points = stats.at("points").get<std::size_t>();
  BOOST_TEST(points < 200000u);
  delmesh::TriangleSoup soup;
  const auto report = read_and_check(dir / "g.off", soup);
  BOOST_TEST(report.vertices == stats.at("vertices").get<std::size_t>());
  BOOST_TEST(report.triangles == stats.at("triangles").get<std::size_t>());
  BOOST_TEST(report.vertices <= points);
  BOOST_TEST(report.vertices > 0u);
}

// Two processes with the same seed write the same bytes: the mesh file, and the statistics but
// for the timings.  Another seed gives another mesh (so the comparison sees a difference).
BOOST_AUTO_TEST_CASE(same_seed_same_files_across_processes) {
  const std::vector<std::string> args{"mesh", "--surface", "torus", "--seed", "5", "--quiet",
                                      "--out", "m.off", "--stats", "m.json"};
  TempDir first, second, other;
  const RunResult a = run_delmesh(args, first.path), b = run_delmesh(args, second.path);
  BOOST_TEST(a.exit_code == 0, a.err);
  BOOST_TEST(b.exit_code == 0, b.err);
  const std::string mesh = read_text(first / "m.off");
  BOOST_TEST(!mesh.empty());
  BOOST_TEST((mesh == read_text(second / "m.off")));
  const nlohmann::json stats_a = nlohmann::json::parse(read_text(first / "m.json")),
                       stats_b = nlohmann::json::parse(read_text(second / "m.json"));
  check_complete(stats_a);
  BOOST_TEST(without_timings(stats_a) == without_timings(stats_b),
             "\n" << without_timings(stats_a).dump(1) << "\n" << without_timings(stats_b).dump(1));
  BOOST_TEST(without_timings(stats_a).contains("solver"));
  delmesh::TriangleSoup soup;
  (void)read_and_check(first / "m.off", soup);
  check_oriented_output(stats_a, soup.points, soup.triangles);

  auto other_args = args;
  other_args[4] = "6";
  BOOST_TEST(run_delmesh(other_args, other.path).exit_code == 0);
  BOOST_TEST((read_text(other / "m.off") != mesh));
}

// Three seeds (three generic height directions, three sample sets) give the catalog's topology:
// the components and the genus of each, from the file alone, with every component outward.
// SampleTopology is what guarantees the topology; the fast tier runs it alone on surfaces of
// genus 0 and 1 and with two components.
BOOST_AUTO_TEST_CASE(three_seeds_same_topology_at_phase_topology) {
  const nlohmann::json catalog = nlohmann::json::parse(run_delmesh({"surfaces", "--json"}).out);
  int checked = 0;
  for (const auto& entry : catalog) {
    const auto name = entry.at("name").get<std::string>();
    if (name != "sphere" && name != "torus" && name != "two_blobs") continue;
    ++checked;
    for (int seed : {1, 2, 3})
      check_topology_for_seed(name, "topology", seed, entry.at("components").get<int>(),
                              entry.at("genus_per_component").get<std::vector<int>>());
  }
  BOOST_TEST(checked == 3);
}

// The same for every catalog surface, meshed completely at the default λ = 0.06.
BOOST_AUTO_TEST_CASE(three_seeds_same_topology_on_the_catalog, *boost::unit_test::label("slow")) {
  const nlohmann::json catalog = nlohmann::json::parse(run_delmesh({"surfaces", "--json"}).out);
  BOOST_TEST(catalog.size() >= 10u);
  for (const auto& entry : catalog)
    for (int seed : {1, 2, 3})
      check_topology_for_seed(entry.at("name").get<std::string>(), "all", seed, entry.at("components").get<int>(),
                              entry.at("genus_per_component").get<std::vector<int>>());
}

// --certify: the certificate of the run's own mesh in the statistics.
BOOST_AUTO_TEST_CASE(certify_puts_the_certificate_in_the_statistics) {
  TempDir dir;
  const RunResult r = run_delmesh(
      {"mesh", "--surface", "torus", "--out", "torus.off", "--stats", "torus.json", "--certify", "--quiet"}, dir.path);
  BOOST_TEST(r.exit_code == 0, r.err);
  const nlohmann::json stats = nlohmann::json::parse(read_text(dir / "torus.json"));
  const nlohmann::json& c = stats.at("certificate");
  BOOST_TEST(c.at("status").get<std::string>() == "certified", c.dump());
  BOOST_TEST(c.at("restricted_matches_mesh").get<bool>());
  BOOST_TEST(c.at("faces_checked").get<std::size_t>() > stats.at("vertices").get<std::size_t>());
  // A run stopped by a limit gets no certificate.
  const RunResult limited = run_delmesh(
      {"mesh", "--surface", "torus", "--max-points", "8", "--out", "t.off", "--stats", "t.json", "--certify", "--quiet"},
      dir.path);
  BOOST_TEST(limited.exit_code == 3, limited.err);
  BOOST_TEST(nlohmann::json::parse(read_text(dir / "t.json")).at("certificate").is_null());
}

BOOST_AUTO_TEST_SUITE_END()
