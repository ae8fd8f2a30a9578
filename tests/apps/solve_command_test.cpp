#include <algorithm>
#include <cmath>

#include <boost/test/unit_test.hpp>
#include <nlohmann/json.hpp>

#include "tests/apps/run_delmesh.h"

using namespace delmesh::test;

namespace {

using Points = std::vector<std::array<double, 3>>;

Points roots_of(const nlohmann::json& j) {
  Points roots;
  for (const auto& r : j.at("roots")) roots.push_back({r.at(0).get<double>(), r.at(1).get<double>(), r.at(2).get<double>()});
  std::sort(roots.begin(), roots.end());
  return roots;
}

//! Asserts the JSON of `delmesh solve --json` has exactly the keys of the contract.
nlohmann::json parse_solve_json(const RunResult& r) {
  BOOST_TEST(r.exit_code == 0, r.err);
  nlohmann::json j = nlohmann::json::parse(r.out);
  std::vector<std::string> keys;
  for (auto it = j.begin(); it != j.end(); ++it) keys.push_back(it.key());
  std::sort(keys.begin(), keys.end());
  BOOST_TEST((keys == std::vector<std::string>{"boxes", "roots", "seconds", "status", "undecided"}));
  BOOST_TEST(j.at("boxes").is_number_integer());
  BOOST_TEST(j.at("seconds").get<double>() >= 0);
  return j;
}

double norm(const std::array<double, 3>& p) { return std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]); }

}  // namespace

BOOST_AUTO_TEST_SUITE(solve_command)

BOOST_AUTO_TEST_CASE(sphere_critical_points_are_the_poles) {
  const nlohmann::json j = parse_solve_json(
      run_delmesh({"solve", "--surface", "sphere", "--primitive", "surface_critical", "--json"}));
  BOOST_TEST(j.at("status").get<std::string>() == "complete");
  BOOST_TEST(j.at("undecided").empty());
  const Points roots = roots_of(j);
  BOOST_REQUIRE(roots.size() == 2u);
  BOOST_TEST(std::abs(roots[0][2] + 1) < 1e-9);
  BOOST_TEST(std::abs(roots[1][2] - 1) < 1e-9);
  for (const auto& p : roots) BOOST_TEST(std::hypot(p[0], p[1]) < 1e-9);
}

BOOST_AUTO_TEST_CASE(sphere_critical_points_in_a_given_direction) {
  // ±d/|d| for d = (1, 2, 2): (±1/3, ±2/3, ±2/3).
  const nlohmann::json j = parse_solve_json(run_delmesh({"solve", "--expr", "x^2+y^2+z^2-1", "--box",
                                                         "-2,2,-2,2,-2,2", "--primitive", "surface_critical",
                                                         "--direction", "1,2,2", "--json"}));
  const Points roots = roots_of(j);
  BOOST_REQUIRE(roots.size() == 2u);
  for (int i = 0; i < 3; ++i) {
    const double expected = (i == 0 ? 1.0 : 2.0) / 3.0;
    BOOST_TEST(std::abs(roots[0][i] + expected) < 1e-9);
    BOOST_TEST(std::abs(roots[1][i] - expected) < 1e-9);
  }
}

BOOST_AUTO_TEST_CASE(line_through_the_centre_meets_the_sphere_at_distance_one) {
  const nlohmann::json j = parse_solve_json(run_delmesh({"solve", "--surface", "sphere", "--primitive",
                                                         "surface_line", "--point", "0,0,0", "--direction",
                                                         "1,2,3", "--json"}));
  BOOST_TEST(j.at("status").get<std::string>() == "complete");
  const Points roots = roots_of(j);
  BOOST_REQUIRE(roots.size() == 2u);
  for (const auto& p : roots) {
    BOOST_TEST(std::abs(norm(p) - 1) < 1e-9);
    // on the line: p ∥ (1, 2, 3)
    BOOST_TEST(std::abs(p[1] - 2 * p[0]) < 1e-9);
    BOOST_TEST(std::abs(p[2] - 3 * p[0]) < 1e-9);
  }
  BOOST_TEST(roots[0][0] * roots[1][0] < 0);  // opposite sides of the centre
}

