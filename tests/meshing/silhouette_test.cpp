#include <boost/test/unit_test.hpp>

#include <cmath>

#include "check_fixture.h"
#include "common/tolerances.h"
#include "meshing/checks/silhouette.h"
#include "meshing/core/detail/vec3.h"

using namespace delmesh;
using delmesh::test::CheckFixture;

BOOST_AUTO_TEST_SUITE(silhouette)

// One sample on a torus: V_p ∩ Σ is the whole torus (it has a handle) and contains the
// silhouette J_{n_p}: Silhouette must fire (Lemma 4.14) with a point of J_{n_p}.
BOOST_AUTO_TEST_CASE(cell_containing_a_handle_fires) {
  CheckFixture f("(x^2+y^2+z^2+0.84)^2-4*(x^2+y^2)", 1.65, {{1.4, 0, 0}});
  const auto w = silhouette_witness(f.restricted, 0);
  BOOST_TEST_REQUIRE(!w.witnesses.empty());
  BOOST_TEST(w.witnesses.front().kind == CheckKind::silhouette);
  BOOST_TEST(std::abs(f.oracle.E(w.witnesses.front().point)) < 1e-8);
  const auto n = f.oracle.normal({1.4, 0, 0});
  BOOST_TEST(std::abs(detail::dot(f.oracle.normal(w.witnesses.front().point), n)) < 1e-6);  // w ∈ J_{n_p}
}

// The cell's gradient-cone certificate over V_p fails by proving a point of Σ ∩ V_p where
// ⟨∇E, n_p⟩ = 0 (a point of J_{n_p}): Silhouette returns that point and solves nothing; a retry
// (attempt 1) solves the primitives instead.
BOOST_AUTO_TEST_CASE(a_refuted_cell_certificate_gives_the_witness) {
  CheckFixture f("(x^2+y^2+z^2+0.84)^2-4*(x^2+y^2)", 1.65, {{1.4, 0, 0}});
  const auto w = silhouette_witness(f.restricted, 0);
  const auto x = f.restricted.cell_silhouette_point(0);
  BOOST_TEST_REQUIRE(x.has_value());
  BOOST_TEST_REQUIRE(w.witnesses.size() == 1u);
  BOOST_TEST(w.witnesses.front().point == *x);
  const auto n = f.oracle.normal({1.4, 0, 0});
  BOOST_TEST(std::abs(f.oracle.E(*x)) < 1e-12);
  BOOST_TEST(std::abs(detail::dot(f.oracle.gradient(*x), n)) < 1e-12);
  BOOST_TEST(f.box.contains(*x));  // V_p ∩ B is all of B: the only sample
  BOOST_TEST(f.oracle.statistics("silhouette_critical").calls == 0u);
  BOOST_TEST(f.oracle.statistics("silhouette_plane").calls == 0u);
  BOOST_TEST(!silhouette_witness(f.restricted, 0, false, 1).witnesses.empty());
  BOOST_TEST(f.oracle.statistics("silhouette_critical").calls == 1u);
}

// The driver's retries use other directions d′ ⟂ n_p (attempts 1 and 2): each still finds a point
// of J_{n_p} in the cell, and not the same point as the seeded direction.  J_{n_p} on this torus
// is four circles that cross, so the solves also leave undecided regions near the crossings;
// their projections are candidates, points of Σ that need not lie on J_{n_p}.
BOOST_AUTO_TEST_CASE(alternative_directions_give_other_witnesses) {
  CheckFixture f("(x^2+y^2+z^2+0.84)^2-4*(x^2+y^2)", 1.65, {{1.4, 0, 0}});
  const auto n = f.oracle.normal({1.4, 0, 0});
  const Vec3 d0 = silhouette_direction(f.restricted, 0, n);
  const Vec3 first = silhouette_witness(f.restricted, 0).witnesses.at(0).point;
  for (int attempt = 1; attempt < tolerances::generic_choice_attempts; ++attempt) {
    const Vec3 d = silhouette_direction(f.restricted, 0, n, attempt);
    BOOST_TEST(std::abs(detail::norm(d) - 1) < 1e-12);
    BOOST_TEST(std::abs(detail::dot(d, n)) < 1e-12);
    BOOST_TEST(std::abs(detail::dot(d, d0)) < 1 - 1e-6);
    const auto w = silhouette_witness(f.restricted, 0, false, attempt);
    std::size_t roots = 0;
    for (const Witness& witness : w.witnesses) {
      const Vec3& x = witness.point;
      BOOST_TEST(std::abs(f.oracle.E(x)) < 1e-8);
      if (witness.from_undecided) continue;
      ++roots;
      BOOST_TEST(std::abs(detail::dot(f.oracle.normal(x), n)) < 1e-6);  // x ∈ J_{n_p}
      BOOST_TEST(detail::distance(x, first) > 1e-6);
    }
    BOOST_TEST(roots > 0u);
  }
}

// Two samples on the torus on opposite sides: V_p ∩ Σ is half of the torus, which still meets
// the silhouette of n_p.
BOOST_AUTO_TEST_CASE(half_torus_cell_fires) {
  CheckFixture f("(x^2+y^2+z^2+0.84)^2-4*(x^2+y^2)", 1.65, {{1.4, 0, 0}, {-1.4, 0, 0}});
  BOOST_TEST(!silhouette_witness(f.restricted, 0).witnesses.empty());
}

// The octahedron on the sphere: V_p ∩ Σ is a cap around p, far from the silhouette (the great
// circle ⟂ n_p): no witness.
BOOST_AUTO_TEST_CASE(small_cap_does_not_fire) {
  CheckFixture f(test::unit_sphere, 1.5, {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}});
  for (VertexId p = 0; p < 6; ++p) BOOST_TEST(silhouette_witness(f.restricted, p).clean());
}

BOOST_AUTO_TEST_SUITE_END()
