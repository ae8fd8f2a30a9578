#include <algorithm>
#include <set>

#include <boost/test/unit_test.hpp>
#include <nlohmann/json.hpp>

#include "symbolic/catalog.h"
#include "tests/apps/run_delmesh.h"

using namespace delmesh::test;

BOOST_AUTO_TEST_SUITE(surfaces_command)

BOOST_AUTO_TEST_CASE(help_exits_zero_and_lists_the_subcommands) {
  const RunResult r = run_delmesh({"--help"});
  BOOST_TEST(r.exit_code == 0);
  for (const char* sub : {"surfaces", "solve", "mesh", "check"}) {
    BOOST_TEST(r.out.find(sub) != std::string::npos, sub);
  }
  const RunResult mesh_help = run_delmesh({"mesh", "--help"});
  BOOST_TEST(mesh_help.exit_code == 0);
  BOOST_TEST(mesh_help.out.find("--lambda") != std::string::npos);
  BOOST_TEST(mesh_help.out.find("0.06") != std::string::npos);  // the default is shown
  BOOST_TEST(mesh_help.err.empty());
  BOOST_TEST(run_delmesh({"solve", "--help"}).exit_code == 0);
  BOOST_TEST(run_delmesh({"check", "--help"}).exit_code == 0);
}

BOOST_AUTO_TEST_CASE(usage_errors_are_one_error_line_and_exit_2) {
  require_invalid_input(run_delmesh({}));
  require_invalid_input(run_delmesh({"frobnicate"}));
  require_invalid_input(run_delmesh({"surfaces", "--bogus"}), "--bogus");
  require_invalid_input(run_delmesh({"check"}));                      // MESH is required
  require_invalid_input(run_delmesh({"mesh", "--lambda", "abc"}));     // not a number
  require_invalid_input(run_delmesh({"solve", "--surface", "sphere"}));  // --primitive is required
}

BOOST_AUTO_TEST_CASE(json_lists_the_catalog) {
  const RunResult r = run_delmesh({"surfaces", "--json"});
  BOOST_TEST(r.exit_code == 0);
  BOOST_TEST(r.err.empty());
  const nlohmann::json j = nlohmann::json::parse(r.out);
  BOOST_REQUIRE(j.is_array());
  BOOST_TEST(j.size() == delmesh::catalog().size());
  std::set<std::string> names;
  for (const auto& e : j) {
    names.insert(e.at("name").get<std::string>());
    const auto box = e.at("box").get<std::vector<double>>();
    BOOST_REQUIRE(box.size() == 6u);
    for (int i = 0; i < 3; ++i) BOOST_TEST(box[2 * i] < box[2 * i + 1]);
    const int components = e.at("components").get<int>();
    BOOST_TEST(components >= 1);
    BOOST_TEST(e.at("genus_per_component").size() == static_cast<std::size_t>(components));
    BOOST_TEST(!e.at("equation").get<std::string>().empty());
    BOOST_TEST(e.contains("description"));
  }
  for (const char* name : {"sphere", "ellipsoid", "torus", "genus2", "chair", "tanglecube", "metaball", "two_blobs"}) {
    BOOST_TEST(names.count(name) == 1u, name);
  }
  for (const auto& e : j) {
    const std::string name = e.at("name").get<std::string>();
    const auto genus = e.at("genus_per_component").get<std::vector<int>>();
    if (name == "sphere") BOOST_TEST((genus == std::vector<int>{0}));
    if (name == "torus") BOOST_TEST((genus == std::vector<int>{1}));
    if (name == "genus2") BOOST_TEST((genus == std::vector<int>{2}));
    if (name == "two_blobs") BOOST_TEST(e.at("components").get<int>() == 2);
  }
}

BOOST_AUTO_TEST_CASE(text_lists_every_surface) {
  const RunResult r = run_delmesh({"surfaces"});
  BOOST_TEST(r.exit_code == 0);
  for (const auto& entry : delmesh::catalog()) {
    BOOST_TEST(r.out.find(entry.name + "\n") != std::string::npos, entry.name);
  }
}

BOOST_AUTO_TEST_SUITE_END()
