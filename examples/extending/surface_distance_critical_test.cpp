// Tests of the example primitive surface_distance_critical (surface_distance_critical.cpp): the
// sphere's answer ±c/|c| (exactly, and by the certified solvers), and the torus's answer for a
// point c in its equatorial plane.  The registry's own tests (tests/solvers/primitive_registry_test.cpp
// and tests/apps/solve_registry_test.cpp, compiled into extending_tests too) solve its known-answer
// row like every other row, in the library and through delmesh_extending.

#include <array>
#include <cmath>
#include <vector>

#include <boost/test/unit_test.hpp>

#include "common/errors.h"
#include "meshing/inputs/implicit_oracle.h"
#include "solvers/primitive_registry.h"
#include "symbolic/catalog.h"

using namespace delmesh;

namespace {

const PrimitiveInfo& row() { return find_primitive("surface_distance_critical"); }

QueryOptions point(const Vec3& c) {
  QueryOptions o;
  o.values[QueryOption::point] = c;
  return o;
}

SolveResult solve(const CompiledPrimitive& primitive, const PrimitiveQuery& query, SolverBackend solver) {
  QuerySolveOptions options;
  options.solver = solver;
  return solve_query(primitive, query, options);
}

//! Each expected point is within 1e-9 of exactly one root, and there are no other roots.
void require_roots(const SolveResult& r, const std::vector<Vec3>& expected) {
  BOOST_TEST(r.status == SolveStatus::complete);
  BOOST_TEST(r.roots.size() == expected.size());
  for (const Vec3& x : expected) {
    int matches = 0;
    for (const CertifiedRoot& root : r.roots)
      matches += std::hypot(root.world[0] - x[0], root.world[1] - x[1], root.world[2] - x[2]) < 1e-9;
    BOOST_TEST(matches == 1, "root " << x[0] << " " << x[1] << " " << x[2]);
  }
}

}  // namespace

BOOST_AUTO_TEST_SUITE(surface_distance_critical)

BOOST_AUTO_TEST_CASE(the_system_vanishes_exactly_at_plus_minus_c_over_norm_c_on_the_sphere) {
  // c with rational |c| (Pythagorean quadruples); any frame (a, b): w = (x − c) × 2x = 0 there.
  const PrimitiveSystem s = row().build(catalog_entry("sphere").surface());
  BOOST_REQUIRE(s.n_parameters() == 9u);
  const std::vector<std::array<GiNaC::numeric, 4>> points = {
      {GiNaC::numeric(3, 10), GiNaC::numeric(-4, 10), GiNaC::numeric(12, 10), GiNaC::numeric(13, 10)},
      {GiNaC::numeric(2, 5), GiNaC::numeric(3, 5), GiNaC::numeric(6, 5), GiNaC::numeric(7, 5)},
      {GiNaC::numeric(-1, 3), GiNaC::numeric(4, 3), GiNaC::numeric(8, 3), GiNaC::numeric(3)}};
  for (const auto& c : points) {
    GiNaC::exmap m;
    for (int i = 0; i < 3; ++i) m[s.parameters[i]] = c[i];
    for (int i = 3; i < 9; ++i) m[s.parameters[i]] = GiNaC::numeric(i % 4 + 1, i + 2);  // any a, b
    for (int sign : {1, -1}) {
      GiNaC::exmap at = m;
      for (int i = 0; i < 3; ++i) at[s.unknowns[i]] = sign * c[i] / c[3];
      for (const GiNaC::ex& e : s.equations) BOOST_TEST(e.subs(at).expand().is_zero());
      BOOST_TEST(s.side_conditions.at(0).subs(at).expand().is_zero());
    }
    // The pole e_z (c is not parallel to it) is not critical: w = −2 c × e_z ≠ 0, so the equations
    // and the side condition do not all vanish there.
    GiNaC::exmap pole = m;
    pole[s.unknowns[0]] = 0;
    pole[s.unknowns[1]] = 0;
    pole[s.unknowns[2]] = 1;
    bool all = s.side_conditions.at(0).subs(pole).expand().is_zero();
    for (const GiNaC::ex& e : s.equations) all = all && e.subs(pole).expand().is_zero();
    BOOST_TEST(!all);
  }
}

