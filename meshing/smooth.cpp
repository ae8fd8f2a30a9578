#include "meshing/smooth.h"

#include <algorithm>
#include <cmath>

#include "meshing/detail/candidates.h"
#include "meshing/detail/vec3.h"

namespace delmesh {

using namespace detail;

Vec3 outward_normal(RestrictedDelaunay& restricted, const TriangleKey& t) {
  const auto& del = restricted.delaunay();
  const Vec3 &p = del.point(t[0]), &q = del.point(t[1]), &r = del.point(t[2]);
  Vec3 n = normalized(cross(q - p, r - p));
  const auto& rec = restricted.voronoi_edge_record(t);
  if (dot(n, restricted.oracle().gradient(rec.dual_point())) < 0) n = (-1.0) * n;
  return n;
}

std::optional<Witness> smooth_witness(RestrictedDelaunay& restricted, const EdgeKey& pq, double threshold) {
  const auto found = restricted.restricted_pair(pq);
  if (!found) return std::nullopt;
  const auto& pair = *found;
  const Vec3 n1 = outward_normal(restricted, pair[0]), n2 = outward_normal(restricted, pair[1]);
  const double g = std::acos(std::clamp(dot(n1, n2), -1.0, 1.0));
  if (!(g > threshold)) return std::nullopt;
  WitnessCollector collector(CheckKind::smooth, pq[0], restricted.delaunay().point(pq[0]));
  for (const auto& t : pair)
    for (const auto& x : restricted.voronoi_edge_record(t).crossings()) collector.add(x);
  auto witnesses = collector.take().witnesses;
  if (witnesses.empty()) return std::nullopt;  // restricted triangles have crossings: not reached
  return witnesses.front();
}

}  // namespace delmesh
