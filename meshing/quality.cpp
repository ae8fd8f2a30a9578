#include "meshing/quality.h"

#include <algorithm>
#include <cmath>

#include "meshing/detail/vec3.h"

namespace delmesh {

using namespace detail;

double circumradius(const Vec3& p, const Vec3& q, const Vec3& r) {
  const double a = distance(q, r), b = distance(p, r), c = distance(p, q);
  const double area2 = norm(cross(q - p, r - p));  // twice the area
  if (!(area2 > 0)) return std::numeric_limits<double>::infinity();
  return a * b * c / (2 * area2);
}

double radius_edge_ratio(const Vec3& p, const Vec3& q, const Vec3& r) {
  const double shortest = std::min({distance(q, r), distance(p, r), distance(p, q)});
  if (!(shortest > 0)) return std::numeric_limits<double>::infinity();
  return circumradius(p, q, r) / shortest;
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

}  // namespace delmesh
