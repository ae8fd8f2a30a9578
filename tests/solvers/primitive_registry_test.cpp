#include "solvers/primitive_registry.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <boost/test/unit_test.hpp>

#include "common/errors.h"
#include "symbolic/catalog.h"

using namespace delmesh;

namespace {

//! Every expected root is within 1e-9 of exactly one certified root, and there are no others.
void require_roots(const SolveResult& result, const std::vector<Vec3>& expected) {
  BOOST_TEST(result.roots.size() == expected.size());
  for (const Vec3& x : expected) {
    int matches = 0;
    for (const CertifiedRoot& r : result.roots) {
      matches += std::abs(r.world[0] - x[0]) < 1e-9 && std::abs(r.world[1] - x[1]) < 1e-9 &&
                 std::abs(r.world[2] - x[2]) < 1e-9;
    }
    BOOST_TEST(matches == 1, "root " << x[0] << " " << x[1] << " " << x[2]);
  }
}

//! Solves the row's known-answer query with the given solver.
SolveResult solve_example(const PrimitiveInfo& row, SolverBackend solver) {
  const CatalogEntry& entry = catalog_entry(row.example.surface);
  const Surface surface = entry.surface();
  const CompiledPrimitive primitive(row.build(surface));
  const PrimitiveQuery query = row.query(row.example.options, entry.box);
  BOOST_REQUIRE(query.parameters.size() == primitive.system.n_parameters());
  BOOST_REQUIRE(query.domain.has_value());
  std::unique_ptr<LinePolynomial> polynomial;
  if (query.line && surface.is_polynomial()) polynomial = std::make_unique<LinePolynomial>(surface);
  QuerySolveOptions options;
  options.solver = solver;
  return solve_query(primitive, query, options, polynomial.get());
}

bool has_text(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

BOOST_AUTO_TEST_SUITE(primitive_registry_rows)

BOOST_AUTO_TEST_CASE(every_row_is_complete_and_its_name_unique) {
  std::set<std::string> names;
  for (const PrimitiveInfo& row : primitive_registry()) {
    BOOST_TEST_CONTEXT(row.name) {
      BOOST_TEST(names.insert(row.name).second);
      BOOST_TEST(!row.summary.empty());
      BOOST_TEST(!row.domain.empty());
      BOOST_TEST(static_cast<bool>(row.builder));
      BOOST_TEST(static_cast<bool>(row.make_query));
      // The table cells of the help and docs/cli.md: no '|' and no line breaks.
      for (const std::string& text : {row.summary, row.domain}) BOOST_TEST(text.find_first_of("|\n") == std::string::npos);
      std::set<QueryOption> read;
      for (const OptionUse& use : row.options) {
        BOOST_TEST(read.insert(use.option).second);
        BOOST_TEST(!use.meaning.empty());
        BOOST_TEST(use.meaning.find_first_of("|\n") == std::string::npos);
      }
      BOOST_CHECK_NO_THROW(catalog_entry(row.example.surface));
      BOOST_CHECK_NO_THROW(row.check_query_options(row.example.options));
    }
  }
}

BOOST_AUTO_TEST_CASE(every_known_answer_is_found_by_the_subdivision_solver) {
  for (const PrimitiveInfo& row : primitive_registry()) {
    BOOST_TEST_CONTEXT(row.name << " on " << row.example.surface) {
      const SolveResult result = solve_example(row, SolverBackend::subdivision);
      BOOST_TEST(result.status == SolveStatus::complete);
      BOOST_TEST(result.undecided.empty());
      require_roots(result, row.example.roots);
    }
  }
}

BOOST_AUTO_TEST_CASE(every_square_known_answer_is_found_by_the_homotopy_solver) {
  // The independent cross-check: total-degree homotopy on the same queries (all are polynomial).
  for (const PrimitiveInfo& row : primitive_registry()) {
    if (!row.build(catalog_entry(row.example.surface).surface()).is_square()) continue;
    BOOST_TEST_CONTEXT(row.name << " on " << row.example.surface) {
      const SolveResult result = solve_example(row, SolverBackend::homotopy);
      BOOST_TEST(result.status == SolveStatus::complete);
      require_roots(result, row.example.roots);
    }
  }
}

BOOST_AUTO_TEST_CASE(an_option_not_read_or_a_required_one_missing_is_invalid_input) {
  for (const PrimitiveInfo& row : primitive_registry()) {
    BOOST_TEST_CONTEXT(row.name) {
      for (QueryOption option : all_query_options) {
        const bool read = std::any_of(row.options.begin(), row.options.end(),
                                      [&](const OptionUse& use) { return use.option == option; });
        if (read) continue;
        QueryOptions given = row.example.options;
        given.values[option] = {1, 2, 3};
        try {
          row.check_query_options(given);
          BOOST_ERROR("no exception for " << option);
        } catch (const InvalidInput& e) {
          BOOST_TEST(has_text(e.what(), option_flag(option) + " is not a parameter of " + row.name));
        }
      }
      for (const OptionUse& use : row.options) {
        if (!use.required) continue;
        QueryOptions given = row.example.options;
        given.values.erase(use.option);
        try {
          (void)row.query(given, catalog_entry(row.example.surface).box);
          BOOST_ERROR("no exception without " << use.option);
        } catch (const InvalidInput& e) {
          BOOST_TEST(has_text(e.what(), row.name + " needs " + option_flag(use.option)));
        }
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(a_query_outside_the_box_has_nothing_to_solve) {
  // A line or plane missing the box gives an empty domain; solve_query answers complete, no roots.
  const PrimitiveInfo& line = find_primitive("surface_line");
  const CompiledPrimitive primitive(line.build(catalog_entry("sphere").surface()));
  QueryOptions o;
  o.values = {{QueryOption::point, {0, 0, 5}}, {QueryOption::direction, {1, 0, 0}}};
  const PrimitiveQuery q = line.query(o, catalog_entry("sphere").box);
  BOOST_TEST(!q.domain.has_value());
  const SolveResult r = solve_query(primitive, q, {});
  BOOST_TEST(r.is_complete());
  BOOST_TEST(r.roots.empty());
}

BOOST_AUTO_TEST_CASE(the_table_has_one_line_per_row) {
  const std::string table = primitive_table_markdown(primitive_registry());
  std::istringstream lines(table);
  std::size_t count = 0;
  for (std::string line; std::getline(lines, line);) ++count;
  BOOST_TEST(count == primitive_registry().size() + 2);  // header and separator
  for (const PrimitiveInfo& row : primitive_registry()) {
    BOOST_TEST(has_text(table, "| `" + row.name + "` | " + row.summary + " | " + options_text(row) + " | "));
  }
}

BOOST_AUTO_TEST_CASE(registering_after_the_registry_was_read_is_refused) {
  PrimitiveInfo row = primitive_registry().front();
  row.name = "late_primitive";
  BOOST_CHECK_THROW(PrimitiveRegistration{row}, PreconditionViolation);
  BOOST_TEST(std::none_of(primitive_registry().begin(), primitive_registry().end(),
                          [](const PrimitiveInfo& r) { return r.name == "late_primitive"; }));
}

BOOST_AUTO_TEST_SUITE_END()
