#include <boost/test/unit_test.hpp>

#include <cmath>

#include "check_fixture.h"
#include "common/tolerances.h"
#include "meshing/detail/vec3.h"
#include "meshing/facet_cycle.h"

using namespace delmesh;
using delmesh::test::CheckFixture;

namespace {

// The oracle of a fixture, except that CurveCritical explores nothing: it returns its whole domain
// as one undecided region, as a solve cut short by its box budget or the time limit does.
class BudgetCutOracle final : public SurfaceOracle {
 public:
  explicit BudgetCutOracle(SurfaceOracle& inner) : inner_(inner) {}
  void set_run_controls(std::uint64_t seed, std::optional<std::chrono::steady_clock::time_point> deadline) override {
    inner_.set_run_controls(seed, deadline);
  }
  const Box3& box() const override { return inner_.box(); }
  const Box3& clip_box() const override { return inner_.clip_box(); }
  SolveResult surface_line(const Vec3& p, const Vec3& v, double t0, double t1) override {
    return inner_.surface_line(p, v, t0, t1);
  }
  SolveResult surface_critical(const Vec3& d, const Domain& domain, std::size_t box_budget) override {
    return inner_.surface_critical(d, domain, box_budget);
  }
  SolveResult surface_plane_contact(const Vec3& o, const Vec3& a, const Vec3& b, const Domain& domain) override {
    return inner_.surface_plane_contact(o, a, b, domain);
  }
  SolveResult curve_critical(const Vec3&, const Vec3&, const Vec3&, const Domain& domain) override {
    SolveResult cut;
    cut.status = SolveStatus::box_limit;
    cut.undecided.push_back({domain.box, UndecidedReason::budget});
    return cut;
  }
  SolveResult silhouette_plane(const Vec3& o, const Vec3& a, const Vec3& b, const Vec3& d,
                               const Domain& domain) override {
    return inner_.silhouette_plane(o, a, b, d, domain);
  }
  SolveResult silhouette_critical(const Vec3& d, const Vec3& d2, const Domain& domain) override {
    return inner_.silhouette_critical(d, d2, domain);
  }
  SolveResult solve(const std::string& primitive, const std::vector<double>& parameters, const Domain& domain,
                    std::size_t box_budget) override {
    return inner_.solve(primitive, parameters, domain, box_budget);
  }
  ConeAnswer prove_gradient_cone(const AffineChart& chart, const Domain& domain, const Vec3& w) override {
    return inner_.prove_gradient_cone(chart, domain, w);
  }
  ConeAnswer gradient_cone_slope(const AffineChart& chart, const Domain& domain, const Vec3& w,
                                 double target) override {
    return inner_.gradient_cone_slope(chart, domain, w, target);
  }
  bool bounds_cone_slopes() const override { return inner_.bounds_cone_slopes(); }
  int gradient_sign(const Vec3& a, const Vec3& b, const Vec3& w) const override {
    return inner_.gradient_sign(a, b, w);
  }
  using SurfaceOracle::value_sign;
  int value_sign(const Vec3& lo, const Vec3& hi) const override { return inner_.value_sign(lo, hi); }
  Vec3 gradient(const Vec3& x) const override { return inner_.gradient(x); }
  Vec3 normal(const Vec3& x) const override { return inner_.normal(x); }
  std::optional<Vec3> project(const Vec3& x) const override { return inner_.project(x); }
  nlohmann::json statistics_json() const override { return inner_.statistics_json(); }

 private:
  SurfaceOracle& inner_;
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