BOOST_AUTO_TEST_CASE(homotopy_backend_agrees_on_the_sphere) {
  const nlohmann::json critical = parse_solve_json(run_delmesh(
      {"solve", "--surface", "sphere", "--primitive", "surface_critical", "--solver", "homotopy", "--json"}));
  const Points poles = roots_of(critical);
  BOOST_REQUIRE(poles.size() == 2u);
  BOOST_TEST(std::abs(poles[0][2] + 1) < 1e-9);
  BOOST_TEST(std::abs(poles[1][2] - 1) < 1e-9);
  const nlohmann::json line = parse_solve_json(run_delmesh({"solve", "--surface", "sphere", "--primitive",
                                                            "surface_line", "--point", "0,0,0", "--direction",
                                                            "1,2,3", "--solver", "homotopy", "--json"}));
  const Points hits = roots_of(line);
  BOOST_REQUIRE(hits.size() == 2u);
  for (const auto& p : hits) BOOST_TEST(std::abs(norm(p) - 1) < 1e-9);
}

BOOST_AUTO_TEST_CASE(taylor_forms_give_the_24_tanglecube_critical_points) {
  // The 24 critical points of tanglecube in direction z (worked out in the solvers' tests), with
  // and without Taylor forms; a mode that does not exist is invalid input.
  Points previous;
  for (const std::string mode : {"never", "always", "automatic"}) {
    const Points roots = roots_of(parse_solve_json(run_delmesh(
        {"solve", "--surface", "tanglecube", "--primitive", "surface_critical", "--taylor-forms", mode, "--json"})));
    BOOST_TEST(roots.size() == 24u);
    for (const auto& p : previous) {
      int matches = 0;
      for (const auto& q : roots)
        matches += std::abs(p[0] - q[0]) < 1e-9 && std::abs(p[1] - q[1]) < 1e-9 && std::abs(p[2] - q[2]) < 1e-9;
      BOOST_TEST(matches == 1, mode);
    }
    previous = roots;
  }
  require_invalid_input(run_delmesh({"solve", "--surface", "tanglecube", "--primitive", "surface_critical",
                                     "--taylor-forms", "sometimes"}),
                        "--taylor-forms");
}

BOOST_AUTO_TEST_CASE(a_line_missing_the_box_has_no_roots) {
  const nlohmann::json j = parse_solve_json(run_delmesh({"solve", "--surface", "sphere", "--primitive",
                                                         "surface_line", "--point", "0,0,5", "--direction",
                                                         "1,0,0", "--json"}));
  BOOST_TEST(j.at("roots").empty());
  BOOST_TEST(j.at("undecided").empty());
}

BOOST_AUTO_TEST_CASE(plane_through_the_torus_centre_cuts_two_circles) {
  // The plane y = 0 cuts the torus in the circles (x ∓ 1)² + z² = 0.16; their critical points in
  // the in-plane direction x are (±0.6, 0, 0) and (±1.4, 0, 0).
  const nlohmann::json j = parse_solve_json(run_delmesh(
      {"solve", "--surface", "torus", "--primitive", "curve_critical", "--plane-origin", "0,0,0", "--plane-normal",
       "0,1,0", "--direction", "1,0,0", "--json"}));
  BOOST_TEST(j.at("status").get<std::string>() == "complete");
  Points roots = roots_of(j);
  BOOST_REQUIRE(roots.size() == 4u);
  const double xs[] = {-1.4, -0.6, 0.6, 1.4};
  for (int i = 0; i < 4; ++i) {
    BOOST_TEST(std::abs(roots[i][0] - xs[i]) < 1e-9);
    BOOST_TEST(std::abs(roots[i][1]) < 1e-9);
    BOOST_TEST(std::abs(roots[i][2]) < 1e-9);
  }
}

BOOST_AUTO_TEST_CASE(a_plane_missing_the_sphere_has_no_contact) {
  const nlohmann::json j = parse_solve_json(run_delmesh({"solve", "--surface", "sphere", "--primitive",
                                                         "surface_plane_contact", "--plane-origin", "0,0,1.2",
                                                         "--plane-normal", "0,0,1", "--json"}));
  BOOST_TEST(j.at("status").get<std::string>() == "complete");
  BOOST_TEST(j.at("roots").empty());
  BOOST_TEST(j.at("undecided").empty());
}

BOOST_AUTO_TEST_CASE(text_output_prints_the_roots) {
  const RunResult r = run_delmesh({"solve", "--surface", "sphere", "--primitive", "surface_critical"});
  BOOST_TEST(r.exit_code == 0, r.err);
  BOOST_TEST(r.out.find("status:    complete") != std::string::npos, r.out);
  BOOST_TEST(r.out.find("roots:     2") != std::string::npos, r.out);
}

