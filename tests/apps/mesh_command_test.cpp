#include <filesystem>

#include <boost/test/unit_test.hpp>
#include <nlohmann/json.hpp>

#include "tests/apps/run_delmesh.h"

using namespace delmesh::test;

namespace {


//! Files of the scratch directory other than the runner's own.
std::vector<std::string> files_in(const ScratchDirectory& dir) {
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
  require_invalid_input(run_delmesh({"mesh", "--surface", "sphere", "--out", "sphere.stl"}), ".stl");
  require_invalid_input(run_delmesh({"mesh", "--surface", "sphere", "--out", "no/such/dir/sphere.off"}), "--out");
  require_invalid_input(run_delmesh({"mesh", "--surface", "sphere", "--phase", "everything"}), "--phase");
  require_invalid_input(run_delmesh({"mesh", "--surface", "sphere", "--solver", "newton"}), "--solver");
  require_invalid_input(run_delmesh({"mesh", "--surface", "sphere", "--size-bound", "0"}), "--size-bound");
  require_invalid_input(run_delmesh({"mesh", "--surface", "sphere", "--time-limit", "-1"}), "--time-limit");
  require_invalid_input(run_delmesh({"mesh", "--surface", "sphere", "--max-points", "0"}), "--max-points");
  require_invalid_input(run_delmesh({"mesh", "--surface", "sphere", "--threads", "-1"}), "--threads");
}

BOOST_AUTO_TEST_CASE(input_mesh_is_validated_then_reported_unimplemented) {
  ScratchDirectory dir;
  write_text(dir / "octahedron.off", octahedron_off);
  write_text(dir / "corrupt.off", "OFF\n6 8 0\n1 0 0\nbroken\n");
  require_invalid_input(run_delmesh({"mesh", "--input-mesh", "missing.off"}, dir.path));
  require_invalid_input(run_delmesh({"mesh", "--input-mesh", "corrupt.off"}, dir.path));
  require_invalid_input(run_delmesh({"mesh", "--input-mesh", "octahedron.off"}, dir.path), "not implemented");
  require_invalid_input(run_delmesh({"mesh", "--input-mesh", "octahedron.off", "--surface", "sphere"}, dir.path));
}

BOOST_AUTO_TEST_CASE(a_failing_run_leaves_existing_outputs_untouched) {
  ScratchDirectory dir;
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
  ScratchDirectory dir;
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
  BOOST_TEST(stats.at("status").get<std::string>() == "complete");
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
  ScratchDirectory dir;
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

BOOST_AUTO_TEST_CASE(a_point_limit_stops_with_exit_3_and_writes_the_partial_outputs) {
  ScratchDirectory dir;
  const RunResult r =
      run_delmesh({"mesh", "--surface", "torus", "--max-points", "8", "--quiet", "--out", "t.obj"}, dir.path);
  BOOST_TEST(!r.signalled);
  BOOST_TEST(r.exit_code == 3, r.err);
  BOOST_TEST(std::filesystem::exists(dir / "t.obj"));
  const nlohmann::json stats = nlohmann::json::parse(read_text(dir / "torus.json"));
  BOOST_TEST(stats.at("status").get<std::string>() == "point_limit");
}

BOOST_AUTO_TEST_CASE(a_time_limit_stops_with_exit_3_and_replaces_outputs_atomically) {
  ScratchDirectory dir;
  write_text(dir / "g.off", octahedron_off);
  const RunResult r = run_delmesh({"mesh", "--surface", "genus2", "--size-bound", "0.01", "--time-limit", "0.5",
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
}

BOOST_AUTO_TEST_SUITE_END()
