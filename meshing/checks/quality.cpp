#include "meshing/checks/quality.h"

#include <algorithm>
#include <cmath>

#include "meshing/core/detail/vec3.h"

namespace delmesh {

using namespace detail;

namespace {

//! Lengths below 2^256 and above 2^-256 need no scaling: the products below (of three lengths, of
//! two in the cross product) stay between 2^-768 and 2^768, inside the normal range.
constexpr int unscaled_exponents = 256;

//! The exponent e of the largest coordinate difference among p, q, r, or 0 when it is below
//! unscaled_exponents in magnitude (or the points coincide): the frame is then left as it is.
//! Scaling by 2^-e is exact, so either way the results are the same bits where no product leaves
//! the normal range.
int frame_exponent(const Vec3& p, const Vec3& q, const Vec3& r) {
  double m = 0;
  for (int k = 0; k < 3; ++k) m = std::max({m, std::abs(q[k] - p[k]), std::abs(r[k] - p[k])});
  const int e = m > 0 ? std::ilogb(m) : 0;
  return std::abs(e) < unscaled_exponents ? 0 : e;
}

//! x · 2^-e (exact while the result stays in the normal range).
Vec3 scaled(const Vec3& x, int e) {
  if (e == 0) return x;
  return {std::scalbn(x[0], -e), std::scalbn(x[1], -e), std::scalbn(x[2], -e)};
}

}  // namespace

double circumradius(const Vec3& p, const Vec3& q, const Vec3& r) {
  // In the frame scaled by 2^-e, the lengths are about 1: no product overflows or underflows.
  const int e = frame_exponent(p, q, r);
  const Vec3 u = scaled(q - p, e), v = scaled(r - p, e), w = scaled(r - q, e);
  const double a = norm(w), b = norm(v), c = norm(u);
  const double area2 = norm(cross(u, v));  // twice the area
  if (!(area2 > 0)) return std::numeric_limits<double>::infinity();
  const double radius = a * b * c / (2 * area2);
  return e == 0 ? radius : std::scalbn(radius, e);
}

double radius_edge_ratio(const Vec3& p, const Vec3& q, const Vec3& r) {
  const int e = frame_exponent(p, q, r);
  const Vec3 u = scaled(q - p, e), v = scaled(r - p, e), w = scaled(r - q, e);
  const double a = norm(w), b = norm(v), c = norm(u);
  const double shortest = std::min({a, b, c});
  if (!(shortest > 0)) return std::numeric_limits<double>::infinity();
  const double area2 = norm(cross(u, v));
  if (!(area2 > 0)) return std::numeric_limits<double>::infinity();
  return a * b * c / (2 * area2) / shortest;
}

std::optional<Witness> quality_witness(RestrictedDelaunay& restricted, const TriangleKey& t, double lambda) {
  const auto& rec = restricted.voronoi_edge_record(t);
  if (!rec.restricted) return std::nullopt;
  const auto& del = restricted.delaunay();
  const Vec3 &p = del.point(t[0]), &q = del.point(t[1]), &r = del.point(t[2]);
  if (radius_edge_ratio(p, q, r) <= 1 + lambda) return std::nullopt;
  // The vertex of the shortest edge inserted last (larger id), as in Theorem 6.1's proof.
  const double a = distance(q, r), b = distance(p, r), c = distance(p, q);
  const VertexId from = (c <= a && c <= b) ? t[1] : t[2];
  return Witness{rec.dual_point(), CheckKind::quality, from, false};
}

std::optional<Witness> size_witness(RestrictedDelaunay& restricted, const TriangleKey& t, double size_bound) {
  const auto& rec = restricted.voronoi_edge_record(t);
  if (!rec.restricted) return std::nullopt;
  const auto& del = restricted.delaunay();
  if (distance(rec.dual_point(), del.point(t[0])) <= size_bound) return std::nullopt;
  return Witness{rec.dual_point(), CheckKind::size, t[0], false};
}

std::optional<Witness> distance_witness(RestrictedDelaunay& restricted, const TriangleKey& t, double max_distance,
                                        const FlowDistance& flow_distance) {
  const auto& rec = restricted.voronoi_edge_record(t);
  if (!rec.restricted) return std::nullopt;
  const auto& del = restricted.delaunay();
  if (flow_distance.bound(del.point(t[0]), del.point(t[1]), del.point(t[2]), max_distance).proved) return std::nullopt;
  return Witness{rec.dual_point(), CheckKind::distance, t[0], false};
}

}  // namespace delmesh