BOOST_AUTO_TEST_CASE(the_solvers_find_plus_minus_c_over_norm_c_on_the_sphere) {
  const CatalogEntry& sphere = catalog_entry("sphere");
  const CompiledPrimitive primitive(row().build(sphere.surface()));
  for (const Vec3& c : std::vector<Vec3>{{0.3, -0.4, 1.2}, {2, 3, 6}, {-0.1, 0.02, 0.05}, {0, 0, 0.5}}) {
    BOOST_TEST_CONTEXT("c = " << c[0] << "," << c[1] << "," << c[2]) {
      const double n = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
      const std::vector<Vec3> expected{{c[0] / n, c[1] / n, c[2] / n}, {-c[0] / n, -c[1] / n, -c[2] / n}};
      const PrimitiveQuery q = row().query(point(c), sphere.box);
      require_roots(solve(primitive, q, SolverBackend::subdivision), expected);
      require_roots(solve(primitive, q, SolverBackend::homotopy), expected);
    }
  }
}

BOOST_AUTO_TEST_CASE(the_torus_answer_for_a_point_in_its_equatorial_plane) {
  // c = 1.3 ĉ in the plane z = 0 (|c| ≠ 0, 1): the distance is critical exactly at ρ ĉ for
  // ρ = ±0.6, ±1.4, where the tube's circle in the plane through the axis and c meets that plane.
  const CatalogEntry& torus = catalog_entry("torus");
  const CompiledPrimitive primitive(row().build(torus.surface()));
  const Vec3 c{0.5, 1.2, 0}, unit{5. / 13, 12. / 13, 0};
  std::vector<Vec3> expected;
  for (double rho : {-1.4, -0.6, 0.6, 1.4}) expected.push_back({rho * unit[0], rho * unit[1], 0});
  require_roots(solve(primitive, row().query(point(c), torus.box), SolverBackend::subdivision), expected);

  // With d = (1, −1, 0.5) the equations also vanish at four points with w ≠ 0 parallel to d (on
  // the plane through c normal to d, where ∇E ⟂ d); the side condition drops them.
  QueryOptions o = point(c);
  o.values[QueryOption::direction] = {1, -1, 0.5};
  const PrimitiveQuery q = row().query(o, torus.box);
  const SolveResult filtered = solve(primitive, q, SolverBackend::subdivision);
  require_roots(filtered, expected);
  PrimitiveSystem unfiltered_system = row().build(torus.surface());
  unfiltered_system.side_conditions.clear();
  const CompiledPrimitive unfiltered(std::move(unfiltered_system));
  SolveResult all = solve(unfiltered, q, SolverBackend::subdivision);
  BOOST_TEST(all.status == SolveStatus::complete);
  BOOST_TEST(all.roots.size() == 2 * expected.size());
  const std::size_t before = all.roots.size();
  BOOST_TEST(drop_spurious_roots(primitive, q.parameters, all) == before - expected.size());
  require_roots(all, expected);
}

BOOST_AUTO_TEST_CASE(a_check_solves_it_through_the_mesher_oracle) {
  // The oracle compiles every registered primitive; a check would call it by name.
  ImplicitOracle oracle(catalog_entry("sphere").surface(), catalog_entry("sphere").box, SolverBackend::subdivision);
  const OrthonormalFrame f = orthonormal_frame({3, -4, 12});
  const SolveResult r = oracle.solve("surface_distance_critical", {0.3, -0.4, 1.2, f.a[0], f.a[1], f.a[2], f.b[0], f.b[1], f.b[2]},
                                     box_domain(oracle.box()), 100000);
  require_roots(r, {{3. / 13, -4. / 13, 12. / 13}, {-3. / 13, 4. / 13, -12. / 13}});
  BOOST_TEST(oracle.statistics("surface_distance_critical").calls == 1u);
  BOOST_TEST(oracle.statistics_json()["per_primitive"]["surface_distance_critical"]["certified_roots"] == 2u);
}

BOOST_AUTO_TEST_CASE(a_point_at_the_box_centre_needs_a_direction) {
  const CatalogEntry& sphere = catalog_entry("sphere");
  BOOST_CHECK_THROW(row().query(point({0, 0, 0}), sphere.box), InvalidInput);
}

BOOST_AUTO_TEST_SUITE_END()
