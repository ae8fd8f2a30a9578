#include "solvers/krawczyk.h"

#include <cmath>
#include <sstream>

#include <boost/test/unit_test.hpp>

#include "common/errors.h"
#include "common/tolerances.h"

using namespace delmesh;

namespace {

//! The unit circle and the diagonal: zeros (±1/√2, ±1/√2).
CompiledSystem circle_and_diagonal() {
  GiNaC::symbol x("x"), y("y");
  return CompiledSystem({x * x + y * y - 1, x - y}, {x, y}, {});
}

std::vector<Interval> box2(double x0, double x1, double y0, double y1) { return {Interval(x0, x1), Interval(y0, y1)}; }

}  // namespace

BOOST_AUTO_TEST_SUITE(krawczyk)

BOOST_AUTO_TEST_CASE(unique_root_is_proved_and_contracted) {
  const CompiledSystem system = circle_and_diagonal();
  RoundingGuard guard;
  const double r = std::sqrt(0.5);
  const KrawczykResult result = krawczyk_test(system, {}, box2(0.6, 0.8, 0.65, 0.75));
  BOOST_TEST(result.outcome == KrawczykOutcome::unique_root);
  BOOST_REQUIRE_EQUAL(result.contracted.size(), 2u);
  for (const Interval& side : result.contracted) {
    BOOST_TEST(side.inf() <= r);
    BOOST_TEST(side.sup() >= r);
    BOOST_TEST(side.sup() - side.inf() < 0.02);  // contracted well inside the 0.2 × 0.1 box
  }
}

BOOST_AUTO_TEST_CASE(box_without_root_is_excluded) {
  const CompiledSystem system = circle_and_diagonal();
  RoundingGuard guard;
  // The diagonal does not meet this box: x − y ∈ [0.3, 0.5].
  BOOST_TEST(krawczyk_test(system, {}, box2(0.6, 0.7, 0.2, 0.3)).outcome == KrawczykOutcome::no_root);
  // x − y can vanish here but the circle is not met near (0.1, 0.1): Krawczyk proves it.
  BOOST_TEST(krawczyk_test(system, {}, box2(0.05, 0.15, 0.05, 0.15)).outcome == KrawczykOutcome::no_root);
}

BOOST_AUTO_TEST_CASE(box_with_two_roots_is_inconclusive) {
  const CompiledSystem system = circle_and_diagonal();
  RoundingGuard guard;
  const KrawczykResult result = krawczyk_test(system, {}, box2(-1, 1, -1, 1));
  BOOST_TEST(result.outcome == KrawczykOutcome::inconclusive);
  // The contracted box still contains both zeros.
  BOOST_TEST(result.contracted[0].inf() <= -std::sqrt(0.5));
  BOOST_TEST(result.contracted[0].sup() >= std::sqrt(0.5));
}

BOOST_AUTO_TEST_CASE(singular_midpoint_jacobian_is_inconclusive) {
  // x² = 0, y = 0: J(0, 0) = [[0, 0], [0, 1]] is singular; the double root is never "unique".
  GiNaC::symbol x("x"), y("y");
  const CompiledSystem system({x * x, y}, {x, y}, {});
  RoundingGuard guard;
  const KrawczykResult result = krawczyk_test(system, {}, box2(-1e-3, 1e-3, -1e-3, 1e-3));
  BOOST_TEST(result.outcome == KrawczykOutcome::inconclusive);
}

BOOST_AUTO_TEST_CASE(parameters_are_used) {
  // x² − c = 0 (1-D): root √c for c = 2.
  GiNaC::symbol x("x"), c("c");
  const CompiledSystem system({x * x - c}, {x}, {c});
  RoundingGuard guard;
  const KrawczykResult result = krawczyk_test(system, {2.0}, {Interval(1.3, 1.5)});
  BOOST_TEST(result.outcome == KrawczykOutcome::unique_root);
  BOOST_TEST(result.contracted[0].inf() <= std::sqrt(2.0));
  BOOST_TEST(result.contracted[0].sup() >= std::sqrt(2.0));
  BOOST_TEST(krawczyk_test(system, {3.0}, {Interval(1.3, 1.5)}).outcome == KrawczykOutcome::no_root);
}

