#include "meshing/restricted_delaunay.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/tolerances.h"
#include "meshing/detail/vec3.h"

namespace delmesh {

using namespace detail;

double seeded_uniform(std::uint64_t seed, std::int64_t a, std::int64_t b, std::int64_t c) {
  std::uint64_t z = seed * 0x9E3779B97F4A7C15ULL;
  for (std::int64_t w : {a, b, c}) {
    z += static_cast<std::uint64_t>(w) + 0x9E3779B97F4A7C15ULL;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
  }
  return static_cast<double>(z >> 11) * (1.0 / 9007199254740992.0);
}

RestrictedDelaunay::RestrictedDelaunay(const Delaunay& del, SurfaceOracle& oracle, std::uint64_t seed)
    : del_(del), oracle_(oracle), seed_(seed) {}

double RestrictedDelaunay::facet_rotation(const EdgeKey& e) const {
  return 2 * M_PI * seeded_uniform(seed_, e[0], e[1], 17);
}

const EdgeRecord& RestrictedDelaunay::edge_record(const TriangleKey& t) {
  auto it = edges_.find(t);
  if (it != edges_.end()) return it->second;
  return edges_.emplace(t, compute(t)).first->second;
}

const VoronoiFacet& RestrictedDelaunay::facet(const EdgeKey& e) {
  auto it = facets_.find(e);
  if (it != facets_.end()) return it->second;
  return facets_.emplace(e, voronoi_facet(del_, e, oracle_.box(), facet_rotation(e))).first->second;
}

EdgeRecord RestrictedDelaunay::compute(const TriangleKey& t) {
  EdgeRecord r;
  r.edge = voronoi_edge(del_, t, oracle_.box());
  if (!r.edge.valid) return r;
  const auto& e = r.edge;
  const auto result = oracle_.surface_line(e.point, e.direction, e.t0, e.t1);
  const double face_tol = tolerances::face_membership_relative_tolerance * oracle_.diagonal();
  // Zeros at Voronoi vertices: whether each would be excluded by §5.1 if it were the only one.
  std::vector<bool> vertex_root_excluded;
  const double vertex_tol = tolerances::duplicate_sample_relative_distance * oracle_.diagonal();
  for (const auto& root : result.roots) {
    // A certified zero numerically at a Voronoi vertex is the §5.1 degeneracy as well.
    const double t = root.midpoint[0];
    const bool at0 = e.at_vertex0 && std::abs(t - e.t0) <= vertex_tol;
    const bool at1 = e.at_vertex1 && std::abs(t - e.t1) <= vertex_tol;
    r.crossings.push_back(root.world);
    if (at0 || at1) {
      const Vec3 into = at0 ? e.direction : (-1.0) * e.direction;
      vertex_root_excluded.push_back(dot(into, oracle_.normal(root.world)) > 0);
    }
  }
  for (const auto& u : result.undecided) {
    const double lo = u.box.bounds[0][0], hi = u.box.bounds[0][1];
    const double tm = 0.5 * (lo + hi);
    const bool near0 = std::abs(tm - e.t0) <= std::abs(tm - e.t1);
    if (u.reason == UndecidedReason::boundary_root && (near0 ? e.at_vertex0 : e.at_vertex1)) {
      const Vec3 v = e.at(near0 ? e.t0 : e.t1);
      const Vec3 into = near0 ? e.direction : (-1.0) * e.direction;  // direction of u − v
      r.crossings.push_back(v);
      vertex_root_excluded.push_back(dot(into, oracle_.normal(v)) > 0);
      continue;
    }
    const auto x = oracle_.project(u.world);
    const double tol = std::max(face_tol, hi - lo);
    if (x) {
      const double tx = dot(*x - e.point, e.direction);
      const double off = distance(*x, e.at(tx));
      if (off <= tol && tx >= e.t0 - tol && tx <= e.t1 + tol) {
        r.candidates.push_back(*x);
        continue;
      }
    }
    ++r.unresolved;
    ++unresolved_;
  }
  const bool lone_excluded_vertex =
      r.crossings.size() == 1 && vertex_root_excluded.size() == 1 && vertex_root_excluded[0];
  r.restricted = !r.crossings.empty() && !lone_excluded_vertex;
  if (r.restricted) r.dual_point = r.crossings.front();
  return r;
}

void RestrictedDelaunay::invalidate(const std::vector<VertexId>& vertices) {
  auto in = [&](VertexId v) { return std::binary_search(vertices.begin(), vertices.end(), v); };
  for (VertexId v : vertices) {
    const bool removed = !del_.contains(v);
    for (auto it = edges_.lower_bound({v, std::numeric_limits<VertexId>::min(), 0});
         it != edges_.end() && it->first[0] == v;) {
      if (removed || (in(it->first[1]) && in(it->first[2])))
        it = edges_.erase(it);
      else
        ++it;
    }
    for (auto it = facets_.lower_bound({v, std::numeric_limits<VertexId>::min()});
         it != facets_.end() && it->first[0] == v;) {
      if (removed || in(it->first[1]))
        it = facets_.erase(it);
      else
        ++it;
    }
  }
  // Records whose smallest vertex is outside the set but that contain a removed vertex.
  for (VertexId v : vertices) {
    if (del_.contains(v)) continue;
    for (auto it = edges_.begin(); it != edges_.end();) {
      if (it->first[1] == v || it->first[2] == v)
        it = edges_.erase(it);
      else
        ++it;
    }
    for (auto it = facets_.begin(); it != facets_.end();) {
      if (it->first[1] == v)
        it = facets_.erase(it);
      else
        ++it;
    }
  }
}

std::vector<TriangleKey> RestrictedDelaunay::star(VertexId p) {
  std::vector<TriangleKey> out;
  for (const auto& t : del_.incident_triangles(p))
    if (edge_record(t).restricted) out.push_back(t);
  return out;
}

std::vector<TriangleKey> RestrictedDelaunay::triangles() {
  std::vector<TriangleKey> out;
  for (const auto& t : del_.triangles())
    if (edge_record(t).restricted) out.push_back(t);
  return out;
}

}  // namespace delmesh
