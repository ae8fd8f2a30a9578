#include <boost/test/unit_test.hpp>

#include <array>
#include <cmath>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "meshing/driver/closed_ball_refinement.h"
#include "meshing/inputs/mesh_oracle.h"

using namespace delmesh;

namespace {

// A PL torus (radii R, r) of n × m quads split into triangles, its vertices jittered in angle
// (seeded) so that no symmetry puts samples in non-generic position.
SurfaceMesh jittered_torus(double R, double r, int n, int m, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> jitter(-0.2, 0.2);
  SurfaceMesh mesh;
  std::vector<SurfaceMesh::Vertex_index> v;
  const double two_pi = 2 * std::acos(-1.0);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const double u = two_pi * (i + jitter(random)) / n, w = two_pi * (j + jitter(random)) / m;
      v.push_back(mesh.add_vertex(Point3((R + r * std::cos(w)) * std::cos(u), (R + r * std::cos(w)) * std::sin(u),
                                         r * std::sin(w))));
    }
  const auto at = [&](int i, int j) { return v[(i % n) * m + (j % m)]; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      mesh.add_face(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      mesh.add_face(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  return mesh;
}

// V − E + F of a set of triangles.
long euler_characteristic(const std::vector<std::array<std::size_t, 3>>& triangles) {
  std::set<std::size_t> vertices;
  std::set<std::pair<std::size_t, std::size_t>> edges;
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k) {
      vertices.insert(t[k]);
      const std::size_t a = t[k], b = t[(k + 1) % 3];
      edges.insert({std::min(a, b), std::max(a, b)});
    }
  return static_cast<long>(vertices.size()) - static_cast<long>(edges.size()) + static_cast<long>(triangles.size());
}

}  // namespace

BOOST_AUTO_TEST_SUITE(closed_ball_refinement)

// Six samples on the outer equator of a PL torus: every cell is an annulus around the tube, so
// the closed-ball check is violated and its witnesses are inserted; the loop (with the
// refinement's checks in between) ends when the property holds, and the output is Del S|Σ of
// a torus (χ = 0), proved homeomorphic to the input: the run is complete.
BOOST_AUTO_TEST_CASE(ring_sample_of_a_torus_is_refined_to_a_torus) {
  const SurfaceMesh sigma = jittered_torus(1.0, 0.4, 12, 6, 7);
  MeshOracle oracle(sigma, Box3::cube(2));
  Refinement refinement(oracle, 1, RefinementLimits{});
  for (int i = 0; i < 12; i += 2) {
    const Point3& p = sigma.point(SurfaceMesh::Vertex_index(static_cast<SurfaceMesh::size_type>(i * 6)));
    BOOST_TEST_REQUIRE(refinement.insert(Witness{{p.x(), p.y(), p.z()}, CheckKind::seed, -1, false}).has_value());
  }
  ClosedBallRefinement record;
  const MeshStatus status = refine_closed_ball(refinement, sigma, MeshStatus::complete, record);
  BOOST_TEST(status == MeshStatus::complete);
  BOOST_TEST(record.rounds >= 1u);
  BOOST_TEST(record.witnesses_inserted >= 1u);
  BOOST_TEST(record.checks == record.rounds + 1);
  BOOST_TEST(record.last_is_current);
  BOOST_TEST(record.last.status == ClosedBallStatus::holds);
  BOOST_TEST(euler_characteristic(record.last.restricted_delaunay) == 0);

  const Certification certification = refinement.certify(status, false);
  const PlStatusDecision decision =
      decide_pl_status(refinement, record, status, certification, false, true, 0.06, false);
  BOOST_TEST(decision.output_equals_restricted_delaunay);
  BOOST_TEST(decision.proves_homeomorphism);
  BOOST_TEST(decision.blocking == 0u);
  BOOST_TEST(decision.status == MeshStatus::complete);
  const nlohmann::json j = closed_ball_refinement_json(record, decision);
  BOOST_TEST(j["rounds"] == record.rounds);
  BOOST_TEST(j["proves_homeomorphism"] == true);

  // A sample inserted after the check (as a later phase would) makes the check stale: nothing is
  // decided from it and the status is certify()'s.
  const Point3& x = sigma.point(SurfaceMesh::Vertex_index(3));
  BOOST_TEST_REQUIRE(refinement.insert(Witness{{x.x(), x.y(), x.z()}, CheckKind::quality, -1, false}).has_value());
  const MeshStatus again = refinement.run();
  const Certification later = refinement.certify(again, false);
  const PlStatusDecision stale = decide_pl_status(refinement, record, again, later, false, true, 0.06, false);
  BOOST_TEST(!stale.check_current);
  BOOST_TEST(!stale.proves_homeomorphism);
  BOOST_TEST(stale.exempt_count == 0u);
  BOOST_TEST(stale.status == later.status);
}

// A run that did not end complete is left alone: no check, no insertion.
BOOST_AUTO_TEST_CASE(a_stopped_run_is_not_refined) {
  const SurfaceMesh sigma = jittered_torus(1.0, 0.4, 12, 6, 7);
  MeshOracle oracle(sigma, Box3::cube(2));
  Refinement refinement(oracle, 1, RefinementLimits{});
  ClosedBallRefinement record;
  BOOST_TEST(refine_closed_ball(refinement, sigma, MeshStatus::time_limit, record) == MeshStatus::time_limit);
  BOOST_TEST(record.checks == 0u);
  BOOST_TEST(!record.last_is_current);
}

BOOST_AUTO_TEST_SUITE_END()
