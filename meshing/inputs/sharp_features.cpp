// Sharp edges, corners and feature curves of a triangle mesh.  See sharp_features.h.
#include "meshing/inputs/sharp_features.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include <CGAL/Exact_rational.h>
#include <CGAL/Interval_nt.h>

#include "common/errors.h"
#include "meshing/inputs/folded_vertices.h"

namespace delmesh {

namespace {

using Vertex = SurfaceMesh::Vertex_index;
using Edge = SurfaceMesh::Edge_index;
using Halfedge = SurfaceMesh::Halfedge_index;

//! cos θ for θ in degrees: exact for 60, 90 and 120, rounded otherwise.
double cosine_of_degrees(double degrees) {
  if (degrees == 60) return 0.5;
  if (degrees == 90) return 0;
  if (degrees == 120) return -0.5;
  return std::cos(degrees * M_PI / 180);
}

//! The sign of ⟨n₁, n₂⟩ − c·|n₁||n₂| in the number type NT (every intermediate stored as an NT),
//! or 2 for "a normal is zero"; for NT = Interval_nt, 3 when a sign is uncertain.
template <class NT>
int angle_test(const std::array<Point3, 6>& p, double c) {
  const auto sign_of = [](const NT& x) -> int {
    if constexpr (std::is_same_v<NT, CGAL::Interval_nt_advanced>) {
      if (x.inf() > 0) return 1;
      if (x.sup() < 0) return -1;
      if (x.inf() == 0 && x.sup() == 0) return 0;
      return 3;
    } else {
      return static_cast<int>(CGAL::sign(x));
    }
  };
  const auto normal = [&](int i) {
    const NT ux = NT(p[i + 1].x()) - NT(p[i].x()), uy = NT(p[i + 1].y()) - NT(p[i].y()),
             uz = NT(p[i + 1].z()) - NT(p[i].z());
    const NT vx = NT(p[i + 2].x()) - NT(p[i].x()), vy = NT(p[i + 2].y()) - NT(p[i].y()),
             vz = NT(p[i + 2].z()) - NT(p[i].z());
    const NT nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    return std::array<NT, 3>{nx, ny, nz};
  };
  const std::array<NT, 3> n1 = normal(0), n2 = normal(3);
  const NT l1 = n1[0] * n1[0] + n1[1] * n1[1] + n1[2] * n1[2];
  const NT l2 = n2[0] * n2[0] + n2[1] * n2[1] + n2[2] * n2[2];
  const int s1 = sign_of(l1), s2 = sign_of(l2);
  if (s1 == 3 || s2 == 3) return 3;
  if (s1 == 0 || s2 == 0) return 2;
  const NT d = n1[0] * n2[0] + n1[1] * n2[1] + n1[2] * n2[2];
  const int sd = sign_of(d);
  if (sd == 3) return 3;
  const int sc = c > 0 ? 1 : (c < 0 ? -1 : 0);
  // d − c·√(l1 l2): compare by signs first, then by squares.
  if (sc == 0) return sd;
  if (sd >= 0 && sc < 0) return 1;
  if (sd <= 0 && sc > 0) return -1;
  const NT lhs = d * d;
  const NT rhs = NT(c) * NT(c) * l1 * l2;
  const int s = sign_of(lhs - rhs);  // sign of d² − c² l1 l2
  if (s == 3) return 3;
  // Both positive: d − c√(l1l2) has the sign of d² − c²l1l2; both negative: the opposite sign.
  return sd > 0 ? s : -s;
}

void require_angle(double angle_deg) {
  if (!(angle_deg > 0 && angle_deg < 180))
    throw PreconditionViolation("detect_features: the feature angle must lie in (0, 180) degrees, got " +
                                std::to_string(angle_deg));
}

//! The three corners of face f in its orientation, starting at the source of h (h in f).
std::array<Point3, 3> corners_from(const SurfaceMesh& mesh, Halfedge h) {
  return {mesh.point(mesh.source(h)), mesh.point(mesh.target(h)), mesh.point(mesh.target(mesh.next(h)))};
}

}  // namespace

bool normals_differ_by_more_than(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                                 const Point3& e, const Point3& f, double angle_deg) {
  require_angle(angle_deg);
  const double cosine = cosine_of_degrees(angle_deg);
  const std::array<Point3, 6> p{a, b, c, d, e, f};
  int s;
  {
    CGAL::Protect_FPU_rounding<true> guard;
    s = angle_test<CGAL::Interval_nt_advanced>(p, cosine);
  }
  if (s == 3) s = angle_test<CGAL::Exact_rational>(p, cosine);
  return s == 2 || s < 0;
}

namespace {

//! |x − p|² − |x − q|² = 2⟨x, q − p⟩ − (|q|² − |p|²), every intermediate an NT: < 0 nearer to p.
template <class NT>
NT bisector_value(const Point3& x, const Point3& p, const Point3& q) {
  const NT dx = NT(q.x()) - NT(p.x()), dy = NT(q.y()) - NT(p.y()), dz = NT(q.z()) - NT(p.z());
  const NT qq = NT(q.x()) * NT(q.x()) + NT(q.y()) * NT(q.y()) + NT(q.z()) * NT(q.z());
  const NT pp = NT(p.x()) * NT(p.x()) + NT(p.y()) * NT(p.y()) + NT(p.z()) * NT(p.z());
  return NT(2) * (NT(x.x()) * dx + NT(x.y()) * dy + NT(x.z()) * dz) - (qq - pp);
}

//! For the point x where the segment uw crosses B(p, q): |x − p|² − |x − s|² times W², where x =
//! X / W in homogeneous coordinates (X = u·b + a·(w − u), W = b, a = −f(u), b = f(w) − f(u) for
//! f = bisector_value of p, q); so its sign is that of |x − p|² − |x − s|².
template <class NT>
NT cut_value(const Point3& u, const Point3& w, const Point3& p, const Point3& q, const Point3& s) {
  const NT fu = bisector_value<NT>(u, p, q), fw = bisector_value<NT>(w, p, q);
  const NT a = -fu, b = fw - fu;
  const NT ex = NT(w.x()) - NT(u.x()), ey = NT(w.y()) - NT(u.y()), ez = NT(w.z()) - NT(u.z());
  const NT X = NT(u.x()) * b + a * ex, Y = NT(u.y()) * b + a * ey, Z = NT(u.z()) * b + a * ez;
  const NT dx = NT(s.x()) - NT(p.x()), dy = NT(s.y()) - NT(p.y()), dz = NT(s.z()) - NT(p.z());
  const NT ss = NT(s.x()) * NT(s.x()) + NT(s.y()) * NT(s.y()) + NT(s.z()) * NT(s.z());
  const NT pp = NT(p.x()) * NT(p.x()) + NT(p.y()) * NT(p.y()) + NT(p.z()) * NT(p.z());
  return (NT(2) * (X * dx + Y * dy + Z * dz) - (ss - pp) * b) * b;
}

//! The exact sign of value<NT>(): interval arithmetic first, exact rationals if it is not certain.
template <class Value>
int exact_sign(const Value& value) {
  {
    CGAL::Protect_FPU_rounding<true> guard;
    const CGAL::Interval_nt_advanced x = value(CGAL::Interval_nt_advanced());
    if (x.inf() > 0) return 1;
    if (x.sup() < 0) return -1;
    if (x.inf() == 0 && x.sup() == 0) return 0;
  }
  return static_cast<int>(CGAL::sign(value(CGAL::Exact_rational())));
}

}  // namespace

FeatureEdges::FeatureEdges(const SurfaceMesh& mesh, const FeatureSet& features) : angle_deg_(features.angle_deg) {
  segments_.reserve(features.feature_edges.size());
  for (Edge e : features.feature_edges)
    segments_.push_back({mesh.point(mesh.vertex(e, 0)), mesh.point(mesh.vertex(e, 1))});
}

bool FeatureEdges::facet_meets_feature_edge(const Point3& p, const Point3& q, const std::vector<Point3>& others) const {
  for (const auto& segment : segments_) {
    const Point3& u = segment[0];
    const Point3& w = segment[1];
    const int su = exact_sign([&](auto nt) { return bisector_value<decltype(nt)>(u, p, q); });
    if (su == 0) continue;
    const int sw = exact_sign([&](auto nt) { return bisector_value<decltype(nt)>(w, p, q); });
    if (sw != -su) continue;  // no strict crossing of B(p, q)
    const bool in_cell = std::all_of(others.begin(), others.end(), [&](const Point3& s) {
      return exact_sign([&](auto nt) { return cut_value<decltype(nt)>(u, w, p, q, s); }) <= 0;
    });
    if (in_cell) return true;
  }
  return false;
}

bool FeatureSet::is_feature_edge(SurfaceMesh::Edge_index e) const {
  return std::binary_search(feature_edges.begin(), feature_edges.end(), e);
}

bool FeatureSet::is_corner(SurfaceMesh::Vertex_index v) const {
  return std::binary_search(corners.begin(), corners.end(), v);
}

namespace {

// The feature edges of the mesh into `set` (border edges and edges whose faces' normals differ by
// more than angle_deg), sorted, with their counts; returns the flag of each edge.
std::vector<char> mark_feature_edges(const SurfaceMesh& mesh, double angle_deg, FeatureSet& set) {
  std::vector<char> feature(mesh.num_edges(), 0);
  for (Edge e : mesh.edges()) {
    const Halfedge h = mesh.halfedge(e), o = mesh.opposite(h);
    if (mesh.is_border(h) || mesh.is_border(o)) {
      ++set.border_edges;
    } else {
      const auto p = corners_from(mesh, h), q = corners_from(mesh, o);
      if (!normals_differ_by_more_than(p[0], p[1], p[2], q[0], q[1], q[2], angle_deg)) continue;
      ++set.sharp_edges;
    }
    feature[std::size_t(e)] = 1;
    set.feature_edges.push_back(e);
  }
  std::sort(set.feature_edges.begin(), set.feature_edges.end());
  return feature;
}

// The number of feature edges at each vertex.
std::vector<std::size_t> feature_degrees(const SurfaceMesh& mesh, const std::vector<Edge>& feature_edges) {
  std::vector<std::size_t> degree(mesh.num_vertices(), 0);
  for (Edge e : feature_edges) {
    ++degree[std::size_t(mesh.vertex(e, 0))];
    ++degree[std::size_t(mesh.vertex(e, 1))];
  }
  return degree;
}

// The corners into `set` (vertices of feature degree 1 or at least 3, and the folded vertices),
// sorted, with the count of folded ones; returns the flag of each vertex.
std::vector<char> mark_corners(const SurfaceMesh& mesh, const std::vector<std::size_t>& degree,
                               const std::vector<Vertex>& folded, FeatureSet& set) {
  std::vector<char> corner(mesh.num_vertices(), 0);
  for (Vertex v : mesh.vertices())
    if (degree[std::size_t(v)] == 1 || degree[std::size_t(v)] >= 3) corner[std::size_t(v)] = 1;
  std::vector<Vertex> folded_sorted = folded;
  std::sort(folded_sorted.begin(), folded_sorted.end());
  folded_sorted.erase(std::unique(folded_sorted.begin(), folded_sorted.end()), folded_sorted.end());
  for (Vertex v : folded_sorted) corner[std::size_t(v)] = 1;
  set.folded_corners = folded_sorted.size();
  for (Vertex v : mesh.vertices())
    if (corner[std::size_t(v)]) set.corners.push_back(v);
  std::sort(set.corners.begin(), set.corners.end());
  return corner;
}

// Walks the feature curves: along feature edges from a vertex until a corner, each edge once.
class CurveWalker {
 public:
  CurveWalker(const SurfaceMesh& mesh, const std::vector<char>& feature, const std::vector<char>& corner)
      : mesh_(mesh), feature_(feature), corner_(corner), used_(mesh.num_edges(), 0) {}