BOOST_AUTO_TEST_CASE(mpfi_agrees_and_is_tighter_on_tiny_boxes) {
  const CompiledSystem system = circle_and_diagonal();
  const double r = std::sqrt(0.5);
  for (int bits : tolerances::escalation_precisions) {
    const KrawczykResult unique = krawczyk_test_mpfi(system, {}, box2(0.6, 0.8, 0.65, 0.75), bits);
    BOOST_TEST(unique.outcome == KrawczykOutcome::unique_root);
    BOOST_TEST(unique.contracted[0].inf() <= r);
    BOOST_TEST(unique.contracted[0].sup() >= r);
    BOOST_TEST(krawczyk_test_mpfi(system, {}, box2(0.6, 0.7, 0.2, 0.3), bits).outcome == KrawczykOutcome::no_root);
    BOOST_TEST(krawczyk_test_mpfi(system, {}, box2(-1, 1, -1, 1), bits).outcome == KrawczykOutcome::inconclusive);
  }
}

BOOST_AUTO_TEST_CASE(mpfi_decides_what_double_cancellation_cannot) {
  // (x + c)² − c² − 2 c x − 1/4 = x² − 1/4 with c = 1e8: in double the enclosure of the value at
  // a point is ~1 wide (cancellation of 1e16-sized terms), so Krawczyk cannot prove the root
  // x = 1/2; at 106 bits it can.  This also checks that the MPFI precision reaches the program.
  GiNaC::symbol x("x"), c("c");
  const CompiledSystem system({GiNaC::pow(x + c, 2) - c * c - 2 * c * x - GiNaC::numeric(1, 4)}, {x}, {c});
  const std::vector<Interval> box = {Interval(0.49, 0.51)};
  {
    RoundingGuard guard;
    BOOST_TEST(krawczyk_test(system, {1e8}, box).outcome == KrawczykOutcome::inconclusive);
  }
  const KrawczykResult high = krawczyk_test_mpfi(system, {1e8}, box, 106);
  BOOST_TEST(high.outcome == KrawczykOutcome::unique_root);
  BOOST_TEST(high.contracted[0].inf() <= 0.5);
  BOOST_TEST(high.contracted[0].sup() >= 0.5);
  BOOST_TEST(high.contracted[0].sup() - high.contracted[0].inf() < 1e-3);  // one quadratic step from 0.02
}

BOOST_AUTO_TEST_CASE(misuse_throws_precondition_violation) {
  const CompiledSystem system = circle_and_diagonal();
  RoundingGuard guard;
  BOOST_CHECK_THROW((void)krawczyk_test(system, {}, {Interval(0, 1)}), PreconditionViolation);
  BOOST_CHECK_THROW((void)krawczyk_test(system, {1.0}, box2(0, 1, 0, 1)), PreconditionViolation);
  GiNaC::symbol x("x"), y("y");
  const CompiledSystem overdetermined({x, y, x + y}, {x, y}, {});
  BOOST_CHECK_THROW((void)krawczyk_test(overdetermined, {}, box2(0, 1, 0, 1)), PreconditionViolation);
  BOOST_CHECK_THROW((void)krawczyk_test_mpfi(system, {}, box2(0, 1, 0, 1), 20), PreconditionViolation);
}

BOOST_AUTO_TEST_CASE(outcome_prints) {
  std::ostringstream out;
  out << KrawczykOutcome::unique_root << ' ' << KrawczykOutcome::no_root << ' ' << KrawczykOutcome::inconclusive;
  BOOST_TEST(out.str() == "unique_root no_root inconclusive");
}

BOOST_AUTO_TEST_SUITE_END()
