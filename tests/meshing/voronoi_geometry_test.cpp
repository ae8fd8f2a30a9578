#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>

#include "common/tolerances.h"
#include "meshing/core/detail/vec3.h"
#include "meshing/voronoi/detail/convex_polytope.h"
#include "meshing/voronoi/restricted_delaunay.h"
#include "meshing/voronoi/voronoi_geometry.h"
#include "sliver_fixture.h"

using namespace delmesh;

BOOST_AUTO_TEST_SUITE(voronoi_geometry)

namespace {

//! The i-th point of the seeded cloud `seed` in [−1, 1]³.
Vec3 cloud_point(std::uint64_t seed, int i) {
  return {2 * seeded_uniform(seed, i, 0) - 1, 2 * seeded_uniform(seed, i, 1) - 1, 2 * seeded_uniform(seed, i, 2) - 1};
}

}  // namespace

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

// The kept Voronoi vertices belong to their triangulation: two triangulations with the same ids
// at different points, asked in turn (and one of them after a move), get their own circumcentres.
BOOST_AUTO_TEST_CASE(voronoi_vertex_is_the_circumcentre_in_each_triangulation) {
  Delaunay a, b;
  BOOST_TEST(a.serial() != b.serial());
  // Both regular tetrahedra inscribed in spheres about (0, 0, 0) and (3, 5, 7).
  const std::vector<Vec3> corners{{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  for (const Vec3& p : corners) {
    a.insert(p, false);
    b.insert({p[0] + 3, p[1] + 5, p[2] + 7}, false);
  }
  for (int round = 0; round < 3; ++round) {
    BOOST_TEST(detail::norm(voronoi_vertex(a, {0, 1, 2, 3})) == 0.0);
    BOOST_TEST(detail::distance(voronoi_vertex(b, {3, 2, 1, 0}), Vec3{3, 5, 7}) == 0.0);
  }
  const std::uint64_t serial = b.serial();
  Delaunay moved = std::move(b);
  BOOST_TEST(moved.serial() == serial);
  BOOST_TEST(detail::distance(voronoi_vertex(moved, {0, 1, 2, 3}), Vec3{3, 5, 7}) == 0.0);
  BOOST_TEST(Delaunay().serial() != a.serial());
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
  // The cell is the cube [−1/2, 1/2]³; its box is that of its vertices, enlarged by the margin
  // for their rounding.
  const double margin = tolerances::face_membership_relative_tolerance * Box3::cube(2).diagonal();
  for (int k = 0; k < 3; ++k) {
    BOOST_TEST(c.domain.box.bounds[k][0] <= -0.5);
    BOOST_TEST(c.domain.box.bounds[k][0] >= -0.5 - 2 * margin);
    BOOST_TEST(c.domain.box.bounds[k][1] >= 0.5);
    BOOST_TEST(c.domain.box.bounds[k][1] <= 0.5 + 2 * margin);
  }
  BOOST_TEST(c.contains({0.4, -0.4, 0.4}, 1e-12));
  BOOST_TEST(!c.contains({0.6, 0, 0}, 1e-12));
  // An unbounded cell is clipped by the box.
  const auto outer = voronoi_cell(del, 1, Box3::cube(2));
  BOOST_TEST(std::abs(outer.domain.box.bounds[0][1] - 2) < 1e-12);
}

// A cell's domain is V_p: on a seeded cloud, points whose nearest site is p (by brute force) lie
// in p's domain box and half-spaces, and points nearer to another site violate a half-space;
// bounded cells (built from their vertices) and unbounded ones (read off the Delaunay dual) alike.
BOOST_AUTO_TEST_CASE(cell_domain_is_the_voronoi_cell) {
  Delaunay del;
  std::vector<Vec3> sites;
  for (int i = 0; i < 60; ++i) {
    const Vec3 x = cloud_point(5, i);
    sites.push_back(x);
    del.insert(x, false);
  }
  const Box3 box = Box3::cube(1.5);
  auto nearest = [&](const Vec3& y) {
    VertexId best = 0;
    for (VertexId s = 1; s < static_cast<VertexId>(sites.size()); ++s)
      if (detail::distance(y, sites[s]) < detail::distance(y, sites[best])) best = s;
    return best;
  };
  int inside = 0, outside = 0;
  for (VertexId p = 0; p < static_cast<VertexId>(sites.size()); ++p) {
    const auto cell = voronoi_cell(del, p, box);
    BOOST_TEST_REQUIRE(cell.valid);
    for (int k = 0; k < 200; ++k) {
      Vec3 y;
      for (int c = 0; c < 3; ++c) y[c] = sites[p][c] + 0.6 * (2 * seeded_uniform(9, p, k, c) - 1);
      if (!box.contains(y)) continue;
      const bool in_cell = nearest(y) == p;
      BOOST_TEST(cell.contains(y, 1e-12) == in_cell);
      (in_cell ? inside : outside)++;
    }
  }
  BOOST_TEST(inside > 1000);
  BOOST_TEST(outside > 1000);
}

// An unbounded cell's box, read off the Delaunay dual, is the bounding box of V_p ∩ B (computed
// here by clipping B with every bisector) up to the rounding margin: it holds that box and
// exceeds it by at most twice the margin on each side.  The cloud's hull vertices have unbounded
// cells, and the box cuts through them.
BOOST_AUTO_TEST_CASE(unbounded_cell_box_is_the_box_of_the_clipped_cell) {
  Delaunay del;
  for (int i = 0; i < 80; ++i) del.insert(cloud_point(13, i), false);
  const Box3 box = Box3::cube(1.25);
  const double margin = tolerances::face_membership_relative_tolerance * box.diagonal();
  int unbounded = 0;
  for (VertexId p : del.vertices()) {
    const auto cells = del.incident_cells(p);
    if (std::all_of(cells.begin(), cells.end(), [](const auto& c) { return c[1] >= 0 && c[2] >= 0 && c[3] >= 0; }))
      continue;
    ++unbounded;
    detail::ConvexPolytope polytope;
    polytope.reset(box);
    for (VertexId q : del.neighbours(p)) {
      using detail::operator-, detail::operator+, detail::operator*;
      const Vec3 w = del.point(q) - del.point(p);
      polytope.clip(w, detail::dot(w, 0.5 * (del.point(q) + del.point(p))), q);
    }
    BOOST_TEST_REQUIRE(!polytope.empty());
    const auto exact = polytope.bounding_box();
    const auto cell = voronoi_cell(del, p, box);
    BOOST_TEST_REQUIRE(cell.valid);
    BOOST_TEST(cell.facet_neighbours == del.neighbours(p));
    for (int k = 0; k < 3; ++k) {
      const auto& b = cell.domain.box.bounds[k];
      BOOST_TEST(b[0] <= exact[0][k] + 1e-12);
      BOOST_TEST(b[0] >= exact[0][k] - 2 * margin - 1e-12);
      BOOST_TEST(b[1] >= exact[1][k] - 1e-12);
      BOOST_TEST(b[1] <= exact[1][k] + 2 * margin + 1e-12);
    }
  }
  BOOST_TEST(unbounded > 20);
}

// One diagram: every Voronoi vertex (voronoi_vertex of a finite cell) is the end of each of its
// four edges, to the bit, and lies in each of its six facets and four cells with no tolerance;
// a facet built from a given ring is the facet built by looking the ring up.
BOOST_AUTO_TEST_CASE(faces_share_their_voronoi_vertices) {
  Delaunay del;
  for (int i = 0; i < 80; ++i) del.insert(cloud_point(11, i), false);
  const Box3 box = Box3::cube(1.5);
  int vertices = 0, edge_ends = 0, facets = 0, cells = 0;
  for (VertexId x : del.vertices()) {
    for (const auto& c : del.incident_cells(x)) {
      if (c[1] < 0 || c[2] < 0 || c[3] < 0 || c[0] != *std::min_element(c.begin(), c.end())) continue;
      const Vec3 v = voronoi_vertex(del, c);
      if (!box.contains(v)) continue;
      ++vertices;
      for (int skip = 0; skip < 4; ++skip) {
        std::array<VertexId, 3> t{};
        for (int k = 0, j = 0; k < 4; ++k)
          if (k != skip) t[j++] = c[k];
        const auto e = voronoi_edge(del, make_triangle_key(t[0], t[1], t[2]), box);
        if (!e.valid) continue;
        const auto ends = voronoi_edge_ends(del, e);
        BOOST_TEST(((e.at_vertex0 && ends[0] == v) || (e.at_vertex1 && ends[1] == v)));
        ++edge_ends;
      }
      for (int i = 0; i < 4; ++i) {
        for (int j = i + 1; j < 4; ++j) {
          const EdgeKey pq = make_edge_key(c[i], c[j]);
          const auto f = voronoi_facet(del, pq, box, 0.7);
          if (!f.valid) continue;
          const auto uv = f.plane_coordinates(v);
          BOOST_TEST(f.contains(uv[0], uv[1], 0.0));
          for (int k = 0; k < 2; ++k)
            BOOST_TEST((uv[k] >= f.domain.box.bounds[k][0] && uv[k] <= f.domain.box.bounds[k][1]));
          const auto ring = del.edge_ring(pq);
          const auto g = voronoi_facet(del, pq, box, 0.7, &ring);
          BOOST_TEST((g.polygon == f.polygon));
          ++facets;
        }
        const auto cell = voronoi_cell(del, c[i], box);
        if (!cell.valid) continue;
        BOOST_TEST(cell.contains(v, 0.0));
        ++cells;
      }
    }
  }
  BOOST_TEST(vertices > 50);
  BOOST_TEST(edge_ends > 150);
  BOOST_TEST(facets > 200);
  BOOST_TEST(cells > 150);
}

// The error radius of a Voronoi vertex encloses the exact circumcentre: for a regular
// tetrahedron it is a few units in the last place.  A sliver whose circumcentre by the formula in
// doubles is off by more than the membership margin (so that no constant margin covers it) gets
// its Voronoi vertex constructed exactly: within the margin of the exact point, and its radius
// encloses that point.  The centre is voronoi_vertex()'s, bit for bit.  The cells of the sliver's
// sites hold the exact circumcentre in their box.
BOOST_AUTO_TEST_CASE(certified_voronoi_vertex_encloses_the_exact_circumcentre) {
  Delaunay regular;
  const std::vector<Vec3> corners{{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  for (const Vec3& p : corners) regular.insert({p[0] + 0.1, p[1] - 0.3, p[2] + 0.7}, false);
  const VoronoiVertex v = certified_voronoi_vertex(regular, {0, 1, 2, 3});
  BOOST_TEST(v.radius < 1e-14);
  BOOST_TEST(detail::distance(v.centre, Vec3{0.1, -0.3, 0.7}) <= v.radius);

  const std::vector<Vec3> points = test::sliver_points();
  const std::vector<Vec3> four(points.begin(), points.begin() + 4);
  Delaunay del;
  for (const Vec3& p : points) del.insert(p, false);
  const double margin =
      tolerances::face_membership_relative_tolerance * Box3::cube(test::sliver_half_width).diagonal();
  BOOST_TEST(!test::exact_circumcentre_within(four, test::formula_circumcentre(four), margin));  // the premise
  for (int round = 0; round < 2; ++round) {  // computed, then kept
    const VoronoiVertex s = certified_voronoi_vertex(del, {3, 1, 0, 2});
    BOOST_TEST(s.centre == voronoi_vertex(del, {0, 1, 2, 3}));
    BOOST_TEST(test::exact_circumcentre_within(four, s.centre, s.radius));
    BOOST_TEST(test::exact_circumcentre_within(four, s.centre, margin));
    BOOST_TEST(s.radius <= margin);
  }
  for (VertexId p = 0; p < 4; ++p) {
    const VoronoiCell cell = voronoi_cell(del, p, Box3::cube(test::sliver_half_width));
    BOOST_TEST_REQUIRE(cell.valid);
    BOOST_TEST(test::exact_circumcentre_in_box(four, cell.domain.box.bounds));
  }
}

BOOST_AUTO_TEST_SUITE_END()