BOOST_AUTO_TEST_CASE(bad_expressions_and_parameters_are_invalid_input) {
  const std::vector<std::string> box{"--box", "-2,2,-2,2,-2,2"};
  auto solve_expr = [&](const std::string& expr) {
    std::vector<std::string> args{"solve", "--expr", expr, "--primitive", "surface_critical"};
    args.insert(args.end(), box.begin(), box.end());
    return run_delmesh(args);
  };
  require_invalid_input(solve_expr("x^2+y^2+z^2-1)"));   // malformed
  require_invalid_input(solve_expr("x^2+y^2+w^2-1"), "w");  // unknown symbol
  require_invalid_input(solve_expr("x^2.5+y^2+z^2-1"));  // non-integer power
  require_invalid_input(solve_expr(""));                 // empty
  require_invalid_input(solve_expr("   "));              // blank
  require_invalid_input(solve_expr("2+3"));              // constant
  require_invalid_input(run_delmesh({"solve", "--expr", "x^2+y^2+z^2-1", "--box", "1,0,-1,1,-1,1", "--primitive",
                                     "surface_critical"}));  // empty box
  require_invalid_input(run_delmesh({"solve", "--expr", "x^2+y^2+z^2-1", "--box", "-1,1,-1,1", "--primitive",
                                     "surface_critical"}));  // five numbers short
  require_invalid_input(run_delmesh({"solve", "--expr", "x^2+y^2+z^2-1", "--primitive", "surface_critical"}),
                        "--box");
  require_invalid_input(run_delmesh({"solve", "--surface", "no_such_surface", "--primitive", "surface_critical"}),
                        "no_such_surface");
  require_invalid_input(run_delmesh({"solve", "--surface", "sphere", "--primitive", "no_such_primitive"}),
                        "no_such_primitive");
  require_invalid_input(
      run_delmesh({"solve", "--surface", "sphere", "--expr", "x^2+y^2+z^2-1", "--primitive", "surface_critical"}));
  // Missing and inconsistent parameters.
  require_invalid_input(run_delmesh({"solve", "--surface", "sphere", "--primitive", "surface_line", "--point", "0,0,0"}),
                        "--direction");
  require_invalid_input(run_delmesh({"solve", "--surface", "sphere", "--primitive", "surface_critical", "--point",
                                     "0,0,0"}),
                        "--point");
  require_invalid_input(run_delmesh({"solve", "--surface", "sphere", "--primitive", "surface_critical",
                                     "--direction", "0,0,0"}));
  require_invalid_input(run_delmesh({"solve", "--surface", "sphere", "--primitive", "surface_critical",
                                     "--direction", "1,2"}),
                        "--direction");
  require_invalid_input(run_delmesh({"solve", "--surface", "sphere", "--primitive", "surface_plane_contact",
                                     "--plane-origin", "0,0,0"}),
                        "--plane-normal");
  require_invalid_input(run_delmesh({"solve", "--surface", "sphere", "--primitive", "curve_critical",
                                     "--plane-origin", "0,0,0", "--plane-normal", "0,0,1", "--direction", "0,0,2"}));
  require_invalid_input(run_delmesh({"solve", "--surface", "sphere", "--primitive", "silhouette_critical",
                                     "--direction", "0,0,1", "--direction2", "0,0,-3"}));
  require_invalid_input(run_delmesh({"solve", "--surface", "sphere", "--primitive", "surface_critical", "--solver",
                                     "magic"}),
                        "--solver");
  require_invalid_input(run_delmesh({"solve", "--surface", "sphere", "--primitive", "surface_plane_contact",
                                     "--plane-origin", "0,0,0", "--plane-normal", "0,0,1", "--solver", "homotopy"}),
                        "homotopy");
  require_invalid_input(run_delmesh({"solve", "--surface", "sphere", "--primitive", "surface_critical",
                                     "--max-boxes", "0"}),
                        "--max-boxes");
  require_invalid_input(run_delmesh({"solve", "--surface", "metaball", "--primitive", "surface_critical", "--solver",
                                     "homotopy"}));  // not polynomial
}

BOOST_AUTO_TEST_SUITE_END()
