#include <boost/test/unit_test.hpp>

#include <cmath>

#include "meshing/quality.h"

using namespace delmesh;

BOOST_AUTO_TEST_SUITE(quality)

BOOST_AUTO_TEST_CASE(radius_edge_ratio_known_values) {
  // Equilateral: R = a/√3, ratio 1/√3.
  BOOST_TEST(std::abs(radius_edge_ratio({0, 0, 0}, {1, 0, 0}, {0.5, std::sqrt(3.0) / 2, 0}) - 1 / std::sqrt(3.0)) < 1e-12);
  // Right isoceles with legs 1: R = √2/2, shortest edge 1.
  BOOST_TEST(std::abs(radius_edge_ratio({0, 0, 0}, {1, 0, 0}, {0, 1, 0}) - std::sqrt(2.0) / 2) < 1e-12);
  BOOST_TEST(std::abs(circumradius({0, 0, 0}, {2, 0, 0}, {0, 2, 0}) - std::sqrt(2.0)) < 1e-12);
  BOOST_TEST(std::isinf(radius_edge_ratio({0, 0, 0}, {1, 0, 0}, {2, 0, 0})));
}

BOOST_AUTO_TEST_SUITE_END()
