#include <cmath>

#include <boost/test/unit_test.hpp>
#include <nlohmann/json.hpp>

#include "tests/apps/run_delmesh.h"

using namespace delmesh::test;

BOOST_AUTO_TEST_SUITE(check_command)

BOOST_AUTO_TEST_CASE(octahedron_has_genus_zero) {
  ScratchDirectory dir;
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

BOOST_AUTO_TEST_CASE(theorem_bounds_pass_and_fail_per_bound) {
  ScratchDirectory dir;
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
  ScratchDirectory dir;
  write_text(dir / "octahedron.off", octahedron_off);
  write_text(dir / "corrupt.off", "OFF\n6 8 0\n1 0 0\n-1 0\nnot a number\n");
  write_text(dir / "indices.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
  require_invalid_input(run_delmesh({"check", "corrupt.off"}, dir.path));
  require_invalid_input(run_delmesh({"check", "indices.off"}, dir.path));
  require_invalid_input(run_delmesh({"check", "missing.off"}, dir.path));
  require_invalid_input(run_delmesh({"check", "octahedron.off", "--lambda", "0"}, dir.path), "--lambda");
  require_invalid_input(run_delmesh({"check", "octahedron.off", "--lambda", "0.5"}, dir.path), "--lambda");
}

BOOST_AUTO_TEST_SUITE_END()
