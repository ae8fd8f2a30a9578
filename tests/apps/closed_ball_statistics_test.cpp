#include <filesystem>
#include <string>
#include <vector>

#include <boost/test/unit_test.hpp>
#include <nlohmann/json.hpp>

#include "tests/apps/run_delmesh.h"
#include "tests/meshing/feature_meshes.h"
#include "tests/temp_dir.h"

using namespace delmesh::test;

namespace {

// `delmesh mesh --input-mesh` on CGAL's data mesh `name` at the default λ; its statistics.
// `extra` is appended to the command line.
nlohmann::json remesh_statistics(const std::string& name, int expected_exit_code, const std::string& phase = "all",
                                 const std::vector<std::string>& extra = {}) {
  TempDir dir;
  const std::string input = cgal_data_mesh(name, dir);
  std::vector<std::string> args{"mesh", "--input-mesh", input, "--phase", phase, "--out", "out.off", "--stats",
                                "out.json", "--quiet"};
  args.insert(args.end(), extra.begin(), extra.end());
  const RunResult r = run_delmesh(args, dir.path);
  BOOST_TEST(r.exit_code == expected_exit_code, r.err);
  return nlohmann::json::parse(read_text(dir.path / "out.json"));
}

}  // namespace

BOOST_AUTO_TEST_SUITE(closed_ball_statistics)

// CGAL's eight (genus 2, 634 triangles): the run ends complete, every Voronoi face of the output's
// vertices meets the input in a closed ball, and the output is exactly Del S|Σ: the statistics
// say the output is proved homeomorphic to the input.
BOOST_AUTO_TEST_CASE(eight_is_proved_homeomorphic) {
  const nlohmann::json stats = remesh_statistics("eight", 0);
  const nlohmann::json& c = stats["closed_ball"];
  BOOST_TEST(c["status"] == "holds");
  BOOST_TEST(c["cells"] == stats["vertices"]);
  BOOST_TEST(c["restricted_delaunay_triangles"] == stats["triangles"]);
  BOOST_TEST(c["violations"]["count"] == 0);
  BOOST_TEST(c["non_generic"]["count"] == 0);
  BOOST_TEST(c["output_equals_restricted_delaunay"] == true);
  BOOST_TEST(c["proves_homeomorphism"] == true);
  BOOST_TEST(c["seconds"].get<double>() >= 0);
}

// CGAL's cube (12 triangles), whole run at the default feature angle: Smooth does not refine the
// edges whose Voronoi facets meet the cube's edges (its normal jumps by 90° there), the closed-ball
// check proves the output homeomorphic to the input, and those Smooth findings are then exempt:
// complete (exit code 0), one sphere, with the exemptions counted and nothing blocking.
BOOST_AUTO_TEST_CASE(cube_is_complete_with_smooth_exempt_at_its_creases) {
  const nlohmann::json stats = remesh_statistics("cube", 0);
  BOOST_TEST(stats["status"] == "complete");
  BOOST_TEST(stats["components"] == 1);
  BOOST_TEST(stats["genus_per_component"] == nlohmann::json::array({0}));
  BOOST_TEST(stats["input_mesh"]["features"]["angle_deg"] == 60.0);
  BOOST_TEST(stats["input_mesh"]["features"]["sharp_edges"] == 12);
  const nlohmann::json& c = stats["closed_ball"];
  BOOST_TEST(c["status"] == "holds");
  BOOST_TEST(c["proves_homeomorphism"] == true);
  BOOST_TEST(c["exempt"]["blocking"] == 0);
  const nlohmann::json& smooth = c["exempt"]["by_kind"]["smooth"];
  BOOST_TEST(smooth.value("no_witness (crease)", 0) > 0);
  BOOST_TEST(c["exempt"]["count"].get<std::size_t>() >= smooth.value("no_witness (crease)", std::size_t{0}));
  // Every exempt Smooth finding is listed under "unsettled" too, as check smooth, no_witness.
  BOOST_TEST(stats["unsettled"]["by_reason"].value("no_witness", 0) == smooth.value("no_witness (crease)", 0));
}

// The same cube with --no-features: Smooth refines at the creases into the termination floor, so
// the run ends uncertified (exit code 5) although the closed-ball check still proves the topology;
// nothing is exempt by the crease rule.
BOOST_AUTO_TEST_CASE(cube_without_features_is_uncertified) {
  const nlohmann::json stats = remesh_statistics("cube", 5, "all", {"--no-features"});
  BOOST_TEST(stats["status"] == "uncertified");
  BOOST_TEST(stats["input_mesh"]["features"]["detected"] == false);
  BOOST_TEST(stats["min_spacing"]["reached"] == true);
  const nlohmann::json& c = stats["closed_ball"];
  BOOST_TEST(c["proves_homeomorphism"] == true);
  BOOST_TEST(!c["exempt"]["by_kind"].contains("smooth"));
  BOOST_TEST(c["exempt"]["blocking"].get<std::size_t>() > 0u);
}

// --feature-angle outside (0, 180), with --no-features, or for an implicit surface: one `error:`
// line and exit code 2, before anything is meshed.
BOOST_AUTO_TEST_CASE(bad_feature_options_are_refused) {
  TempDir dir;
  const std::string input = cgal_data_mesh("cube", dir);
  const std::vector<std::vector<std::string>> refused{
      {"mesh", "--input-mesh", input, "--feature-angle", "0"},
      {"mesh", "--input-mesh", input, "--feature-angle", "180"},
      {"mesh", "--input-mesh", input, "--feature-angle", "-30"},
      {"mesh", "--input-mesh", input, "--feature-angle", "nan"},
      {"mesh", "--input-mesh", input, "--feature-angle", "45", "--no-features"},
      {"mesh", "--surface", "torus", "--feature-angle", "45"},
      {"mesh", "--surface", "torus", "--no-features"}};
  for (const auto& args : refused) {
    const RunResult r = run_delmesh(args, dir.path);
    BOOST_TEST(r.exit_code == 2, args[3] << " " << args[4] << ": " << r.err);
    BOOST_TEST(r.single_error_line(), r.err);
  }
  BOOST_TEST(!std::filesystem::exists(dir.path / "cube_remeshed.off"));
  BOOST_TEST(!std::filesystem::exists(dir.path / "torus.off"));
}

// The cube's topology phase: the closed-ball property holds and the output is Del S|Σ, so the run
// ends complete (exit code 0) with the input's topology (one sphere).
BOOST_AUTO_TEST_CASE(cube_topology_phase_is_complete) {
  const nlohmann::json stats = remesh_statistics("cube", 0, "topology");
  BOOST_TEST(stats["status"] == "complete");
  BOOST_TEST(stats["components"] == 1);
  BOOST_TEST(stats["genus_per_component"] == nlohmann::json::array({0}));
  const nlohmann::json& c = stats["closed_ball"];
  BOOST_TEST(c["status"] == "holds");
  BOOST_TEST(c["current"] == true);
  BOOST_TEST(c["proves_homeomorphism"] == true);
  BOOST_TEST(c["exempt"]["blocking"] == 0);
}

BOOST_AUTO_TEST_SUITE_END()
