#include "solvers/detail/mean_value.h"

#include <cmath>

#include <boost/test/unit_test.hpp>

using namespace delmesh;

namespace {

//! The mean-value test of f(x, y) = (x² + y² − 1, x − y) on [x0, x1] × [y0, y1] around its centre,
//! with the exact interval Jacobian (2X, 2Y; 1, −1) over the box.
bool circle_and_diagonal_excluded(double x0, double x1, double y0, double y1, Interval* enclosure) {
  const Interval X(x0, x1), Y(y0, y1);
  const Interval mx((x0 + x1) / 2), my((y0 + y1) / 2);
  const Interval fm[2] = {mx * mx + my * my - Interval(1), mx - my};
  const Interval jx[4] = {Interval(2) * X, Interval(2) * Y, Interval(1), Interval(-1)};
  const Interval offset[2] = {X - mx, Y - my};
  return detail::mean_value_excludes<Interval>(2, 2, fm, jx, offset, enclosure);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(mean_value_test)

BOOST_AUTO_TEST_CASE(a_box_far_from_the_zeros_is_excluded) {
  RoundingGuard guard;
  Interval enclosure[2];
  BOOST_TEST(circle_and_diagonal_excluded(2.0, 2.5, 2.0, 2.5, enclosure));
}

BOOST_AUTO_TEST_CASE(a_box_around_a_zero_is_not_and_its_enclosures_hold_zero) {
  RoundingGuard guard;
  const double r = 1 / std::sqrt(2.0);  // (r, r) solves both equations
  Interval enclosure[2];
  BOOST_TEST(!circle_and_diagonal_excluded(r - 0.01, r + 0.02, r - 0.02, r + 0.01, enclosure));
  for (const Interval& e : enclosure) BOOST_TEST((e.inf() <= 0 && 0 <= e.sup()));
}

BOOST_AUTO_TEST_CASE(the_second_equation_alone_can_exclude) {
  // on the circle's arc but away from the diagonal: x − y ≥ 0.5 on the box
  RoundingGuard guard;
  Interval enclosure[2];
  BOOST_TEST(circle_and_diagonal_excluded(0.95, 1.0, -0.3, 0.0, enclosure));
}

BOOST_AUTO_TEST_SUITE_END()
