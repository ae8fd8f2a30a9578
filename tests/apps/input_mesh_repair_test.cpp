// `delmesh mesh --input-mesh F --repair` and the sharp-feature counts of the input-mesh
// statistics, through the program.
#include <sstream>
#include <string>

#include <boost/test/unit_test.hpp>
#include <nlohmann/json.hpp>

#include "meshing/inputs/input_mesh.h"
#include "meshing/inputs/mesh_io.h"
#include "tests/apps/run_delmesh.h"

using namespace delmesh::test;

namespace {

// The box [x0, x1] × [y0, y1] × [z0, z1] as OFF faces with indices from `first`, outward.
void add_box(std::ostringstream& points, std::ostringstream& faces, std::size_t first, double x0, double x1,
             double y0, double y1, double z0, double z1) {
  for (int k = 0; k < 8; ++k)
    points << (k & 1 ? x1 : x0) << ' ' << (k & 2 ? y1 : y0) << ' ' << (k & 4 ? z1 : z0) << '\n';
  // Quads outward: -x, +x, -y, +y, -z, +z (vertex k has bit 0 = x, bit 1 = y, bit 2 = z).
  const int quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& q : quads)
    faces << "4 " << first + q[0] << ' ' << first + q[1] << ' ' << first + q[2] << ' ' << first + q[3] << '\n';
}

// The cube [0, 2]³ and the bar [1, 3] × [0.5, 1.5]² through its face x = 2, as one mesh.
std::string overlapping_boxes_off() {
  std::ostringstream points, faces;
  add_box(points, faces, 0, 0, 2, 0, 2, 0, 2);
  add_box(points, faces, 8, 1, 3, 0.5, 1.5, 0.5, 1.5);
  return "OFF\n16 12 0\n" + points.str() + faces.str();
}

}  // namespace

BOOST_AUTO_TEST_SUITE(input_mesh_repair_suite)

BOOST_AUTO_TEST_CASE(a_self_intersecting_mesh_is_refused_and_repaired_with_repair) {
  TempDir dir;
  write_text(dir.path / "boxes.off", overlapping_boxes_off());
  // Without --repair: the existing refusal.
  const RunResult refused = run_delmesh({"mesh", "--input-mesh", "boxes.off", "--quiet"}, dir.path);
  require_invalid_input(refused, "the surface intersects itself");
  BOOST_TEST(!std::filesystem::exists(dir.path / "boxes_remeshed.json"));
  // With it: autorefinement gives the union, which is remeshed (stopped early by --max-points).
  const RunResult r = run_delmesh({"mesh", "--input-mesh", "boxes.off", "--repair", "--max-points", "300"}, dir.path);
  BOOST_TEST(!r.signalled);
  BOOST_TEST((r.exit_code == 0 || r.exit_code == 3 || r.exit_code == 5), r.err);
  const auto lines = r.err_lines();
  BOOST_REQUIRE(!lines.empty());
  BOOST_TEST(lines.front().rfind("delmesh: --repair: boxes.off: ", 0) == 0u, lines.front());
  BOOST_TEST(lines.front().find("removed by autorefinement; 24 triangles and 16 vertices before") != std::string::npos,
             lines.front());
  const nlohmann::json stats = nlohmann::json::parse(read_text(dir.path / "boxes_remeshed.json"));
  const nlohmann::json& repair = stats["input_mesh"]["repair"];
  BOOST_TEST(repair["method"] == "autorefine");
  BOOST_TEST(repair["faces_before"] == 24);
  BOOST_TEST(repair["vertices_before"] == 16);
  BOOST_TEST(repair["intersecting_pairs"].get<std::size_t>() > 0u);
  BOOST_TEST(repair["faces_after"] == stats["input_mesh"]["triangles"]);
  BOOST_TEST(stats["input_mesh"]["components"] == 1);
  BOOST_TEST(stats["input_mesh"]["genus_per_component"] == nlohmann::json::array({0}));
  // The union's features: the cube's 8 corners and 12 edges, the bar's 4 end corners and 8
  // edges outside the cube, and the square where the bar leaves the cube (4 corners, 4 edges).
  const nlohmann::json& features = stats["input_mesh"]["features"];
  BOOST_TEST(features["corners"] == 16);
  BOOST_TEST(features["curves"] == 24);
  BOOST_TEST(features["folded_corners"] == 0);
  // --repair on a valid mesh changes nothing and says so; without --input-mesh it is refused.
  write_text(dir.path / "octahedron.off", octahedron_off);
  const RunResult same =
      run_delmesh({"mesh", "--input-mesh", "octahedron.off", "--repair", "--max-points", "50"}, dir.path);
  BOOST_TEST(same.err.find("delmesh: --repair: octahedron.off: no self-intersections, nothing to repair") == 0u,
             same.err);
  const nlohmann::json same_stats = nlohmann::json::parse(read_text(dir.path / "octahedron_remeshed.json"));
  BOOST_TEST(same_stats["input_mesh"]["repair"]["method"] == "none");
  require_invalid_input(run_delmesh({"mesh", "--surface", "sphere", "--repair"}, dir.path), "--repair needs --input-mesh");
  // An open mesh is refused with its own defect, --repair or not.
  write_text(dir.path / "open.off", "OFF\n4 3 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n");
  require_invalid_input(run_delmesh({"mesh", "--input-mesh", "open.off", "--repair"}, dir.path), "not closed");
}

BOOST_AUTO_TEST_CASE(input_mesh_statistics_count_the_sharp_features) {
  TempDir dir;
  write_text(dir.path / "octahedron.off", octahedron_off);
  const RunResult r = run_delmesh({"mesh", "--input-mesh", "octahedron.off", "--quiet", "--max-points", "50"}, dir.path);
  BOOST_TEST((r.exit_code == 3 || r.exit_code == 5 || r.exit_code == 0), r.err);
  const nlohmann::json stats = nlohmann::json::parse(read_text(dir.path / "octahedron_remeshed.json"));
  // The octahedron's faces meet at normals 70.5° apart: all 12 edges are sharp, the 6 vertices
  // (four sharp edges each) corners, each edge one curve.
  const nlohmann::json& features = stats["input_mesh"]["features"];
  BOOST_TEST(features["angle_deg"] == 60.0);
  BOOST_TEST(features["sharp_edges"] == 12);
  BOOST_TEST(features["corners"] == 6);
  BOOST_TEST(features["curves"] == 12);
  BOOST_TEST(features["closed_curves"] == 0);
  BOOST_TEST(features["folded_corners"] == 0);
}

BOOST_AUTO_TEST_SUITE_END()
