#include <cmath>
#include <sstream>
#include <string>

#include <boost/test/unit_test.hpp>
#include <nlohmann/json.hpp>

#include "tests/apps/run_delmesh.h"

using namespace delmesh::test;

namespace {

// A latitude-longitude sphere (rings × sectors quadrilaterals, two triangles each, fans at the
// poles) with its vertices on the unit sphere: its thin polar triangles make it far from the
// restricted Delaunay triangulation of its vertices, as meshes of other programs often are.
std::string uv_sphere_off(int rings, int sectors) {
  const double pi = std::acos(-1.0);
  std::ostringstream v, f;
  v.precision(17);
  v << 0 << " " << 0 << " " << 1 << "\n";
  for (int i = 1; i < rings; ++i)
    for (int j = 0; j < sectors; ++j) {
      const double theta = pi * i / rings, phi = 2 * pi * j / sectors;
      v << std::sin(theta) * std::cos(phi) << " " << std::sin(theta) * std::sin(phi) << " " << std::cos(theta) << "\n";
    }
  v << 0 << " " << 0 << " " << -1 << "\n";
  const int south = 1 + (rings - 1) * sectors;
  const auto at = [&](int i, int j) { return 1 + (i - 1) * sectors + j % sectors; };
  int faces = 0;
  for (int j = 0; j < sectors; ++j, ++faces) f << "3 0 " << at(1, j) << " " << at(1, j + 1) << "\n";
  for (int i = 1; i + 1 < rings; ++i)
    for (int j = 0; j < sectors; ++j, faces += 2)
      f << "3 " << at(i, j) << " " << at(i + 1, j) << " " << at(i, j + 1) << "\n3 " << at(i, j + 1) << " "
        << at(i + 1, j) << " " << at(i + 1, j + 1) << "\n";
  for (int j = 0; j < sectors; ++j, ++faces) f << "3 " << south << " " << at(rings - 1, j + 1) << " " << at(rings - 1, j) << "\n";
  return "OFF\n" + std::to_string(south + 1) + " " + std::to_string(faces) + " 0\n" + v.str() + f.str();
}

}  // namespace

BOOST_AUTO_TEST_SUITE(check_command)

BOOST_AUTO_TEST_CASE(octahedron_has_genus_zero) {
  TempDir dir;
  write_text(dir / "octahedron.off", octahedron_off);
  const RunResult r = run_delmesh({"check", "octahedron.off", "--json"}, dir.path);
  BOOST_TEST(r.exit_code == 0, r.err);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  BOOST_TEST(j.at("vertices").get<int>() == 6);
  BOOST_TEST(j.at("triangles").get<int>() == 8);
  BOOST_TEST(j.at("components").get<int>() == 1);
  BOOST_TEST(j.at("euler_characteristic").get<int>() == 2);
  BOOST_TEST((j.at("genus_per_component").get<std::vector<int>>() == std::vector<int>{0}));
  BOOST_TEST(j.at("closed").get<bool>());
  BOOST_TEST(j.at("manifold").get<bool>());
  BOOST_TEST(j.at("orientable").get<bool>());
  BOOST_TEST(std::abs(j.at("min_angle_deg").get<double>() - 60.0) < 1e-9);

  const RunResult text = run_delmesh({"check", "octahedron.off"}, dir.path);
  BOOST_TEST(text.exit_code == 0);
  BOOST_TEST(text.out.find("genus per component:   0") != std::string::npos, text.out);
}

