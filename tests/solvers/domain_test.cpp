#include "solvers/domain.h"

#include <cmath>
#include <cstdint>
#include <sstream>
#include <vector>

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

BOOST_AUTO_TEST_CASE(half_space_normals_hold_up_to_three_entries) {
  const HalfSpaceNormal n{0.5, -2, 3};
  BOOST_TEST(n.size() == 3u);
  BOOST_TEST(std::vector<double>(n.begin(), n.end()) == (std::vector<double>{0.5, -2, 3}), boost::test_tools::per_element());
  BOOST_TEST(HalfSpaceNormal{}.empty());
  BOOST_CHECK_THROW((HalfSpaceNormal{1, 2, 3, 4}), PreconditionViolation);
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

// The 70-gon circumscribed about the unit circle (more half-spaces than the mask has bits),
// subdivided as a cone certificate does: at every box the masked classify() answers as the full
// one, and a bit is cleared only for a half-space that strictly contains the box.
BOOST_AUTO_TEST_CASE(masked_classify_answers_as_classify_on_every_sub_box) {
  constexpr int sides = 70;
  Domain d = Domain::from_box({{-1.5, 1.5}, {-1.5, 1.5}});
  for (int i = 0; i < sides; ++i) {
    const double angle = 2 * M_PI * i / sides;
    d.half_spaces.push_back({{std::cos(angle), std::sin(angle)}, 1});
  }
  BOOST_TEST(all_half_spaces_active(d) == ~std::uint64_t{0});
  Domain three = Domain::from_box({{0, 1}, {0, 1}});
  three.half_spaces.assign(3, {{1, 1}, 1});
  BOOST_TEST(all_half_spaces_active(three) == std::uint64_t{7});

  RoundingGuard guard;
  struct Node {
    Interval u[2];
    std::uint64_t active;
    int depth;
  };
  std::vector<Node> stack{{{Interval(-1.5, 1.5), Interval(-1.5, 1.5)}, all_half_spaces_active(d), 0}};
  std::size_t visited = 0, skipped_tests = 0;
  const DomainSide sides_seen[3] = {DomainSide::inside, DomainSide::outside, DomainSide::boundary};
  int seen[3] = {0, 0, 0};
  while (!stack.empty()) {
    Node node = stack.back();
    stack.pop_back();
    ++visited;
    std::uint64_t active = node.active;
    const DomainSide masked = classify(d, node.u, active);
    BOOST_TEST_REQUIRE(masked == classify(d, node.u));
    for (int k = 0; k < 3; ++k) seen[k] += masked == sides_seen[k];
    for (std::size_t i = 0; i < classify_mask_bits; ++i) {
      if (active >> i & 1) continue;
      ++skipped_tests;
      const auto& h = d.half_spaces[i];
      BOOST_TEST_REQUIRE((h.normal[0] * node.u[0] + h.normal[1] * node.u[1] - h.offset).sup() < 0);
    }
    if (masked != DomainSide::boundary || node.depth == 18) continue;
    const int j = node.depth % 2;
    const double mid = 0.5 * (node.u[j].inf() + node.u[j].sup());
    Node left = node, right = node;
    left.u[j] = Interval(node.u[j].inf(), mid);
    right.u[j] = Interval(mid, node.u[j].sup());
    left.active = right.active = active;
    left.depth = right.depth = node.depth + 1;
    stack.push_back(left);
    stack.push_back(right);
  }
  BOOST_TEST(visited > 1000u);
  BOOST_TEST(skipped_tests > 0u);
  BOOST_TEST(seen[0] > 0);
  BOOST_TEST(seen[1] > 0);
  BOOST_TEST(seen[2] > 0);
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
