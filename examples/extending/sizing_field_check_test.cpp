// Tests of the example check sizing_field (sizing_field_check.cpp): its row in the check registry,
// where it must fire and where it must stay silent (a sharp threshold on the octahedron, and
// every restricted triangle of a denser sample of the sphere), and DelMesh runs with it: the
// driver runs it and counts it in the statistics, the output keeps Theorem 6.1 and the
// certificate (which runs the topology rows only) certifies it.

#include <cmath>
#include <string>
#include <vector>

#include <boost/test/unit_test.hpp>

#include "meshing/checks/check_registry.h"
#include "meshing/checks/quality.h"
#include "meshing/core/detail/vec3.h"
#include "meshing/driver/del_mesh.h"
#include "meshing/verify/certificate.h"
#include "symbolic/catalog.h"
#include "tests/meshing/check_fixture.h"

using namespace delmesh;
using delmesh::test::CheckFixture;

namespace {

const CheckInfo& row() { return find_check("sizing_field"); }

// The example's field, restated: 2 % of the box diagonal on the mid-plane, growing by half the
// distance from it.
double field(const Vec3& x, const Box3& box) {
  return 0.02 * box.diagonal() + 0.5 * std::abs(x[2] - 0.5 * (box.lo[2] + box.hi[2]));
}

CheckResult run_check(CheckFixture& f, const TriangleKey& t) {
  const CheckContext context{f.restricted, row().kind, 0.06, std::nullopt, std::nullopt, nullptr, true};
  return row().check(context, t);
}

const std::vector<Vec3> octahedron{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};

// n points spread over the unit sphere (the Fibonacci lattice).
std::vector<Vec3> fibonacci_sphere(int n) {
  std::vector<Vec3> points;
  const double golden = M_PI * (3 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1 - (2 * i + 1.0) / n, rho = std::sqrt(1 - z * z);
    points.push_back({rho * std::cos(golden * i), rho * std::sin(golden * i), z});
  }
  return points;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(sizing_field_check)

BOOST_AUTO_TEST_CASE(row_is_registered_after_the_paper_checks) {
  const auto& rows = check_registry();
  BOOST_TEST(rows.size() == builtin_checks().size() + 1);
  BOOST_TEST(rows.back().name == "sizing_field");
  BOOST_TEST(static_cast<int>(row().kind) == static_cast<int>(CheckKind::distance) + 1);
  BOOST_TEST(check_kind_name(row().kind) == "sizing_field");
  BOOST_TEST(check_kind_count() == static_cast<int>(CheckKind::distance) + 2);
  BOOST_TEST((row().face == FaceKind::triangle));
  BOOST_TEST((row().dirtied == Dirtied::restricted_triangles));
  BOOST_TEST((row().phase == CheckPhase::geometry));
}

// The octahedron's eight hull faces are Tri S|Σ of the unit sphere; each one's surface Delaunay
// ball has centre c = (±1, ±1, ±1)/√3 and radius r = √(2 − 2/√3).  In the cube of half-width w,
// h(c) = 0.04·√3·w + 0.5/√3: the check fires on all eight faces for w just below
// w* = (r − 0.5/√3)/(0.04·√3) and on none just above.
BOOST_AUTO_TEST_CASE(threshold_is_sharp_on_the_octahedron) {
  const double r = std::sqrt(2 - 2 / std::sqrt(3.0));
  const double w_star = (r - 0.5 / std::sqrt(3.0)) / (0.04 * std::sqrt(3.0));
  for (const double w : {w_star * (1 - 1e-6), w_star * (1 + 1e-6)}) {
    CheckFixture f(test::unit_sphere, w, octahedron);
    const auto triangles = f.restricted.triangles();
    BOOST_TEST_REQUIRE(triangles.size() == 8u);
    for (const auto& t : triangles) {
      const CheckResult result = run_check(f, t);
      BOOST_TEST(result.unsettled.empty());
      BOOST_TEST(result.witnesses.size() == (w < w_star ? 1u : 0u), "half-width " << w);
      for (const auto& witness : result.witnesses) {
        BOOST_TEST(std::abs(std::abs(witness.point[2]) - 1 / std::sqrt(3.0)) < 1e-9);
        BOOST_TEST(std::abs(detail::distance(witness.point, f.del.point(t[0])) - r) < 1e-9);
      }
    }
  }
}

// 300 points of the sphere in the cube [-1.5, 1.5]³: h is 0.104 on the equator and the balls have
// radius ≈ 0.1, so the check fires near the equator and not near the poles.  On every Delaunay
// triangle it fires exactly when the triangle is restricted and r > h(c), with c as its witness:
// a point of Σ on the dual edge, at distance r from every sample (the ball is empty).
BOOST_AUTO_TEST_CASE(fires_exactly_where_the_ball_exceeds_the_field) {
  CheckFixture f(test::unit_sphere, 1.5, fibonacci_sphere(300));
  int fired = 0, silent = 0, unrestricted = 0;
  for (const auto& t : f.del.triangles()) {
    const VoronoiEdgeRecord& record = f.restricted.voronoi_edge_record(t);
    const CheckResult result = run_check(f, t);
    BOOST_TEST(result.unsettled.empty());
    if (!record.restricted) {
      BOOST_TEST(result.witnesses.empty());
      ++unrestricted;
      continue;
    }
    const Vec3 c = record.dual_point();
    const double r = detail::distance(c, f.del.point(t[0]));
    const bool must_fire = r > field(c, f.box);
    BOOST_TEST_REQUIRE(result.witnesses.size() == (must_fire ? 1u : 0u),
                       "r " << r << " h " << field(c, f.box) << " at z " << c[2]);
    if (!must_fire) {
      ++silent;
      continue;
    }
    ++fired;
    const Witness& w = result.witnesses.front();
    BOOST_TEST((w.kind == row().kind));
    BOOST_TEST(w.measured_from == t[0]);
    BOOST_TEST(std::abs(f.oracle.E(w.point)) < 1e-9);
    BOOST_TEST(detail::distance(w.point, c) == 0.0);
    BOOST_TEST(f.del.nearest(w.point).second >= r * (1 - 1e-9));
  }
  BOOST_TEST_MESSAGE("fired " << fired << ", silent " << silent << ", not restricted " << unrestricted);
  BOOST_TEST(fired > 0);
  BOOST_TEST(silent > 0);
  BOOST_TEST(unrestricted > 0);
}

// DelMesh on the sphere with the example compiled in: the driver runs the row and counts it under
// its name; every output triangle obeys the field (its circumradius ≤ r ≤ h(c), and |c − g| ≤ r
// for the centroid g inside the ball, so with h 0.5-Lipschitz, circumradius ≤ 2·h(g)); Theorem 6.1
// holds, and the certificate (topology rows only) certifies the output.
BOOST_AUTO_TEST_CASE(del_mesh_runs_the_row_and_keeps_the_guarantees) {
  const CatalogEntry& entry = catalog_entry("sphere");
  DelMeshOptions options;
  options.threads = 1;
  const DelMeshResult result = del_mesh(entry.surface(), entry.box, options);
  const auto& s = result.statistics;
  test::check_theorem_6_1(entry, result, options.lambda);
  BOOST_TEST(s.at("insertions").at("sizing_field").get<std::size_t>() > 0u);
  BOOST_TEST(s.at("checks").at("sizing_field").get<std::size_t>() > 0u);
  BOOST_TEST(s.at("seconds_per_check").contains("sizing_field"));

  std::vector<Point3> points;
  std::vector<std::array<std::size_t, 3>> triangles;
  mesh_to_soup(result.mesh, points, triangles);
  for (const auto& t : triangles) {
    const Vec3 p{points[t[0]].x(), points[t[0]].y(), points[t[0]].z()}, q{points[t[1]].x(), points[t[1]].y(), points[t[1]].z()},
        r{points[t[2]].x(), points[t[2]].y(), points[t[2]].z()};
    const Vec3 g{(p[0] + q[0] + r[0]) / 3, (p[1] + q[1] + r[1]) / 3, (p[2] + q[2] + r[2]) / 3};
    BOOST_TEST(circumradius(p, q, r) <= 2 * field(g, entry.box) + 1e-12);
  }
  const Certificate certificate = certify_mesh(points, triangles, entry.surface(), entry.box);
  BOOST_TEST((certificate.status == CertificateStatus::certified));
  BOOST_TEST(certificate.restricted_matches_mesh);
  BOOST_TEST(!to_json(certificate).at("seconds_per_check").contains("sizing_field"));
}

BOOST_AUTO_TEST_SUITE_END()