// Polygons are triangulated as `mesh --input-mesh` does: a cube of six quadrilaterals (OFF) and an
// open grid of quadrilaterals (OBJ, reported, not refused).
BOOST_AUTO_TEST_CASE(polygon_meshes_are_triangulated) {
  TempDir dir;
  write_text(dir / "cube.off",
             "OFF\n8 6 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
             "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 2 3 7 6\n4 1 2 6 5\n4 0 4 7 3\n");
  const RunResult r = run_delmesh({"check", "cube.off", "--json"}, dir.path);
  BOOST_TEST(r.exit_code == 0, r.err);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  BOOST_TEST(j.at("vertices").get<int>() == 8);
  BOOST_TEST(j.at("triangles").get<int>() == 12);
  BOOST_TEST(j.at("edges").get<int>() == 18);
  BOOST_TEST((j.at("genus_per_component").get<std::vector<int>>() == std::vector<int>{0}));
  BOOST_TEST(j.at("closed").get<bool>());
  BOOST_TEST(j.at("manifold").get<bool>());
  BOOST_TEST(j.at("oriented").get<bool>());
  BOOST_TEST(std::abs(j.at("min_angle_deg").get<double>() - 45.0) < 1e-9);

  write_text(dir / "grid.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\nf 1 2 5 4\nf 2 3 6 5\n");
  const RunResult grid = run_delmesh({"check", "grid.obj", "--json"}, dir.path);
  BOOST_TEST(grid.exit_code == 0, grid.err);
  const nlohmann::json g = nlohmann::json::parse(grid.out);
  BOOST_TEST(g.at("triangles").get<int>() == 4);
  BOOST_TEST(!g.at("closed").get<bool>());
  BOOST_TEST(g.at("boundary_loops").get<int>() == 1);

  write_text(dir / "flat.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n2 0 0\n3 0 0\n4 0 1 2 3\n");
  require_invalid_input(run_delmesh({"check", "flat.off"}, dir.path),
                        "mesh file 'flat.off': face 0 (4 vertices) could not be triangulated (a degenerate polygon)");
}