  // The feature edges at v, ascending by edge index.
  std::vector<Edge> feature_edges_at(Vertex v) const {
    std::vector<Edge> at;
    if (mesh_.halfedge(v) == SurfaceMesh::null_halfedge()) return at;
    for (Halfedge h : CGAL::halfedges_around_target(v, mesh_))
      if (feature_[std::size_t(mesh_.edge(h))] != 0) at.push_back(mesh_.edge(h));
    std::sort(at.begin(), at.end());
    return at;
  }

  // The end of e other than v.
  Vertex other_end(Edge e, Vertex v) const { return mesh_.vertex(e, 0) == v ? mesh_.vertex(e, 1) : mesh_.vertex(e, 0); }

  // Whether a walk has taken e.
  bool used(Edge e) const { return used_[std::size_t(e)] != 0; }

  // From vertex `from` along feature edge `first` until a corner, or back at `stop` (a closed
  // curve without corner).
  FeatureCurve walk(Vertex from, Edge first, Vertex stop) {
    FeatureCurve curve;
    curve.vertices.push_back(from);
    Edge e = first;
    Vertex v = from;
    while (true) {
      used_[std::size_t(e)] = 1;
      curve.edges.push_back(e);
      v = other_end(e, v);
      curve.vertices.push_back(v);
      if (corner_[std::size_t(v)] || v == stop) break;
      // v has exactly two feature edges; go on along the one not just used.
      Edge next = e;
      for (Edge f : feature_edges_at(v))
        if (f != e) next = f;
      if (next == e || used_[std::size_t(next)]) break;  // (not reached for a degree-2 vertex)
      e = next;
    }
    curve.closed = curve.vertices.back() == curve.vertices.front();
    return curve;
  }

