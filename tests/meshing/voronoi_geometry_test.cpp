#include <boost/test/unit_test.hpp>

#include <cmath>

#include "meshing/voronoi_geometry.h"

using namespace delmesh;

BOOST_AUTO_TEST_SUITE(voronoi_geometry)

BOOST_AUTO_TEST_CASE(edge_of_a_hull_triangle_is_a_ray_clipped_by_the_box) {
  Delaunay del;
  for (auto p : std::vector<Vec3>{{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, 0, -1}}) del.insert(p, false);
  const auto e = voronoi_edge(del, {0, 1, 2}, Box3::cube(2));
  BOOST_TEST_REQUIRE(e.valid);
  // The circumcentre of the tetrahedron is the origin; the ray goes to +z up to the box.
  const Vec3 lo = e.at(e.t0), hi = e.at(e.t1);
  const Vec3 top = lo[2] > hi[2] ? lo : hi;
  const Vec3 bottom = lo[2] > hi[2] ? hi : lo;
  BOOST_TEST(std::abs(bottom[2]) < 1e-12);
  BOOST_TEST(std::abs(top[2] - 2) < 1e-12);
  BOOST_TEST((e.at_vertex0 != e.at_vertex1));
}

BOOST_AUTO_TEST_CASE(edge_in_dimension_two_is_a_full_line) {
  Delaunay del;
  for (auto p : std::vector<Vec3>{{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}}) del.insert(p, false);
  const auto e = voronoi_edge(del, {0, 1, 2}, Box3::cube(2));
  BOOST_TEST_REQUIRE(e.valid);
  BOOST_TEST(!e.at_vertex0);
  BOOST_TEST(!e.at_vertex1);
  BOOST_TEST(std::abs(e.t1 - e.t0 - 4) < 1e-12);
}

BOOST_AUTO_TEST_CASE(facet_is_the_bisector_polygon) {
  Delaunay del;
  del.insert({-1, 0, 0}, false);
  del.insert({1, 0, 0}, false);
  const auto f = voronoi_facet(del, {0, 1}, Box3::cube(2), 0.3);
  BOOST_TEST_REQUIRE(f.valid);
  BOOST_TEST(std::abs(f.origin[0]) < 1e-12);
  BOOST_TEST(std::abs(std::abs(f.normal[0]) - 1) < 1e-12);
  // The polygon is the square x = 0 of the box: area 16.
  double area = 0;
  for (std::size_t i = 0; i < f.polygon.size(); ++i) {
    const auto& a = f.polygon[i];
    const auto& b = f.polygon[(i + 1) % f.polygon.size()];
    area += 0.5 * (a[0] * b[1] - a[1] * b[0]);
  }
  BOOST_TEST(std::abs(area - 16) < 1e-9);
  const auto uv = f.plane_coordinates({0, 1.9, -1.9});
  BOOST_TEST(f.contains(uv[0], uv[1], 1e-9));
  const auto out = f.plane_coordinates({0, 2.1, 0});
  BOOST_TEST(!f.contains(out[0], out[1], 1e-9));
}

BOOST_AUTO_TEST_CASE(cell_is_clipped_by_bisectors) {
  Delaunay del;
  for (auto p : std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}})
    del.insert(p, false);
  const auto c = voronoi_cell(del, 0, Box3::cube(2));
  BOOST_TEST_REQUIRE(c.valid);
  BOOST_TEST(c.facet_neighbours.size() == 6u);
  for (int k = 0; k < 3; ++k) {
    BOOST_TEST(std::abs(c.domain.box.bounds[k][0] + 0.5) < 1e-12);
    BOOST_TEST(std::abs(c.domain.box.bounds[k][1] - 0.5) < 1e-12);
  }
  BOOST_TEST(c.contains({0.4, -0.4, 0.4}, 1e-12));
  BOOST_TEST(!c.contains({0.6, 0, 0}, 1e-12));
  // An unbounded cell is clipped by the box.
  const auto outer = voronoi_cell(del, 1, Box3::cube(2));
  BOOST_TEST(std::abs(outer.domain.box.bounds[0][1] - 2) < 1e-12);
}

BOOST_AUTO_TEST_SUITE_END()
