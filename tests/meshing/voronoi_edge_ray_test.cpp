#include <boost/test/unit_test.hpp>

#include <array>
#include <cmath>
#include <random>

#include "meshing/core/detail/vec3.h"
#include "meshing/voronoi/delaunay.h"
#include "meshing/voronoi/voronoi_geometry.h"

using namespace delmesh;
using namespace delmesh::detail;

BOOST_AUTO_TEST_SUITE(voronoi_edge_ray)

// Four samples on a tilted plane, rounded to doubles, the fourth inside the circumcircle of the
// other three: Del S is one cell, flat to rounding, whose Voronoi vertex lies far away, and the
// Voronoi edge of the triangle pqr is the ray from that vertex away from the fourth sample s.
// Every point of it is at least as near to p as to s.  The side of s is within rounding of pqr's
// plane, where a dot product in doubles often gets it wrong (then the ray runs back through the
// box); the clipped edge inside the box must hold only points no nearer to s than to p.
BOOST_AUTO_TEST_CASE(ray_of_a_flat_hull_cell_leaves_on_the_exact_side) {
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::size_t examined = 0, wrong = 0;
  for (int attempt = 0; attempt < 2000 && wrong < 20; ++attempt) {
    const Vec3 u = normalized(Vec3{unit(random), unit(random), unit(random)});
    Vec3 w = cross(u, Vec3{unit(random), unit(random), unit(random)});
    w = normalized(w);
    const auto on_plane = [&](double a, double b) { return Vec3{a * u[0] + b * w[0], a * u[1] + b * w[1], a * u[2] + b * w[2]}; };
    const Vec3 p = on_plane(1, 0), q = on_plane(-0.5, 0.8), r = on_plane(-0.5, -0.8), s = on_plane(0.1 * unit(random), 0.1 * unit(random));
    Delaunay del;
    for (const Vec3& x : {p, q, r, s}) (void)del.insert(x, false);
    if (del.dimension() != 3) continue;
    const TriangleKey t{0, 1, 2};
    const auto apexes = del.triangle_apexes(t);
    BOOST_TEST_REQUIRE(apexes.has_value());
    const VoronoiEdge e = voronoi_edge(del, t, Box3::cube(4));
    ++examined;
    const bool double_side = dot(s - p, e.direction) > 0;
    if (!e.valid) continue;
    const Vec3 x = e.at(0.5 * (e.t0 + e.t1));
    const bool nearer_to_s = norm(x - s) < norm(x - p) * (1 - 1e-9);
    if (nearer_to_s) ++wrong;
    BOOST_TEST(!nearer_to_s, "the clipped edge holds a point nearer to s (double side " << double_side << ")");
  }
  BOOST_TEST(examined > 1000u);
  BOOST_TEST(wrong == 0u);
}

BOOST_AUTO_TEST_SUITE_END()