 private:
  const SurfaceMesh& mesh_;
  const std::vector<char>& feature_;
  const std::vector<char>& corner_;
  std::vector<char> used_;
};

// The feature curves into `set`: those from each corner, then the closed curves without a corner,
// each found from its smallest vertex.
void trace_curves(const SurfaceMesh& mesh, const std::vector<std::size_t>& degree, const std::vector<char>& corner,
                  CurveWalker& walker, FeatureSet& set) {
  for (Vertex c : set.corners)
    for (Edge e : walker.feature_edges_at(c))
      if (!walker.used(e)) set.curves.push_back(walker.walk(c, e, c));
  for (Vertex v : mesh.vertices()) {
    if (degree[std::size_t(v)] != 2 || corner[std::size_t(v)]) continue;
    const std::vector<Edge> at = walker.feature_edges_at(v);
    if (walker.used(at[0])) continue;
    // Every vertex of this unused cycle has a larger index than v, since the cycles are found in
    // ascending order of their smallest vertex: start towards the smaller neighbour.
    const Vertex n0 = walker.other_end(at[0], v), n1 = walker.other_end(at[1], v);
    FeatureCurve curve = walker.walk(v, n0 < n1 ? at[0] : at[1], v);
    curve.without_corner = true;
    set.curves.push_back(std::move(curve));
  }
  for (const FeatureCurve& curve : set.curves) {
    set.closed_curves += curve.closed;
    set.curves_without_corner += curve.without_corner;
  }
}

}  // namespace

FeatureSet detect_features(const SurfaceMesh& mesh, double angle_deg, const std::vector<Vertex>& folded) {
  require_angle(angle_deg);
  for (Vertex v : folded)
    if (!mesh.is_valid(v) || std::size_t(v) >= mesh.num_vertices())
      throw PreconditionViolation("detect_features: a folded vertex is not a vertex of the mesh");
  FeatureSet set;
  set.angle_deg = angle_deg;
  const std::vector<char> feature = mark_feature_edges(mesh, angle_deg, set);
  const std::vector<std::size_t> degree = feature_degrees(mesh, set.feature_edges);
  const std::vector<char> corner = mark_corners(mesh, degree, folded, set);
  CurveWalker walker(mesh, feature, corner);
  trace_curves(mesh, degree, corner, walker, set);
  return set;
}

FeatureSet detect_features(const SurfaceMesh& mesh, double angle_deg) {
  require_angle(angle_deg);
  return detect_features(mesh, angle_deg, folded_vertices(mesh));
}

nlohmann::json features_json(const FeatureSet& f) {
  return {{"angle_deg", f.angle_deg},
          {"sharp_edges", f.sharp_edges},
          {"curves", f.curves.size()},
          {"closed_curves", f.closed_curves},
          {"corners", f.corners.size()},
          {"folded_corners", f.folded_corners}};
}

}  // namespace delmesh
