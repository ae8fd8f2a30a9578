// Tests of meshing/checks/detail/candidates.h: undecided regions become candidate witnesses or unsettled
// findings, never nothing, and witnesses come furthest from the sample first.
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "check_fixture.h"
#include "meshing/checks/detail/candidates.h"
#include "meshing/core/detail/vec3.h"

using namespace delmesh;
using delmesh::detail::WitnessCollector;
using delmesh::test::CheckFixture;

namespace {

// A square region of half-width r in the facet's plane coordinates, centred at the world point c.
UndecidedBox plane_region(const VoronoiFacet& f, const Vec3& c, double r) {
  const auto uv = f.plane_coordinates(c);
  UndecidedBox u;
  u.box.bounds = {{uv[0] - r, uv[0] + r}, {uv[1] - r, uv[1] + r}};
  u.world = c;
  return u;
}

// The smallest tolerance (to 1e-12) with which the facet contains c's plane coordinates.
double distance_outside(const VoronoiFacet& f, const Vec3& c) {
  const auto uv = f.plane_coordinates(c);
  double lo = 0, hi = 1;
  while (hi - lo > 1e-12) {
    const double mid = 0.5 * (lo + hi);
    (f.contains(uv[0], uv[1], mid) ? hi : lo) = mid;
  }
  return hi;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(candidates)

// The facet x = 0.4 of (0.2,0,0), (0.6,0,0), cut by the sample (0.4,0.9,0): the circle
// Σ ∩ {x = 0.4} (radius √0.84) leaves F near y = √0.84.
struct CutFacet : CheckFixture {
  CutFacet() : CheckFixture(test::unit_sphere, 1.6, {{0.2, 0, 0}, {0.6, 0, 0}, {0.4, 0.9, 0}}) {}
  const VoronoiFacet& facet() { return restricted.facet({0, 1}); }
};

// A region that holds a zero of Σ ∩ F near F's edge: its centre is on Σ just outside F, at a
// distance between 2r (the region's half-diagonal bound of old) and its diameter 2√2·r.  The
// projection can be that far from the zero (candidates.h), so the region is a candidate.
BOOST_FIXTURE_TEST_CASE(region_within_its_diameter_of_the_facet_is_a_candidate, CutFacet) {
  const Vec3 c{0.4, std::sqrt(0.84), 0};
  const double outside = distance_outside(facet(), c);
  BOOST_TEST_REQUIRE(outside > 1e-3);
  const double r = outside / 2.5;
  WitnessCollector collector(CheckKind::facet_contact, 0, del.point(0));
  collector.add_region(oracle, facet(), plane_region(facet(), c, r));
  const CheckResult result = collector.take();
  BOOST_TEST_REQUIRE(result.witnesses.size() == 1u);
  BOOST_TEST(result.unsettled.empty());
  BOOST_TEST(result.witnesses[0].from_undecided);
  BOOST_TEST(std::abs(oracle.E(result.witnesses[0].point)) < 1e-9);
}

// The same point with a region ten times too small for that distance: unsettled, located at the
// region's centre, and no witness.
BOOST_FIXTURE_TEST_CASE(region_projecting_outside_the_facet_is_unsettled, CutFacet) {
  const Vec3 c{0.4, std::sqrt(0.84), 0};
  const double r = distance_outside(facet(), c) / 30;
  WitnessCollector collector(CheckKind::facet_contact, 0, del.point(0));
  collector.add_region(oracle, facet(), plane_region(facet(), c, r));
  const CheckResult result = collector.take();
  BOOST_TEST(result.witnesses.empty());
  BOOST_TEST_REQUIRE(result.unsettled.size() == 1u);
  BOOST_TEST(result.unsettled[0].reason == UnsettledReason::region_outside_face);
  BOOST_TEST(result.unsettled[0].check == CheckKind::facet_contact);
  BOOST_TEST(detail::distance(result.unsettled[0].location, c) == 0.0);
}

// Newton's projection cannot leave the centre of the sphere (∇E = 0 there): the region is
// unsettled, for a facet region, a cell region and a line region alike.
BOOST_FIXTURE_TEST_CASE(unprojectable_region_is_unsettled, CutFacet) {
  BOOST_TEST_REQUIRE(!oracle.project({0, 0, 0}).has_value());
  UndecidedBox u;
  u.box.bounds = {{-0.01, 0.01}, {-0.01, 0.01}, {-0.01, 0.01}};
  u.world = {0, 0, 0};
  const VoronoiCell cell = voronoi_cell(del, 0, box);
  BOOST_TEST_REQUIRE(cell.valid);
  WitnessCollector collector(CheckKind::silhouette, 0, del.point(0));
  collector.add_region(oracle, cell, u);
  collector.add_region(oracle, facet(), plane_region(facet(), {0, 0, 0}, 0.01));
  collector.add_line_region(oracle, u);
  const CheckResult result = collector.take();
  BOOST_TEST(result.witnesses.empty());
  BOOST_TEST_REQUIRE(result.unsettled.size() == 3u);
  for (const auto& x : result.unsettled) BOOST_TEST(x.reason == UnsettledReason::unprojectable_region);
}

// The paper's witness (the furthest from the sample) first, the others after it in decreasing
// distance, ties in the order added.
BOOST_AUTO_TEST_CASE(witnesses_come_furthest_first) {
  WitnessCollector collector(CheckKind::topo_disk, 7, {0, 0, 0});
  collector.add({1, 0, 0});
  collector.add({0, 3, 0}, true);
  collector.add({0, 0, 2});
  collector.add({-1, 0, 0});
  const CheckResult result = collector.take();
  BOOST_TEST_REQUIRE(result.witnesses.size() == 4u);
  const std::vector<double> expected_x{0, 0, 1, -1};
  for (std::size_t i = 0; i < 4; ++i) {
    BOOST_TEST(result.witnesses[i].point[0] == expected_x[i]);
    BOOST_TEST(result.witnesses[i].kind == CheckKind::topo_disk);
    BOOST_TEST(result.witnesses[i].measured_from == 7);
  }
  BOOST_TEST(result.witnesses[0].from_undecided);
  BOOST_TEST(!result.witnesses[1].from_undecided);
}

BOOST_AUTO_TEST_SUITE_END()
