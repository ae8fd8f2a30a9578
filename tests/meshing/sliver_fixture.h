#pragma once
// A sliver: four points within 1e-10 of a plane and nearly on a circle of radius 0.05 in it (the
// plane tilted against the axes, the offsets along its normal of mixed signs), whose circumcentre
// by the formula in doubles is off the exact one by about 5e-9, ten times
// tolerances::face_membership_relative_tolerance · diag for the box [−1.5, 1.5]³; and six
// points 0.2 from the circle's centre along the axes, so that the sliver is a Delaunay cell with
// the four points inside the hull.
#include <array>
#include <vector>

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>

#include "common/vec3.h"

namespace delmesh::test {

inline const double sliver_half_width = 1.5;

//! The four sliver points (ids 0–3 when inserted first) and the six around them (ids 4–9).
inline std::vector<Vec3> sliver_points() {
  const Vec3 centre{0.7123, -0.5177, 0.6419};
  std::vector<Vec3> points{{0.69820430581766169, -0.48795172474351867, 0.60426555401254578},
                           {0.66716347005120635, -0.51461054298483921, 0.6631872947913332},
                           {0.7244887747494263, -0.54725789708043637, 0.680341702489485},
                           {0.75803867716849693, -0.52202801844116142, 0.62217079151995702}};
  for (int k = 0; k < 3; ++k)
    for (double s : {-0.2, 0.2}) {
      Vec3 x = centre;
      x[k] += s;
      points.push_back(x);
    }
  return points;
}

//! The circumcentre of the four points by the formula in doubles, as voronoi_vertex() computes
//! it for cells that are not nearly flat: p + (|a|² b×c + |b|² c×a + |c|² a×b) / (2⟨a, b×c⟩).
inline Vec3 formula_circumcentre(const std::vector<Vec3>& four) {
  auto sub = [](const Vec3& x, const Vec3& y) { return Vec3{x[0] - y[0], x[1] - y[1], x[2] - y[2]}; };
  auto cross = [](const Vec3& x, const Vec3& y) {
    return Vec3{x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]};
  };
  auto dot = [](const Vec3& x, const Vec3& y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; };
  const Vec3 a = sub(four[1], four[0]), b = sub(four[2], four[0]), c = sub(four[3], four[0]);
  const Vec3 bc = cross(b, c), ca = cross(c, a), ab = cross(a, b);
  const double d = 2 * dot(a, bc);
  const double aa = dot(a, a), bb = dot(b, b), cc = dot(c, c);
  Vec3 x{};
  for (int k = 0; k < 3; ++k) x[k] = four[0][k] + (1.0 / d) * (aa * bc[k] + bb * ca[k] + cc * ab[k]);
  return x;
}

//! Whether |x − c*| ≤ radius for the exact circumcentre c* of the four points (exact arithmetic).
inline bool exact_circumcentre_within(const std::vector<Vec3>& four, const Vec3& x, double radius) {
  using Exact = CGAL::Exact_predicates_exact_constructions_kernel;
  auto point = [](const Vec3& y) { return Exact::Point_3(y[0], y[1], y[2]); };
  const Exact::Point_3 star = CGAL::circumcenter(point(four[0]), point(four[1]), point(four[2]), point(four[3]));
  return CGAL::squared_distance(point(x), star) <= Exact::FT(radius) * Exact::FT(radius);
}

//! Whether the exact circumcentre of the four points lies in the box {[lo_k, hi_k]} (exactly).
inline bool exact_circumcentre_in_box(const std::vector<Vec3>& four, const std::vector<std::array<double, 2>>& bounds) {
  using Exact = CGAL::Exact_predicates_exact_constructions_kernel;
  auto point = [](const Vec3& y) { return Exact::Point_3(y[0], y[1], y[2]); };
  const Exact::Point_3 star = CGAL::circumcenter(point(four[0]), point(four[1]), point(four[2]), point(four[3]));
  for (int k = 0; k < 3; ++k)
    if (star[k] < bounds[k][0] || star[k] > bounds[k][1]) return false;
  return true;
}

}  // namespace delmesh::test
