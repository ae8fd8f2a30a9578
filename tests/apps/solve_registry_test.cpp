// `delmesh solve` and the primitive registry: every registered primitive is listed by
// `delmesh solve --help` and solvable from the command line (its row's known-answer query), and
// the table of primitives in docs/cli.md is the one the registry generates.  Compiled into apps_tests
// (with delmesh) and into extending_tests (with delmesh_extending, examples/extending).

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <boost/test/unit_test.hpp>
#include <nlohmann/json.hpp>

#include "solvers/primitive_registry.h"
#include "tests/apps/run_delmesh.h"

using namespace delmesh;
using namespace delmesh::test;

namespace {

//! The text between the line holding `begin` and the line holding `end` (both excluded).
std::string block_between(const std::string& text, const std::string& begin, const std::string& end) {
  const std::size_t b = text.find(begin), e = text.find(end);
  if (b == std::string::npos || e == std::string::npos || e < b) return "(markers not found)";
  const std::size_t start = text.find('\n', b) + 1;
  return text.substr(start, text.rfind('\n', e) + 1 - start);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(solve_registry)

BOOST_AUTO_TEST_CASE(every_primitive_is_listed_by_the_help) {
  const RunResult r = run_delmesh({"solve", "--help"});
  BOOST_TEST(r.exit_code == 0, r.err);
  for (const PrimitiveInfo& row : primitive_registry()) {
    BOOST_TEST(r.out.find("  " + row.name + ": " + row.summary + "\n") != std::string::npos, row.name);
  }
}

BOOST_AUTO_TEST_CASE(every_known_answer_is_found_from_the_command_line) {
  for (const PrimitiveInfo& row : primitive_registry()) {
    BOOST_TEST_CONTEXT(row.name << " on " << row.example.surface) {
      std::vector<std::string> args{"solve", "--surface", row.example.surface, "--primitive", row.name, "--json"};
      for (const auto& [option, value] : row.example.options.values) {
        args.push_back(option_flag(option));
        args.push_back(vector_text(value));
      }
      const RunResult r = run_delmesh(args);
      BOOST_REQUIRE_MESSAGE(r.exit_code == 0, r.err);
      const nlohmann::json j = nlohmann::json::parse(r.out);
      BOOST_TEST(j.at("status").get<std::string>() == "complete");
      BOOST_TEST(j.at("undecided").empty());
      BOOST_TEST(j.at("roots").size() == row.example.roots.size());
      for (const Vec3& x : row.example.roots) {
        int matches = 0;
        for (const auto& root : j.at("roots")) {
          matches += std::abs(root.at(0).get<double>() - x[0]) < 1e-9 &&
                     std::abs(root.at(1).get<double>() - x[1]) < 1e-9 &&
                     std::abs(root.at(2).get<double>() - x[2]) < 1e-9;
        }
        BOOST_TEST(matches == 1, "root " << x[0] << " " << x[1] << " " << x[2]);
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(the_documented_table_is_the_generated_one) {
  std::ifstream in(std::string(DELMESH_SOURCE_DIR) + "/docs/cli.md");
  std::stringstream doc;
  doc << in.rdbuf();
  const std::string expected = primitive_table_markdown(builtin_primitives());
  const std::string found =
      block_between(doc.str(), "<!-- primitive table: generated", "<!-- end of primitive table -->");
  BOOST_TEST(found == expected, "docs/cli.md's table of primitives is out of date; it should read:\n" << expected);
}

BOOST_AUTO_TEST_SUITE_END()
