#include "meshing/checks/smooth.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "meshing/checks/detail/candidates.h"
#include "meshing/core/detail/vec3.h"
#include "meshing/inputs/mesh_oracle.h"

namespace delmesh {

using namespace detail;

namespace {

//! ∇E at x for the run of `restricted`, remembered per thread for the last points asked (a
//! direct-mapped table keyed by the point's bits): Smooth asks for a triangle's normal from each
//! of its three edges.  An entry is tied to the triangulation's serial, which no other
//! triangulation of the process has, and so to the run and its oracle.
Vec3 gradient_at(RestrictedDelaunay& restricted, const Vec3& x) {
  struct Entry {
    std::uint64_t serial = 0;  // no Delaunay has serial 0
    Vec3 point{}, gradient{};
  };
  constexpr std::size_t size = 256;
  thread_local std::array<Entry, size> table;
  std::uint64_t hash = 0;
  for (double c : x) {
    std::uint64_t bits;
    std::memcpy(&bits, &c, sizeof bits);
    hash = (hash ^ bits) * 0x100000001b3ull;
  }
  Entry& e = table[(hash >> 40) % size];
  const std::uint64_t serial = restricted.delaunay().serial();
  if (e.serial != serial || e.point != x) e = {serial, x, restricted.oracle().gradient(x)};
  return e.gradient;
}

}  // namespace

Vec3 outward_normal(RestrictedDelaunay& restricted, const TriangleKey& t) {
  const auto& del = restricted.delaunay();
  const Vec3 &p = del.point(t[0]), &q = del.point(t[1]), &r = del.point(t[2]);
  Vec3 n = normalized(cross(q - p, r - p));
  const auto& rec = restricted.voronoi_edge_record(t);
  if (dot(n, gradient_at(restricted, rec.dual_point())) < 0) n = (-1.0) * n;
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

bool smooth_exempt_edge(RestrictedDelaunay& restricted, const EdgeKey& pq) {
  const auto* mesh = dynamic_cast<const MeshOracle*>(&restricted.oracle());
  if (!mesh || mesh->feature_edges().empty()) return false;
  const auto& del = restricted.delaunay();
  const auto point = [&](VertexId v) {
    const auto& x = del.point(v);
    return Point3(x[0], x[1], x[2]);
  };
  std::vector<Point3> others;
  for (VertexId s : del.neighbours(pq[0]))
    if (s != pq[1]) others.push_back(point(s));
  return mesh->feature_edges().facet_meets_feature_edge(point(pq[0]), point(pq[1]), others);
}

CheckResult smooth_check(RestrictedDelaunay& restricted, const TriangleKey& t, double threshold) {
  CheckResult result;
  if (!restricted.voronoi_edge_record(t).restricted) return result;
  for (const auto& e : {make_edge_key(t[0], t[1]), make_edge_key(t[0], t[2]), make_edge_key(t[1], t[2])}) {
    const auto w = smooth_witness(restricted, e, threshold);
    if (!w) continue;
    if (!smooth_exempt_edge(restricted, e)) return CheckResult{{*w}, {}};
    result.unsettled.push_back({CheckKind::smooth, UnsettledReason::no_witness, w->point});
  }
  return result;
}

}  // namespace delmesh