BOOST_AUTO_TEST_CASE(theorem_bounds_pass_and_fail_per_bound) {
  TempDir dir;
  write_text(dir / "octahedron.off", octahedron_off);
  // Angles and radius-edge ratio satisfy the λ = 0.06 bounds, the roughness (≈ 1.23 rad > 2β) does not.
  const RunResult r = run_delmesh({"check", "octahedron.off", "--lambda", "0.06", "--json"}, dir.path);
  BOOST_TEST(r.exit_code == 1, r.err);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  BOOST_TEST(j.at("pass").at("min_angle_deg").get<bool>());
  BOOST_TEST(j.at("pass").at("max_radius_edge_ratio").get<bool>());
  BOOST_TEST(!j.at("pass").at("max_roughness_rad").get<bool>());
  BOOST_TEST(!j.at("pass").at("all").get<bool>());
  BOOST_TEST(std::abs(j.at("bounds").at("max_radius_edge_ratio").get<double>() - 1.06) < 1e-12);
  const RunResult text = run_delmesh({"check", "octahedron.off", "--lambda", "0.06"}, dir.path);
  BOOST_TEST(text.exit_code == 1);
  BOOST_TEST(text.out.find("FAIL") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(bad_files_and_lambda_are_invalid_input) {
  TempDir dir;
  write_text(dir / "octahedron.off", octahedron_off);
  write_text(dir / "corrupt.off", "OFF\n6 8 0\n1 0 0\n-1 0\nnot a number\n");
  write_text(dir / "indices.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
  require_invalid_input(run_delmesh({"check", "corrupt.off"}, dir.path));
  require_invalid_input(run_delmesh({"check", "indices.off"}, dir.path));
  require_invalid_input(run_delmesh({"check", "missing.off"}, dir.path));
  require_invalid_input(run_delmesh({"check", "octahedron.off", "--lambda", "0"}, dir.path), "--lambda");
  require_invalid_input(run_delmesh({"check", "octahedron.off", "--lambda", "0.5"}, dir.path), "--lambda");
}

// Open, non-manifold and non-orientable meshes are reported, not refused: counts of boundary edges
// and loops and of non-manifold edges and vertices; the genus only where it is defined (null in
// JSON, "-" in the text).  A single triangle used to be refused or given genus -1.
BOOST_AUTO_TEST_CASE(open_non_manifold_and_non_orientable_meshes_are_reported) {
  TempDir dir;
  write_text(dir / "triangle.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  // A Möbius strip: a band of six triangles closed with a half twist.
  write_text(dir / "mobius.off",
             "OFF\n6 6 0\n0 0 0\n1 0 0\n2 0 0\n0 1 0\n1 1 0\n2 1 0\n"
             "3 0 1 4\n3 0 4 3\n3 1 2 5\n3 1 5 4\n3 2 3 0\n3 2 0 5\n");
  // Three triangles on one edge, and a fourth touching them at one vertex only.
  write_text(dir / "fin.off",
             "OFF\n7 4 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n2 2 0\n3 3 0\n3 0 1 2\n3 1 0 3\n3 0 1 4\n3 1 5 6\n");
  // A square annulus: two boundary loops.
  write_text(dir / "annulus.off",
             "OFF\n8 8 0\n-2 -2 0\n2 -2 0\n2 2 0\n-2 2 0\n-1 -1 0\n1 -1 0\n1 1 0\n-1 1 0\n"
             "3 0 1 4\n3 1 5 4\n3 1 2 5\n3 2 6 5\n3 2 3 6\n3 3 7 6\n3 3 0 7\n3 0 4 7\n");
  // A tetrahedron with one face turned over: closed and orientable, but not oriented.
  write_text(dir / "flipped.off",
             "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 2 1 3\n");
  write_text(dir / "octahedron.off", octahedron_off);

  struct Expected {
    const char* file;
    std::size_t boundary_edges, boundary_loops, nonmanifold_edges, nonmanifold_vertices;
    bool closed, orientable;
    int genus;  // -1: undefined (null)
  };
  const Expected cases[] = {
      {"triangle.off", 3, 1, 0, 0, false, true, -1},
      {"mobius.off", 6, 1, 0, 0, false, false, -1},
      {"fin.off", 9, 1, 1, 2, false, false, -1},
      {"annulus.off", 8, 2, 0, 0, false, true, -1},
      {"octahedron.off", 0, 0, 0, 0, true, true, 0},
  };
  for (const Expected& e : cases) {
    BOOST_TEST_CONTEXT(e.file) {
      const RunResult r = run_delmesh({"check", e.file, "--json"}, dir.path);
      BOOST_TEST(r.exit_code == 0, r.err);
      const nlohmann::json j = nlohmann::json::parse(r.out);
      BOOST_TEST(j.at("boundary_edges").get<std::size_t>() == e.boundary_edges);
      BOOST_TEST(j.at("boundary_loops").get<std::size_t>() == e.boundary_loops);
      BOOST_TEST(j.at("nonmanifold_edges").get<std::size_t>() == e.nonmanifold_edges);
      BOOST_TEST(j.at("nonmanifold_vertices").get<std::size_t>() == e.nonmanifold_vertices);
      BOOST_TEST(j.at("closed").get<bool>() == e.closed);
      BOOST_TEST(j.at("orientable").get<bool>() == e.orientable);
      const nlohmann::json& genus = j.at("genus_per_component").at(0);
      if (e.genus < 0) {
        BOOST_TEST(genus.is_null(), genus.dump());
      } else {
        BOOST_TEST(genus.get<int>() == e.genus);
      }
      BOOST_TEST(r.out.find("-1") == std::string::npos, r.out);
    }
  }
  const RunResult text = run_delmesh({"check", "triangle.off"}, dir.path);
  BOOST_TEST(text.exit_code == 0, text.err);
  BOOST_TEST(text.out.find("genus per component:   -") != std::string::npos, text.out);
  BOOST_TEST(text.out.find("closed:                no (3 boundary edges in 1 boundary loop)") != std::string::npos, text.out);
  const RunResult fin = run_delmesh({"check", "fin.off"}, dir.path);
  BOOST_TEST(fin.out.find("(1 non-manifold edge, 2 non-manifold vertices)") != std::string::npos, fin.out);
  const RunResult flipped = run_delmesh({"check", "flipped.off", "--json"}, dir.path);
  BOOST_TEST(flipped.exit_code == 0, flipped.err);
  const nlohmann::json f = nlohmann::json::parse(flipped.out);
  BOOST_TEST(f.at("closed").get<bool>());
  BOOST_TEST(f.at("orientable").get<bool>());
  BOOST_TEST(!f.at("oriented").get<bool>());
  BOOST_TEST(f.at("genus_per_component").at(0).get<int>() == 0);
}

// The partial mesh of a run stopped at 9 points (a closed component and an open one) is
// checkable: the open component has no genus.
BOOST_AUTO_TEST_CASE(partial_mesh_of_a_point_limited_run_is_checkable) {
  TempDir dir;
  const RunResult m = run_delmesh(
      {"mesh", "--surface", "torus", "--max-points", "9", "--out", "t.off", "--stats", "t.json", "--quiet"}, dir.path);
  BOOST_TEST(m.exit_code == 3, m.err);
  const RunResult r = run_delmesh({"check", "t.off", "--json"}, dir.path);
  BOOST_TEST(r.exit_code == 0, r.err);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  const nlohmann::json stats = nlohmann::json::parse(read_text(dir / "t.json"));
  BOOST_TEST(j.at("vertices") == stats.at("vertices"));
  BOOST_TEST(j.at("triangles") == stats.at("triangles"));
  BOOST_TEST(!j.at("closed").get<bool>());
  BOOST_TEST(j.at("boundary_loops").get<std::size_t>() >= 1u);
  std::size_t undefined = 0;
  for (const auto& g : j.at("genus_per_component")) undefined += g.is_null() ? 1 : 0;
  BOOST_TEST(undefined >= 1u);
}

// The certificate of delmesh's own output: certified, and the mesh is Tri S|Σ of its vertices.
BOOST_AUTO_TEST_CASE(certify_delmesh_output) {
  TempDir dir;
  const RunResult m = run_delmesh(
      {"mesh", "--surface", "sphere", "--out", "sphere.off", "--stats", "sphere.json", "--quiet"}, dir.path);
  BOOST_TEST(m.exit_code == 0, m.err);
  const RunResult r = run_delmesh({"check", "sphere.off", "--surface", "sphere", "--certify", "--json"}, dir.path);
  BOOST_TEST(r.exit_code == 0, r.err);
  const nlohmann::json c = nlohmann::json::parse(r.out).at("certificate");
  BOOST_TEST(c.at("status").get<std::string>() == "certified", c.dump());
  BOOST_TEST(c.at("restricted_matches_mesh").get<bool>());
  BOOST_TEST(c.at("faces_checked").get<std::size_t>() > 0u);
  BOOST_TEST(c.at("witnesses").at("count").get<int>() == 0);
  BOOST_TEST(c.at("seconds").get<double>() > 0);
  // The same with the expression and box, and as text.
  const RunResult text = run_delmesh(
      {"check", "sphere.off", "--expr", "x^2+y^2+z^2-1", "--box", "-1.5,1.5,-1.5,1.5,-1.5,1.5", "--certify"}, dir.path);
  BOOST_TEST(text.exit_code == 0, text.err);
  BOOST_TEST(text.out.find("certificate:           certified") != std::string::npos, text.out);
  BOOST_TEST(text.out.find("Tri S|Sigma = mesh:  yes") != std::string::npos, text.out);
}

// A tetrahedron whose vertices lie on the thin torus misses its handle: never certified (exit 1).
BOOST_AUTO_TEST_CASE(certify_refuses_a_mesh_that_misses_a_handle) {
  TempDir dir;
  write_text(dir / "tetra.off",
             "OFF\n4 4 0\n1.08 0 0\n-1.08 0 0\n0 0.92 0\n0 -1 0.08\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
  const RunResult r = run_delmesh({"check", "tetra.off", "--surface", "thin_handle", "--certify", "--json"}, dir.path);
  BOOST_TEST(r.exit_code == 1, r.err);
  const nlohmann::json c = nlohmann::json::parse(r.out).at("certificate");
  BOOST_TEST(c.at("status").get<std::string>() != "certified", c.dump());
  const RunResult text = run_delmesh({"check", "tetra.off", "--surface", "thin_handle", "--certify"}, dir.path);
  BOOST_TEST(text.exit_code == 1);
  BOOST_TEST(text.out.find("certificate:           certified") == std::string::npos, text.out);
}

// A mesh from elsewhere that is not Tri S|Σ of its vertices: the restricted-Delaunay certificate
// cannot say, the gradient flow certifies it (auto runs it), with a Hausdorff bound at least
// the largest distance of a vertex ring's chord midpoint to the sphere.
BOOST_AUTO_TEST_CASE(certify_a_mesh_that_is_not_the_restricted_delaunay_triangulation) {
  TempDir dir;
  write_text(dir / "uv.off", uv_sphere_off(8, 16));
  const RunResult r = run_delmesh({"check", "uv.off", "--surface", "sphere", "--certify", "--json"}, dir.path);
  BOOST_TEST(r.exit_code == 0, r.err);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  BOOST_TEST(!j.at("certificate").at("restricted_matches_mesh").get<bool>());
  BOOST_TEST(j.at("gradient_flow").at("status").get<std::string>() == "certified", j.at("gradient_flow").dump());
  BOOST_TEST(j.at("topology").at("verdict").get<std::string>() == "certified");
  BOOST_TEST(j.at("topology").at("method").get<std::string>() == "gradient-flow");
  const double bound = j.at("topology").at("hausdorff_upper_bound").get<double>();
  const double sagitta = 1 - std::cos(std::acos(-1.0) / 16);  // the equator's chords
  BOOST_TEST(bound >= sagitta);
  BOOST_TEST(bound <= 10 * sagitta);
  BOOST_TEST(j.at("gradient_flow").at("triangle_distance_bounds").size() == 16u * 2u * 7u);
  // Only the gradient flow; and as text, where the restricted-Delaunay status is explained.
  const RunResult flow =
      run_delmesh({"check", "uv.off", "--surface", "sphere", "--certify", "--method", "gradient-flow", "--json"}, dir.path);
  BOOST_TEST(flow.exit_code == 0, flow.err);
  BOOST_TEST(!nlohmann::json::parse(flow.out).contains("certificate"));
  const RunResult text = run_delmesh({"check", "uv.off", "--surface", "sphere", "--certify"}, dir.path);
  BOOST_TEST(text.out.find("topology:              certified (gradient-flow)") != std::string::npos, text.out);
  BOOST_TEST(text.out.find("Hausdorff distance:  <= ") != std::string::npos, text.out);
  // The restricted-Delaunay certificate alone does not certify it: exit 1, undecided.
  const RunResult delaunay = run_delmesh(
      {"check", "uv.off", "--surface", "sphere", "--certify", "--method", "restricted-delaunay", "--json"}, dir.path);
  BOOST_TEST(delaunay.exit_code == 1);
  BOOST_TEST(nlohmann::json::parse(delaunay.out).at("topology").at("verdict").get<std::string>() == "undecided");
}

// --method both on delmesh's own mesh: the two independent proofs hold.
BOOST_AUTO_TEST_CASE(certify_both_methods_on_delmesh_output) {
  TempDir dir;
  const RunResult m = run_delmesh({"mesh", "--surface", "torus", "--size-bound", "0.1", "--out", "torus.off",
                                   "--stats", "torus.json", "--quiet"},
                                  dir.path);
  BOOST_TEST_REQUIRE(m.exit_code == 0, m.err);
  const RunResult r =
      run_delmesh({"check", "torus.off", "--surface", "torus", "--certify", "--method", "both", "--json"}, dir.path);
  BOOST_TEST(r.exit_code == 0, r.err);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  BOOST_TEST(j.at("certificate").at("status").get<std::string>() == "certified");
  BOOST_TEST(j.at("gradient_flow").at("status").get<std::string>() == "certified");
  BOOST_TEST(j.at("topology").at("method").get<std::string>() == "both");
}

// A mesh with a hole is refuted by the gradient flow (the sphere is a closed surface); the
// tetrahedron on the thin torus is left undecided, never certified.
BOOST_AUTO_TEST_CASE(certify_gradient_flow_refutes_only_with_a_proof) {
  TempDir dir;
  write_text(dir / "open.off", "OFF\n6 7 0\n1 0 0\n-1 0 0\n0 1 0\n0 -1 0\n0 0 1\n0 0 -1\n"
                               "3 0 2 4\n3 2 1 4\n3 1 3 4\n3 3 0 4\n3 2 0 5\n3 1 2 5\n3 3 1 5\n");
  const RunResult r = run_delmesh(
      {"check", "open.off", "--surface", "sphere", "--certify", "--method", "gradient-flow", "--json"}, dir.path);
  BOOST_TEST(r.exit_code == 1, r.err);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  BOOST_TEST(j.at("topology").at("verdict").get<std::string>() == "refuted", j.dump());
  BOOST_TEST(j.at("topology").at("hausdorff_upper_bound").is_null());
  write_text(dir / "tetra.off",
             "OFF\n4 4 0\n1.08 0 0\n-1.08 0 0\n0 0.92 0\n0 -1 0.08\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
  const RunResult t = run_delmesh({"check", "tetra.off", "--surface", "thin_handle", "--certify", "--json"}, dir.path);
  BOOST_TEST(t.exit_code == 1);
  const nlohmann::json tj = nlohmann::json::parse(t.out);
  BOOST_TEST(tj.at("topology").at("verdict").get<std::string>() == "undecided");
  BOOST_TEST(tj.at("gradient_flow").at("reason").get<std::string>().find("transverse") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(certify_options_are_validated) {
  TempDir dir;
  write_text(dir / "octahedron.off", octahedron_off);
  require_invalid_input(run_delmesh({"check", "octahedron.off", "--certify"}, dir.path), "--certify");
  require_invalid_input(run_delmesh({"check", "octahedron.off", "--surface", "sphere"}, dir.path), "--certify");
  require_invalid_input(run_delmesh({"check", "octahedron.off", "--seed", "3"}, dir.path), "--certify");
  require_invalid_input(run_delmesh({"check", "octahedron.off", "--method", "both"}, dir.path), "--certify");
  require_invalid_input(
      run_delmesh({"check", "octahedron.off", "--surface", "sphere", "--certify", "--method", "flow"}, dir.path),
      "--method");
  require_invalid_input(run_delmesh({"check", "octahedron.off", "--surface", "nosuch", "--certify"}, dir.path));
  require_invalid_input(run_delmesh({"check", "octahedron.off", "--expr", "x^2+y^2+z^2-1", "--certify"}, dir.path),
                        "--box");
  // Σ reaches the box: not a valid surface for the certificate.
  require_invalid_input(run_delmesh({"check", "octahedron.off", "--expr", "x^2+y^2+z^2-1", "--box",
                                     "-1,1,-1,1,-1,1", "--certify"}, dir.path));
}

// Acceptance: `check --certify` on delmesh's own output at lambda 0.06, every catalog surface.
BOOST_AUTO_TEST_CASE(certify_every_catalog_output, *boost::unit_test::label("slow")) {
  TempDir dir;
  const nlohmann::json catalog = nlohmann::json::parse(run_delmesh({"surfaces", "--json"}, dir.path).out);
  BOOST_REQUIRE(catalog.size() >= 10u);
  for (const auto& entry : catalog) {
    const std::string name = entry.at("name").get<std::string>();
    const RunResult m = run_delmesh({"mesh", "--surface", name, "--lambda", "0.06", "--out", name + ".off", "--stats",
                                     name + ".json", "--quiet"},
                                    dir.path);
    BOOST_TEST(m.exit_code == 0, name << ": " << m.err);
    const RunResult r = run_delmesh({"check", name + ".off", "--surface", name, "--certify", "--json"}, dir.path);
    BOOST_TEST(r.exit_code == 0, name << ": " << r.err);
    const nlohmann::json c = nlohmann::json::parse(r.out).at("certificate");
    BOOST_TEST(c.at("status").get<std::string>() == "certified", name << ": " << c.dump());
    BOOST_TEST(c.at("restricted_matches_mesh").get<bool>(), name);
    const nlohmann::json stats = nlohmann::json::parse(read_text(dir / (name + ".json")));
    BOOST_TEST_MESSAGE(name << ": meshing " << stats.at("seconds").get<double>() << " s, certificate "
                            << c.at("seconds").get<double>() << " s");
  }
}

BOOST_AUTO_TEST_SUITE_END()
