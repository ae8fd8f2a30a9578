#include <boost/test/unit_test.hpp>

#include "meshing/delaunay.h"

using namespace delmesh;

BOOST_AUTO_TEST_SUITE(delaunay)

BOOST_AUTO_TEST_CASE(ids_are_insertion_order_and_never_reused) {
  Delaunay del;
  const auto a = del.insert({0, 0, 0}, true);
  const auto b = del.insert({1, 0, 0}, false);
  BOOST_TEST(*a == 0);
  BOOST_TEST(*b == 1);
  BOOST_TEST(!del.insert({1, 0, 0}, false).has_value());  // duplicate point
  BOOST_TEST(del.is_seed(0));
  BOOST_TEST(!del.is_seed(1));
  del.remove(0);
  BOOST_TEST(!del.contains(0));
  const auto c = del.insert({0, 1, 0}, false);
  BOOST_TEST(*c == 2);
  BOOST_TEST(del.size() == 2u);
}

BOOST_AUTO_TEST_CASE(low_dimensions_have_the_right_simplices) {
  Delaunay del;
  del.insert({0, 0, 0}, false);
  del.insert({1, 0, 0}, false);
  BOOST_TEST(del.dimension() == 1);
  BOOST_TEST(del.triangles().empty());
  BOOST_TEST(del.is_edge({0, 1}));
  del.insert({0, 1, 0}, false);
  del.insert({1, 1.2, 0}, false);  // coplanar: dimension 2, two triangles
  BOOST_TEST(del.dimension() == 2);
  BOOST_TEST(del.triangles().size() == 2u);
  BOOST_TEST(del.incident_triangles(0).size() + del.incident_triangles(3).size() >= 2u);
  del.insert({0.3, 0.3, 1}, false);
  BOOST_TEST(del.dimension() == 3);
  BOOST_TEST(del.is_triangle(make_triangle_key(0, 1, 4)));
}

BOOST_AUTO_TEST_CASE(removal_restores_the_triangulation) {
  Delaunay del;
  for (auto p : std::vector<std::array<double, 3>>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}) del.insert(p, false);
  const auto before = del.triangles();
  const auto id = del.insert({0.2, 0.2, 0.2}, true);
  BOOST_TEST(del.neighbours(*id).size() == 4u);
  BOOST_TEST(del.triangles().size() == 10u);  // 4 hull + 6 interior
  del.remove(*id);
  BOOST_TEST((del.triangles() == before));
  BOOST_TEST(del.nearest({0.9, 0.1, 0}).first == 1);
}

BOOST_AUTO_TEST_CASE(keys_are_sorted) {
  BOOST_TEST((make_triangle_key(5, 2, 9) == TriangleKey{2, 5, 9}));
  BOOST_TEST((make_edge_key(7, 3) == EdgeKey{3, 7}));
}

BOOST_AUTO_TEST_SUITE_END()
