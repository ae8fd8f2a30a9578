#include <boost/test/unit_test.hpp>

#include <cmath>

#include "check_fixture.h"
#include "common/tolerances.h"
#include "forwarding_oracle.h"
#include "meshing/checks/facet_cycle.h"
#include "meshing/core/detail/vec3.h"

using namespace delmesh;
using delmesh::test::CheckFixture;

namespace {

// The oracle of a fixture, except that CurveCritical explores nothing: it returns its whole domain
// as one undecided region, as a solve cut short by its box budget or the time limit does.
class BudgetCutOracle final : public test::ForwardingOracle {
 public:
  using ForwardingOracle::ForwardingOracle;
  SolveResult curve_critical(const Vec3&, const Vec3&, const Vec3&, const Domain& domain) override {
    SolveResult cut;
    cut.status = SolveStatus::box_limit;
    cut.undecided.push_back({domain.box, UndecidedReason::budget});
    return cut;
  }
};

// Four small spheres of radius 0.05 centred at (0, ±0.6, 0) and (0, 0, ±0.6): the plane x = 0
// cuts each in a small closed curve, none of them around the middle of the facet below.
const char* four_small_spheres =
    "(x^2+(y-0.6)^2+z^2-0.0025)*(x^2+(y+0.6)^2+z^2-0.0025)*(x^2+y^2+(z-0.6)^2-0.0025)*(x^2+y^2+(z+0.6)^2-0.0025)";

}  // namespace

BOOST_AUTO_TEST_SUITE(facet_cycle)

// The facet x = 0.4 contains the whole circle Σ ∩ {x = 0.4}: a closed curve (Lemma 4.9).
BOOST_AUTO_TEST_CASE(facet_containing_a_closed_curve_fires) {
  CheckFixture f(test::unit_sphere, 1.6, {{0.2, 0, 0}, {0.6, 0, 0}});
  const auto w = facet_cycle_witness(f.restricted, {0, 1});
  BOOST_TEST_REQUIRE(!w.witnesses.empty());
  BOOST_TEST(w.witnesses.front().kind == CheckKind::facet_cycle);
  BOOST_TEST(std::abs(w.witnesses.front().point[0] - 0.4) < 1e-9);
  BOOST_TEST(std::abs(f.oracle.E(w.witnesses.front().point)) < 1e-9);
}

// A closed curve has critical points in every direction: with the alternative frames of the
// driver's retries (attempts 1 and 2) the check still fires, in the same plane, with a witness on
// another line of the facet.
BOOST_AUTO_TEST_CASE(alternative_directions_find_the_closed_curve_too) {
  CheckFixture f(test::unit_sphere, 1.6, {{0.2, 0, 0}, {0.6, 0, 0}});
  const VoronoiFacet& cached = f.restricted.facet({0, 1});
  const Vec3 first = facet_cycle_witness(f.restricted, {0, 1}).witnesses.at(0).point;
  for (int attempt = 1; attempt < tolerances::generic_choice_attempts; ++attempt) {
    const VoronoiFacet rotated = f.restricted.rotated_facet({0, 1}, attempt);
    BOOST_TEST_REQUIRE(rotated.valid);
    BOOST_TEST(detail::distance(rotated.normal, cached.normal) < 1e-15);
    BOOST_TEST(std::abs(detail::dot(rotated.a, cached.a)) < 1 - 1e-6);  // another in-plane direction
    const auto w = facet_cycle_witness(f.restricted, {0, 1}, attempt);
    BOOST_TEST_REQUIRE(!w.witnesses.empty());
    const Vec3 x = w.witnesses.front().point;
    BOOST_TEST(std::abs(x[0] - 0.4) < 1e-9);
    BOOST_TEST(std::abs(f.oracle.E(x)) < 1e-9);
    BOOST_TEST(detail::distance(x, first) > 1e-6);
  }
}

// The facet x = 1.2 misses the sphere.
BOOST_AUTO_TEST_CASE(facet_missing_the_surface_does_not_fire) {
  CheckFixture f(test::unit_sphere, 1.6, {{1.0, 0, 0}, {1.4, 0, 0}});
  BOOST_TEST(facet_cycle_witness(f.restricted, {0, 1}).clean());
}

// Four samples around the x-axis cut the facet x = 0 down to a small square around the origin
// that meets the sphere nowhere... and eight around it make F ∩ Σ open arcs only: the facet
// between (−0.1,0,0) and (0.1,0,0) limited by samples at (0,±1.4,0), (0,0,±1.4) is the square
// |y|, |z| ≤ 0.7 which lies inside the ball: no curve at all.
BOOST_AUTO_TEST_CASE(facet_inside_the_ball_does_not_fire) {
  CheckFixture f(test::unit_sphere, 1.6,
                 {{-0.1, 0, 0}, {0.1, 0, 0}, {0, 1.4, 0}, {0, -1.4, 0}, {0, 0, 1.4}, {0, 0, -1.4}});
  BOOST_TEST(facet_cycle_witness(f.restricted, {0, 1}).clean());
}

// The facet x = 0 between (±0.1, 0, 0) holds four small closed curves of Σ.  The full solve finds
// their critical points and the check fires.  When CurveCritical leaves the whole facet undecided,
// the line through the facet's centre misses every curve (checked below), and the region must then
// be reported unsettled, not taken as clean.
BOOST_AUTO_TEST_CASE(undecided_critical_region_is_unsettled_unless_its_line_gives_a_witness) {
  CheckFixture f(four_small_spheres, 1.6, {{-0.1, 0, 0}, {0.1, 0, 0}});
  BOOST_TEST_REQUIRE(!facet_cycle_witness(f.restricted, {0, 1}).witnesses.empty());

  BudgetCutOracle cut(f.oracle);
  RestrictedDelaunay restricted(f.del, cut, 1);
  const VoronoiFacet& facet = restricted.facet({0, 1});
  BOOST_TEST_REQUIRE(facet.valid);
  const auto& bounds = facet.domain.box.bounds;
  const Vec3 centre = facet.world(0.5 * (bounds[0][0] + bounds[0][1]), 0.5 * (bounds[1][0] + bounds[1][1]));
  // The line through the centre along the facet's first axis passes the circles' centres at more
  // than their radius: it meets Σ ∩ F nowhere.
  for (const Vec3& c : std::vector<Vec3>{{0, 0.6, 0}, {0, -0.6, 0}, {0, 0, 0.6}, {0, 0, -0.6}}) {
    const Vec3 r = detail::operator-(c, centre);
    const double along = detail::dot(r, facet.a);
    BOOST_TEST_REQUIRE(detail::dot(r, r) - along * along > 0.06 * 0.06);
  }
  const auto result = facet_cycle_witness(restricted, {0, 1});
  BOOST_TEST(result.witnesses.empty());
  BOOST_TEST_REQUIRE(result.unsettled.size() == 1u);
  BOOST_TEST(result.unsettled.front().check == CheckKind::facet_cycle);
  BOOST_TEST(result.unsettled.front().reason == UnsettledReason::undecided_critical_region);
  BOOST_TEST(detail::distance(result.unsettled.front().location, centre) < 1e-12);
}

BOOST_AUTO_TEST_SUITE_END()
