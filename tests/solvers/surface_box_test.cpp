// Tests of the proved bounding box of a surface in a box (solvers/surface_box.h).
#include "solvers/surface_box.h"

#include <cmath>

#include <boost/test/unit_test.hpp>

#include "common/errors.h"
#include "symbolic/surface.h"

using namespace delmesh;

namespace {

CompiledSystem compiled(const GiNaC::ex& E) {
  return CompiledSystem({E}, {coordinate_x(), coordinate_y(), coordinate_z()}, {});
}

// Whether b holds the box [lo, hi] and exceeds it by at most `slack` on every side.
void check_tight(const Box3& b, const std::array<double, 3>& lo, const std::array<double, 3>& hi, double slack) {
  for (int k = 0; k < 3; ++k) {
    BOOST_TEST(b.lo[k] <= lo[k]);
    BOOST_TEST(b.hi[k] >= hi[k]);
    BOOST_TEST(b.lo[k] >= lo[k] - slack);
    BOOST_TEST(b.hi[k] <= hi[k] + slack);
  }
}

}  // namespace

BOOST_AUTO_TEST_SUITE(surface_box)

BOOST_AUTO_TEST_CASE(an_ellipsoid_is_held_and_bounded_to_the_resolution) {
  // x²/4 + y² + 4z² = 1: the extents are ±2, ±1, ±1/2, reached at the axes' ends.
  const GiNaC::symbol &x = coordinate_x(), &y = coordinate_y(), &z = coordinate_z();
  const auto E = compiled(x * x / 4 + y * y + 4 * z * z - 1);
  const Box3 B = Box3::cube(3);
  SurfaceBoxOptions options;
  options.resolution = 1.0 / 256;
  const SurfaceBox r = surface_bounding_box(E, B, options);
  BOOST_TEST(!r.empty);
  // A box narrower than resolution · 6 along the side, and the enclosures' overestimation on it.
  check_tight(r.box, {-2, -1, -0.5}, {2, 1, 0.5}, 0.1);
  BOOST_TEST(r.evaluations > 0u);
}

BOOST_AUTO_TEST_CASE(the_catalog_genus_2_surface_is_flat_in_its_box) {
  // (x² − x⁴ − y²)² + z² = 1/50 has |z| ≤ √(1/50) ≈ 0.1414, attained on the curve x² − x⁴ = y²,
  // in the box [−1.3, 1.3] × [−0.9, 0.9] × [−0.4, 0.4].
  const GiNaC::symbol &x = coordinate_x(), &y = coordinate_y(), &z = coordinate_z();
  const GiNaC::ex g = x * x - GiNaC::pow(x, 4) - y * y;
  const auto E = compiled(g * g + z * z - GiNaC::numeric(1, 50));
  Box3 B;
  B.lo = {-1.3, -0.9, -0.4};
  B.hi = {1.3, 0.9, 0.4};
  const SurfaceBox r = surface_bounding_box(E, B);
  BOOST_TEST(!r.empty);
  const double zmax = std::sqrt(1.0 / 50);
  BOOST_TEST(r.box.hi[2] >= zmax);
  BOOST_TEST(r.box.lo[2] <= -zmax);
  BOOST_TEST(r.box.hi[2] < 0.2);
  BOOST_TEST(r.box.lo[2] > -0.2);
  // x reaches ±√((1 + √(1 + 4·0.1414))/2) ≈ ±1.061 (where y = 0 and g = −√(1/50)).
  BOOST_TEST(r.box.hi[0] >= 1.06);
  BOOST_TEST(r.box.hi[0] < 1.2);
}

BOOST_AUTO_TEST_CASE(a_surface_outside_the_box_is_proved_absent) {
  // The unit sphere about (10, 0, 0) misses the cube [−1, 1]³.
  const GiNaC::symbol &x = coordinate_x(), &y = coordinate_y(), &z = coordinate_z();
  const auto E = compiled((x - 10) * (x - 10) + y * y + z * z - 1);
  const SurfaceBox r = surface_bounding_box(E, Box3::cube(1));
  BOOST_TEST(r.empty);
}

BOOST_AUTO_TEST_CASE(a_spent_budget_still_gives_a_bound_that_holds) {
  // With one box per side the bound is B's side or a half's: never inside the sphere's extent.
  const GiNaC::symbol &x = coordinate_x(), &y = coordinate_y(), &z = coordinate_z();
  const auto E = compiled(x * x + y * y + z * z - 1);
  for (std::size_t budget : {1u, 2u, 5u, 40u}) {
    SurfaceBoxOptions options;
    options.evaluations_per_side = budget;
    const SurfaceBox r = surface_bounding_box(E, Box3::cube(4), options);
    BOOST_TEST(!r.empty);
    check_tight(r.box, {-1, -1, -1}, {1, 1, 1}, 3.0);
    BOOST_TEST(r.evaluations <= 6 * budget);
  }
}

BOOST_AUTO_TEST_CASE(misuse_throws) {
  const GiNaC::symbol &x = coordinate_x(), &y = coordinate_y(), &z = coordinate_z();
  const auto E = compiled(x * x + y * y + z * z - 1);
  SurfaceBoxOptions zero_resolution;
  zero_resolution.resolution = 0;
  BOOST_CHECK_THROW(surface_bounding_box(E, Box3::cube(2), zero_resolution), PreconditionViolation);
  SurfaceBoxOptions no_budget;
  no_budget.evaluations_per_side = 0;
  BOOST_CHECK_THROW(surface_bounding_box(E, Box3::cube(2), no_budget), PreconditionViolation);
  const CompiledSystem two({x, y}, {x, y, z}, {});
  BOOST_CHECK_THROW(surface_bounding_box(two, Box3::cube(2)), PreconditionViolation);
}

BOOST_AUTO_TEST_SUITE_END()
