#include "solvers/domain.h"

#include <sstream>

#include <boost/test/unit_test.hpp>

#include "common/errors.h"

using namespace delmesh;

BOOST_AUTO_TEST_SUITE(domain)

BOOST_AUTO_TEST_CASE(from_box_validates) {
  const Domain d = Domain::from_box({{0, 1}, {-2, 2}});
  BOOST_TEST(d.dimension() == 2u);
  BOOST_TEST(d.scale() == 4.0);
  BOOST_CHECK_THROW(Domain::from_box({{1, 0}}), PreconditionViolation);
  BOOST_CHECK_THROW(Domain::from_box({}), PreconditionViolation);
  BOOST_CHECK_THROW(Domain::from_box({{0, std::numeric_limits<double>::infinity()}}), PreconditionViolation);
  Domain bad = Domain::from_box({{0, 1}, {0, 1}});
  bad.half_spaces.push_back({{1, 0, 0}, 0});
  BOOST_CHECK_THROW(bad.validate(), PreconditionViolation);
  bad.half_spaces.back() = {{0, 0}, 1};
  BOOST_CHECK_THROW(bad.validate(), PreconditionViolation);
}

BOOST_AUTO_TEST_CASE(classify_against_box_faces_and_half_spaces) {
  // The triangle u ≥ 0, v ≥ 0, u + v ≤ 1 as the unit box cut by one half-space.
  Domain d = Domain::from_box({{0, 1}, {0, 1}});
  d.half_spaces.push_back({{1, 1}, 1});
  RoundingGuard guard;
  const Interval inside[2] = {Interval(0.2, 0.3), Interval(0.2, 0.3)};
  const Interval beyond_diagonal[2] = {Interval(0.6, 0.7), Interval(0.6, 0.7)};
  const Interval on_diagonal[2] = {Interval(0.5), Interval(0.5)};
  const Interval on_face[2] = {Interval(0.0), Interval(0.5)};
  const Interval outside_box[2] = {Interval(1.5, 2), Interval(0.1, 0.2)};
  BOOST_TEST(classify(d, inside) == DomainSide::inside);
  BOOST_TEST(classify(d, beyond_diagonal) == DomainSide::outside);
  BOOST_TEST(classify(d, on_diagonal) == DomainSide::boundary);
  BOOST_TEST(classify(d, on_face) == DomainSide::boundary);
  BOOST_TEST(classify(d, outside_box) == DomainSide::outside);
  std::ostringstream out;
  out << DomainSide::inside << ' ' << DomainSide::outside << ' ' << DomainSide::boundary;
  BOOST_TEST(out.str() == "inside outside boundary");
}

BOOST_AUTO_TEST_CASE(status_and_reason_print) {
  std::ostringstream out;
  out << SolveStatus::complete << ' ' << SolveStatus::non_isolated << ' ' << UndecidedReason::singular_root << ' '
      << UndecidedReason::boundary_root;
  BOOST_TEST(out.str() == "complete non_isolated singular_root boundary_root");
  SolverCounters a, b;
  a.boxes = 3, b.boxes = 4, b.roots_outside = 2, b.seconds = 0.5;
  a += b;
  BOOST_TEST(a.boxes == 7u);
  BOOST_TEST(a.roots_outside == 2u);
  BOOST_TEST(a.seconds == 0.5);
}

BOOST_AUTO_TEST_SUITE_END()
