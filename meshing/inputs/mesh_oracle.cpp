// The surface oracle of a closed triangle mesh.  See mesh_oracle.h for what each primitive means
// on a piecewise-linear surface and what is exact.
//
// Steps shared by the primitives:
//  1. The faces that can matter are found with the AABB tree: those meeting the segment (exact
//     do_intersect), or the bounding box of the facet or cell (widened by the face-membership
//     tolerance, so that a point of F computed in doubles is inside it).
//  2. Every sign is decided exactly: CGAL::orientation on the input doubles for sides of planes,
//     and det / dot signs in interval arithmetic with an exact rational fallback.
//  3. The points returned (crossings) are constructed in doubles from the exact combinatorics.
#include "meshing/inputs/mesh_oracle.h"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_rational.h>
#include <CGAL/Interval_nt.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "common/errors.h"
#include "common/tolerances.h"
#include "meshing/core/detail/vec3.h"
#include "meshing/inputs/unit_scale.h"
#include "meshing/voronoi/voronoi_geometry.h"
#include "solvers/query_geometry.h"

namespace delmesh {

using namespace detail;

namespace {

using Primitive = CGAL::AABB_face_graph_triangle_primitive<SurfaceMesh>;
using AabbTraits = CGAL::AABB_traits<Kernel, Primitive>;
using Tree = CGAL::AABB_tree<AabbTraits>;
using Face = SurfaceMesh::Face_index;
using VertexIndex = SurfaceMesh::Vertex_index;

// The primitives in the order of the statistics.
enum PrimitiveIndex { line_index, critical_index, contact_index, curve_index, sil_plane_index, sil_critical_index };
constexpr const char* primitive_names[] = {"surface_line",  "surface_critical", "surface_plane_contact",
                                           "curve_critical", "silhouette_plane", "silhouette_critical"};

Point3 point(const Vec3& x) { return {x[0], x[1], x[2]}; }
Vec3 vec(const Point3& p) { return {p.x(), p.y(), p.z()}; }

int interval_sign(const CGAL::Interval_nt_advanced& x) {
  if (x.inf() > 0) return 1;
  if (x.sup() < 0) return -1;
  if (x.inf() == 0 && x.sup() == 0) return 0;
  return 2;  // not certain
}

// The exact sign of a quantity that value(NT{}) computes in the number type NT from the input
// doubles: in interval arithmetic first, and in exact rationals when the interval's sign is not
// certain.  value must store every intermediate as an NT (expression templates must not outlive
// their operands).
template <class Value>
int filtered_sign(Value&& value) {
  {
    CGAL::Protect_FPU_rounding<true> guard;
    if (const int sign = interval_sign(value(CGAL::Interval_nt_advanced())); sign != 2) return sign;
  }
  return static_cast<int>(CGAL::sign(value(CGAL::Exact_rational())));
}

// The sign of orientation(p, q, r, s_ε) for s_ε = s + (ε, ε², ε³), ε > 0 infinitesimal (exact):
// det(q − p, r − p, s_ε − p) = orientation(p, q, r, s) + ε n_x + ε² n_y + ε³ n_z with
// n = (q − p) × (r − p), so its sign is the first non-zero one among them; each component of n is
// the orientation of the projections of p, q, r onto the other two axes.  0 only if p, q, r are
// collinear.
int perturbed_orientation(const Point3& p, const Point3& q, const Point3& r, const Point3& s) {
  if (const CGAL::Orientation o = CGAL::orientation(p, q, r, s); o != CGAL::COPLANAR) return static_cast<int>(o);
  using Point2 = Kernel::Point_2;
  const CGAL::Orientation n[3] = {CGAL::orientation(Point2(p.y(), p.z()), Point2(q.y(), q.z()), Point2(r.y(), r.z())),
                                  CGAL::orientation(Point2(p.z(), p.x()), Point2(q.z(), q.x()), Point2(r.z(), r.x())),
                                  CGAL::orientation(Point2(p.x(), p.y()), Point2(q.x(), q.y()), Point2(r.x(), r.y()))};
  for (const CGAL::Orientation c : n)
    if (c != CGAL::COLLINEAR) return static_cast<int>(c);
  return 0;
}

// The exact sign of ⟨x − y, d⟩.
int dot_difference_sign(const Vec3& x, const Vec3& y, const Vec3& d) {
  return filtered_sign([&](auto zero) {
    using NT = decltype(zero);
    NT s = 0;
    for (int k = 0; k < 3; ++k) {
      const NT difference = NT(x[k]) - NT(y[k]);
      s += difference * NT(d[k]);
    }
    return s;
  });
}

// ⟨(b − a) × (c − a), d⟩ in the number type NT (every intermediate stored as an NT, so that
// expression templates never outlive their operands).
template <class NT>
NT facing_determinant(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const NT u0 = NT(b[0]) - NT(a[0]), u1 = NT(b[1]) - NT(a[1]), u2 = NT(b[2]) - NT(a[2]);
  const NT v0 = NT(c[0]) - NT(a[0]), v1 = NT(c[1]) - NT(a[1]), v2 = NT(c[2]) - NT(a[2]);
  const NT n0 = u1 * v2 - u2 * v1, n1 = u2 * v0 - u0 * v2, n2 = u0 * v1 - u1 * v0;
  const NT s = n0 * NT(d[0]) + n1 * NT(d[1]) + n2 * NT(d[2]);
  return s;
}

// The exact sign of ⟨(b − a) × (c − a), d⟩: how the triangle abc faces relative to d.
int facing_sign(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return filtered_sign([&](auto zero) { return facing_determinant<decltype(zero)>(a, b, c, d); });
}

// Whether the point u (unknowns of the domain) lies in the domain's box and half-spaces, up to tol.
bool in_domain(const Domain& domain, const std::vector<double>& u, double tol) {
  for (std::size_t k = 0; k < u.size(); ++k)
    if (u[k] < domain.box.bounds[k][0] - tol || u[k] > domain.box.bounds[k][1] + tol) return false;
  return half_spaces_contain(domain, u, tol);
}

// A root at world point x with unknowns u (a point box).
CertifiedRoot point_root(const std::vector<double>& u, const Vec3& x) {
  CertifiedRoot r;
  for (double c : u) r.box.bounds.push_back({c, c});
  r.midpoint = u;
  r.world = x;
  r.inside_domain = true;
  return r;
}

UndecidedBox point_region(const std::vector<double>& u, const Vec3& x, UndecidedReason reason) {
  UndecidedBox r;
  for (double c : u) r.box.bounds.push_back({c, c});
  r.reason = reason;
  r.world = x;
  return r;
}

// The plane through o, o + a, o + b (the doubles) and its frame.
struct Plane {
  Point3 p0, p1, p2;
  Vec3 o, a, b, n;
  Plane(const Vec3& origin, const Vec3& ua, const Vec3& ub)
      : p0(point(origin)), p1(point(origin + ua)), p2(point(origin + ub)), o(origin), a(ua), b(ub), n(cross(ua, ub)) {}
  //! Exact side of x: +1 on the side of a × b, −1 on the other, 0 on the plane.
  int exact_side(const Vec3& x) const { return static_cast<int>(CGAL::orientation(p0, p1, p2, point(x))); }
  //! The side under the perturbation (a vertex on the plane counts as positive).
  int side(const Vec3& x) const { return exact_side(x) >= 0 ? 1 : -1; }
  std::vector<double> uv(const Vec3& x) const { return {dot(x - o, a), dot(x - o, b)}; }
  //! The crossing of the segment xy (whose ends lie on different sides) with the plane.
  Vec3 crossing(const Vec3& x, const Vec3& y) const {
    const double hx = dot(x - o, n), hy = dot(y - o, n);
    double s = hx == hy ? 0.5 : hx / (hx - hy);
    s = std::clamp(s, 0.0, 1.0);
    return x + s * (y - x);
  }
};

// The height ⟨x, a⟩ of the exact crossing x of the segment PQ with the plane through the double
// points p0, p1, p2, in the number type NT: x = P + s (Q − P), s = h(P) / (h(P) − h(Q)) with
// h(X) = det(p1 − p0, p2 − p0, X − p0).  Precondition: P and Q lie on different sides under the
// perturbation, so h(P) ≠ h(Q) exactly (an enclosure of the denominator may still hold 0).
template <class NT>
NT crossing_height(const Plane& plane, const Vec3& P, const Vec3& Q, const Vec3& a) {
  const Vec3 o = vec(plane.p0), o1 = vec(plane.p1), o2 = vec(plane.p2);
  NT u[3], v[3], dp[3], dq[3];
  for (int k = 0; k < 3; ++k) {
    u[k] = NT(o1[k]) - NT(o[k]);
    v[k] = NT(o2[k]) - NT(o[k]);
    dp[k] = NT(P[k]) - NT(o[k]);
    dq[k] = NT(Q[k]) - NT(o[k]);
  }
  const NT n0 = u[1] * v[2] - u[2] * v[1], n1 = u[2] * v[0] - u[0] * v[2], n2 = u[0] * v[1] - u[1] * v[0];
  const NT hp = n0 * dp[0] + n1 * dp[1] + n2 * dp[2], hq = n0 * dq[0] + n1 * dq[1] + n2 * dq[2];
  const NT t = hp / (hp - hq);
  NT height = 0;
  for (int k = 0; k < 3; ++k) {
    const NT x = NT(P[k]) + t * (NT(Q[k]) - NT(P[k]));
    height += x * NT(a[k]);
  }
  return height;
}

// The exact sign of ⟨x_e − x_f, a⟩ for the crossings x_e, x_f of the mesh segments e = e0 e1 and
// f = f0 f1 with the plane (crossing_height's precondition on both).
int crossing_height_sign(const Plane& plane, const Vec3& e0, const Vec3& e1, const Vec3& f0, const Vec3& f1,
                         const Vec3& a) {
  return filtered_sign([&](auto zero) {
    using NT = decltype(zero);
    const NT difference = crossing_height<NT>(plane, e0, e1, a) - crossing_height<NT>(plane, f0, f1, a);
    return difference;
  });
}

// A plane section: per crossing mesh edge, its point and its neighbours along the section.
struct SectionGraph {
  using Edge = std::pair<int, int>;
  std::map<Edge, std::vector<Edge>> next;
  std::map<Edge, Vec3> at;
};

}  // namespace

struct MeshOracle::Impl {
  SurfaceMesh mesh;
  Tree tree;
  std::vector<Vec3> points;               // by vertex index
  std::vector<std::array<int, 3>> faces;  // by face index, outward order
  std::vector<Vec3> face_normal;          // unit outward normal by face index
  std::vector<Vec3> vertex_normal;        // angle-weighted, by vertex index
  std::vector<std::vector<int>> link;     // neighbours in cyclic order, by vertex index
  double feature_tolerance = 0;
  //! How far from a primitive's domain a mesh face still counts as near it (faces_near): the
  //! face-membership tolerance of the checks, face_membership_relative_tolerance · diagonal.
  double face_margin = 0;

  explicit Impl(const SurfaceMesh& m) : mesh(m) {
    points.resize(mesh.number_of_vertices());
    for (VertexIndex v : mesh.vertices()) points[v.idx()] = vec(mesh.point(v));
    faces.resize(mesh.number_of_faces());
    face_normal.resize(faces.size());
    vertex_normal.assign(points.size(), Vec3{0, 0, 0});
    for (Face f : mesh.faces()) {
      int k = 0;
      for (VertexIndex v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) faces[f.idx()][k++] = static_cast<int>(v.idx());
      const auto& t = faces[f.idx()];
      const Vec3 n = cross(points[t[1]] - points[t[0]], points[t[2]] - points[t[0]]);
      face_normal[f.idx()] = norm(n) > 0 ? normalized(n) : Vec3{0, 0, 0};
      for (int i = 0; i < 3; ++i) {
        const Vec3 e1 = points[t[(i + 1) % 3]] - points[t[i]], e2 = points[t[(i + 2) % 3]] - points[t[i]];
        const double c = dot(e1, e2) / (norm(e1) * norm(e2));
        const double angle = std::acos(std::clamp(c, -1.0, 1.0));
        vertex_normal[t[i]] = vertex_normal[t[i]] + angle * face_normal[f.idx()];
      }
    }
    for (auto& n : vertex_normal)
      if (norm(n) > 0) n = normalized(n);
    // A sample at a vertex must not lie on the silhouette of its own normal: if some incident
    // face does not face the angle-weighted normal, the first incident face normal or the plain
    // mean that every incident face faces (exactly) is taken instead, if there is one.
    for (VertexIndex v : mesh.vertices()) {
      std::vector<int> star;
      for (Face f : CGAL::faces_around_target(mesh.halfedge(v), mesh)) star.push_back(static_cast<int>(f.idx()));
      auto faced_by_all = [&](const Vec3& n) {
        for (int f : star)
          if (facing_sign(vertex(f, 0), vertex(f, 1), vertex(f, 2), n) <= 0) return false;
        return true;
      };
      if (faced_by_all(vertex_normal[v.idx()])) continue;
      Vec3 mean{0, 0, 0};
      for (int f : star) mean = mean + face_normal[f];
      std::vector<Vec3> candidates{mean};
      for (int f : star) candidates.push_back(face_normal[f]);
      for (const Vec3& n : candidates)
        if (norm(n) > 0 && faced_by_all(n)) {
          vertex_normal[v.idx()] = normalized(n);
          break;
        }
    }
    link.resize(points.size());
    for (VertexIndex v : mesh.vertices())
      for (VertexIndex w : CGAL::vertices_around_target(mesh.halfedge(v), mesh)) link[v.idx()].push_back(static_cast<int>(w.idx()));
    tree.insert(mesh.faces().begin(), mesh.faces().end(), mesh);
    tree.build();
    tree.accelerate_distance_queries();
    (void)tree.closest_point(mesh.point(*mesh.vertices().begin()));  // builds the search tree now
  }

  //! The side of x: 0 if x lies on a face (exact), else the parity of the crossings of Σ by the
  //! segment from x to a point q outside the bounding box of the vertices (−1 odd: inside, +1
  //! even: outside).  Every sign is exact, and q is perturbed symbolically to
  //! q + (ε, ε², ε³) (perturbed_orientation), so the segment meets no edge or vertex and lies in
  //! no face's plane: each crossing is transversal through the interior of one face, and the
  //! sides alternate along it.  One segment, no retries: time linear in the faces it meets.
  int side_of(const Vec3& x) const {
    const CGAL::Bbox_3 bounds = tree.bbox();
    if (x[0] < bounds.xmin() || x[0] > bounds.xmax() || x[1] < bounds.ymin() || x[1] > bounds.ymax() ||
        x[2] < bounds.zmin() || x[2] > bounds.zmax())
      return 1;
    // q: beyond the nearer of the box's sides normal to the first axis, in a fixed oblique direction.
    const double span = std::max({bounds.xmax() - bounds.xmin(), bounds.ymax() - bounds.ymin(), bounds.zmax() - bounds.zmin()});
    const bool up = 2 * x[0] >= bounds.xmin() + bounds.xmax();
    double qx = up ? bounds.xmax() + span : bounds.xmin() - span;
    if (!std::isfinite(qx) || (up ? !(qx > bounds.xmax()) : !(qx < bounds.xmin())))
      qx = std::nextafter(up ? bounds.xmax() : bounds.xmin(), up ? HUGE_VAL : -HUGE_VAL);
    const double run = std::abs(qx - x[0]);
    const double qy = x[1] + 0.3 * run, qz = x[2] + 0.17 * run;
    const Point3 p = point(x);
    const Point3 q(qx, std::isfinite(qy) ? qy : x[1], std::isfinite(qz) ? qz : x[2]);

    std::vector<Face> found;
    tree.all_intersected_primitives(Kernel::Segment_3(p, q), std::back_inserter(found));
    std::size_t crossings = 0;
    for (Face face : found) {
      const auto& t = faces[face.idx()];
      const Point3 a = mesh.point(VertexIndex(t[0])), b = mesh.point(VertexIndex(t[1])), c = mesh.point(VertexIndex(t[2]));
      const CGAL::Orientation side_x = CGAL::orientation(a, b, c, p);
      if (side_x == CGAL::COPLANAR) {
        // The segment meets the face's plane only at x (q_ε is off it).
        if (CGAL::do_intersect(Kernel::Triangle_3(a, b, c), p)) return 0;
        continue;
      }
      if (perturbed_orientation(a, b, c, q) == static_cast<int>(side_x)) continue;  // x, q_ε on one side
      // The line through x and q_ε meets the face's interior iff it passes on the same side of
      // its three edges (none of these signs is 0: x is off the plane, so not on an edge's line).
      const int s = perturbed_orientation(p, a, b, q);
      if (perturbed_orientation(p, b, c, q) == s && perturbed_orientation(p, c, a, q) == s) ++crossings;
    }
    return crossings % 2 == 1 ? -1 : 1;
  }

  const Vec3& vertex(int f, int k) const { return points[faces[f][k]]; }

  //! The faces whose triangle meets the box [lo − margin, hi + margin] (exact), ascending.
  std::vector<int> faces_in_box(const Vec3& lo, const Vec3& hi, double margin) const {
    const CGAL::Bbox_3 query(lo[0] - margin, lo[1] - margin, lo[2] - margin, hi[0] + margin, hi[1] + margin,
                             hi[2] + margin);
    std::vector<Face> found;
    tree.all_intersected_primitives(query, std::back_inserter(found));
    std::vector<int> out;
    for (Face f : found) out.push_back(static_cast<int>(f.idx()));
    std::sort(out.begin(), out.end());
    return out;
  }

  //! The faces meeting the bounding box of a facet polygon (plane frame) or of a 3-D domain,
  //! enlarged by face_margin.
  std::vector<int> faces_near(const Plane& plane, const Domain& domain) const {
    BoundingBox box;
    for (double u : {domain.box.bounds[0][0], domain.box.bounds[0][1]})
      for (double v : {domain.box.bounds[1][0], domain.box.bounds[1][1]}) box.add(plane.o + u * plane.a + v * plane.b);
    return faces_in_box(box.lo, box.hi, face_margin);
  }
  std::vector<int> faces_near(const Domain& domain) const {
    const auto& b = domain.box.bounds;
    return faces_in_box({b[0][0], b[1][0], b[2][0]}, {b[0][1], b[1][1], b[2][1]}, face_margin);
  }

  //! The faces on the two sides of the edge from vertex u to vertex w (left: u→w in its order).
  std::array<int, 2> edge_faces(int u, int w) const {
    const auto h = mesh.halfedge(VertexIndex(u), VertexIndex(w));
    return {static_cast<int>(mesh.face(h).idx()), static_cast<int>(mesh.face(mesh.opposite(h)).idx())};
  }

  //! The section of the given faces by the plane (sides under the perturbation): its vertices
  //! are the mesh edges crossing the plane (sorted vertex pairs), each crossing face joins two.
  SectionGraph section(const Plane& plane, const std::vector<int>& faces_used) const {
    SectionGraph g;
    for (int f : faces_used) {
      std::array<int, 3> side{};
      for (int k = 0; k < 3; ++k) side[k] = plane.side(vertex(f, k));
      if (side[0] == side[1] && side[1] == side[2]) continue;
      std::vector<SectionGraph::Edge> crossing;
      for (int k = 0; k < 3; ++k) {
        if (side[k] == side[(k + 1) % 3]) continue;
        const int u = faces[f][k], w = faces[f][(k + 1) % 3];
        const SectionGraph::Edge e{std::min(u, w), std::max(u, w)};
        if (!g.at.count(e)) g.at[e] = plane.crossing(points[e.first], points[e.second]);
        crossing.push_back(e);
      }
      g.next[crossing[0]].push_back(crossing[1]);
      g.next[crossing[1]].push_back(crossing[0]);
    }
    return g;
  }

  //! Whether w is higher than v in direction d (ties: the larger index is higher).
  bool higher(int w, int v, const Vec3& d) const {
    const int s = dot_difference_sign(points[w], points[v], d);
    return s != 0 ? s > 0 : w > v;
  }

  //! How face f faces d under the perturbation (exactly parallel counts as facing).
  int facing(int f, const Vec3& d) const {
    return facing_sign(vertex(f, 0), vertex(f, 1), vertex(f, 2), d) >= 0 ? 1 : -1;
  }
};

MeshOracle::MeshOracle(const SurfaceMesh& input, const Box3& input_box)
    : box_(input_box), stats_(6), scale_exponent_(unit_scale_exponent(input_box)) {
  if (input.number_of_faces() == 0) throw PreconditionViolation("MeshOracle: the mesh has no face");
  if (!CGAL::is_closed(input) || !CGAL::is_triangle_mesh(input))
    throw PreconditionViolation("MeshOracle: the mesh is not a closed triangle mesh");
  // At unit scale (meshing/inputs/unit_scale.h): the mesh and the box times 2^-k, exactly.
  SurfaceMesh mesh = input;
  scale_mesh(mesh, -scale_exponent_);
  box_ = scaled_box(input_box, -scale_exponent_);
  const Box3& box = box_;
  Box3 vertices{box.hi, box.lo};
  for (const Point3& p : mesh.points())
    for (int k = 0; k < 3; ++k) {
      if (!(p[k] > box.lo[k] && p[k] < box.hi[k]))
        throw PreconditionViolation("MeshOracle: a vertex of the mesh is not strictly inside the box");
      vertices.lo[k] = std::min(vertices.lo[k], p[k]);
      vertices.hi[k] = std::max(vertices.hi[k], p[k]);
    }
  clip_box_ = clip_box_around(vertices, box);
  impl_ = std::make_unique<Impl>(mesh);
  impl_->feature_tolerance = tolerances::mesh_feature_relative_distance * box_.diagonal();
  impl_->face_margin = tolerances::face_membership_relative_tolerance * box_.diagonal();
}

MeshOracle::~MeshOracle() = default;

void MeshOracle::set_run_controls(std::uint64_t, std::optional<std::chrono::steady_clock::time_point>) {}

SolveResult MeshOracle::finish(int index, SolveResult result, std::chrono::steady_clock::time_point start) {
  if (result.undecided.empty()) result.status = SolveStatus::complete;
  const std::lock_guard<std::mutex> lock(statistics_mutex_);
  auto& s = stats_[index];
  ++s.calls;
  s.certified_roots += result.roots.size();
  s.undecided += result.undecided.size();
  s.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

namespace {

// How the line through pa, pb meets Σ at a mesh vertex x strictly between them (collinear with
// them exactly): it crosses, it touches, or it runs in the plane of a face of x's star.
enum class VertexPassage { crosses, touches, in_face_plane };

// Near x, Σ is the cone from x over the link polygon a_0 … a_{k−1} (cyclic), and the line's two
// rays from x leave in the directions ±D, D = pb − pa.  Let χ(u) be 1 if the ray x + t·u
// (small t > 0) runs inside the solid, else 0.  Seen along D, i.e. projected onto the plane
// ⟂ D through x, the link becomes a closed polygon around the projection of x; its winding
// number about that point is χ(D) − χ(−D) (crossing the cone changes χ by one, and the
// projection sends the unit sphere minus ±D onto the punctured plane, keeping the angle about
// the axis).  So the line crosses Σ at x iff the winding number is ±1, and touches iff it is 0.
// It is counted by the signed crossings of a half-plane bounded by the line (through a point c
// off the line): with y(w) = orientation(pa, pb, c, w) and the turn orientation(pa, pb, a_i,
// a_{i+1}) — both exact — this is the crossing-number rule in the projected plane, with
// y ≤ 0 / y > 0 as the two sides (a link vertex on the half-plane is not counted twice).  A turn
// of zero means a_i, a_{i+1} and the line are coplanar: the line lies in the plane of the face
// x a_i a_{i+1}, and nothing is decided.
VertexPassage vertex_passage(const std::vector<Point3>& link, const Point3& pa, const Point3& pb) {
  Point3 c = pa;
  for (int k = 0; k < 3; ++k) {
    c = Point3(pa.x() + (k == 0), pa.y() + (k == 1), pa.z() + (k == 2));
    if (!CGAL::collinear(pa, pb, c)) break;
  }
  auto up = [&](const Point3& w) { return CGAL::orientation(pa, pb, c, w) == CGAL::POSITIVE; };
  int winding = 0;
  for (std::size_t i = 0; i < link.size(); ++i) {
    const Point3& a = link[i];
    const Point3& b = link[(i + 1) % link.size()];
    const auto turn = CGAL::orientation(pa, pb, a, b);
    if (turn == CGAL::COPLANAR) return VertexPassage::in_face_plane;
    if (!up(a) && up(b) && turn == CGAL::POSITIVE) ++winding;
    if (up(a) && !up(b) && turn == CGAL::NEGATIVE) --winding;
  }
  return winding != 0 ? VertexPassage::crosses : VertexPassage::touches;
}

// The contacts of the segment [A, B] = {p + t·v : t ∈ [t0, t1]} with the mesh faces it meets,
// by kind: crossings inside a face, contacts through an edge or a vertex (all exact
// orientations), ends on a face's plane, and faces in whose plane it runs.
class SegmentContacts {
 public:
  SegmentContacts(const std::vector<Vec3>& points, const std::vector<std::array<int, 3>>& faces, const Vec3& p,
                  const Vec3& v, double t0, double t1)
      : points_(points), faces_(faces), p_(p), v_(v), t0_(t0), t1_(t1), A_(p + t0 * v), B_(p + t1 * v),
        pa_(point(A_)), pb_(point(B_)) {}

  const Point3& pa() const { return pa_; }
  const Point3& pb() const { return pb_; }

  // Classifies the contact with face f.
  void add_face(int f) {
    const Point3 a = point(vertex(f, 0)), b = point(vertex(f, 1)), c = point(vertex(f, 2));
    const int sa = CGAL::orientation(a, b, c, pa_), sb = CGAL::orientation(a, b, c, pb_);
    if (sa == 0 && sb == 0) {
      coplanar_ = true;
      return;
    }
    if (sa == 0 || sb == 0) {
      (sa == 0 ? zero_at_t0_ : zero_at_t1_) = true;
      return;
    }
    // A and B are on opposite sides; where the line passes relative to the face's edges.
    int zeros = 0, zero_edge = -1;
    for (int k = 0; k < 3; ++k) {
      const Point3 x = point(vertex(f, k)), y = point(vertex(f, (k + 1) % 3));
      if (CGAL::orientation(pa_, pb_, x, y) == CGAL::COPLANAR) {
        ++zeros;
        zero_edge = k;
      }
    }
    if (zeros == 0) {
      interior_.push_back({crossing_t(f), f});
    } else if (zeros == 1) {
      const int u = faces_[f][zero_edge], w = faces_[f][(zero_edge + 1) % 3];
      edge_hits_[{std::min(u, w), std::max(u, w)}].push_back({f, sa});
    } else {
      // Two edges through the line: it passes through their common vertex.
      for (int k = 0; k < 3; ++k) {
        const Point3 x = point(vertex(f, k));
        if (CGAL::collinear(pa_, pb_, x)) vertex_hits_.insert(faces_[f][k]);
      }
    }
  }

  // Whether the segment runs in the plane of a face.
  bool coplanar() const { return coplanar_; }

  // The roots and undecided regions of the contacts (`link`: each vertex's link polygon).
  void report(const std::vector<std::vector<int>>& link, SolveResult& result) const {
    for (const auto& [t, f] : interior_) result.roots.push_back(point_root({t}, p_ + t * v_));
    report_edge_hits(result);
    report_vertex_hits(link, result);
    if (zero_at_t0_) result.undecided.push_back(point_region({t0_}, A_, UndecidedReason::boundary_root));
    if (zero_at_t1_) result.undecided.push_back(point_region({t1_}, B_, UndecidedReason::boundary_root));
    if (coplanar_) {
      UndecidedBox r;
      r.box.bounds.push_back({t0_, t1_});
      r.reason = UndecidedReason::non_isolated;
      r.world = 0.5 * (A_ + B_);
      result.undecided.push_back(r);
    }
  }

 private:
  const Vec3& vertex(int f, int k) const { return points_[faces_[f][k]]; }

  // The parameter of the segment's crossing with the plane of face f (A and B on opposite sides).
  double crossing_t(int f) const {
    const Vec3& a = vertex(f, 0);
    const Vec3 n = cross(vertex(f, 1) - a, vertex(f, 2) - a);
    const double ha = dot(A_ - a, n), hb = dot(B_ - a, n);
    const double s = std::clamp(ha == hb ? 0.5 : ha / (ha - hb), 0.0, 1.0);
    return t0_ + s * (t1_ - t0_);
  }

  // The line crosses Σ at an edge iff A lies on the same side of both faces' planes (the two
  // faces, seen along the line, lie on opposite sides of the edge); otherwise it touches.
  void report_edge_hits(SolveResult& result) const {
    for (const auto& [edge, faces] : edge_hits_) {
      const double t = crossing_t(faces.front().first);
      const Vec3 x = p_ + t * v_;
      if (faces.size() == 2 && faces[0].second == faces[1].second)
        result.roots.push_back(point_root({t}, x));
      else
        result.undecided.push_back(point_region({t}, x, UndecidedReason::singular_root));
    }
  }

  // The line crosses Σ at a vertex iff vertex_passage() says so; otherwise it touches, or it
  // runs in a face's plane.
  void report_vertex_hits(const std::vector<std::vector<int>>& link, SolveResult& result) const {
    for (int vtx : vertex_hits_) {
      const Vec3& x = points_[vtx];
      const double t = std::clamp(t0_ + dot(x - A_, B_ - A_) / dot(B_ - A_, B_ - A_) * (t1_ - t0_), t0_, t1_);
      std::vector<Point3> polygon;
      for (int w : link[vtx]) polygon.push_back(point(points_[w]));
      if (vertex_passage(polygon, pa_, pb_) == VertexPassage::crosses)
        result.roots.push_back(point_root({t}, x));
      else
        result.undecided.push_back(point_region({t}, x, UndecidedReason::singular_root));
    }
  }

  const std::vector<Vec3>& points_;
  const std::vector<std::array<int, 3>>& faces_;
  const Vec3 p_, v_;
  const double t0_, t1_;
  const Vec3 A_, B_;
  const Point3 pa_, pb_;
  bool zero_at_t0_ = false, zero_at_t1_ = false, coplanar_ = false;
  // Contacts through a mesh edge: per edge (sorted vertex pair), the faces' plane sides of A.
  std::map<std::pair<int, int>, std::vector<std::pair<int, int>>> edge_hits_;  // edge -> (face, side of A)
  std::set<int> vertex_hits_;
  std::vector<std::pair<double, int>> interior_;  // (t, face)
};

}  // namespace

SolveResult MeshOracle::surface_line(const Vec3& p, const Vec3& v, double t0, double t1) {
  const auto start = std::chrono::steady_clock::now();
  const Impl& m = *impl_;
  SolveResult result;
  if (!(t0 < t1)) return finish(line_index, std::move(result), start);
  SegmentContacts contacts(m.points, m.faces, p, v, t0, t1);
  std::vector<Face> hit;
  m.tree.all_intersected_primitives(Kernel::Segment_3(contacts.pa(), contacts.pb()), std::back_inserter(hit));
  std::sort(hit.begin(), hit.end());
  result.counters.boxes = hit.size();
  for (Face face : hit) contacts.add_face(static_cast<int>(face.idx()));
  contacts.report(m.link, result);
  std::sort(result.roots.begin(), result.roots.end(),
            [](const CertifiedRoot& x, const CertifiedRoot& y) { return x.midpoint[0] < y.midpoint[0]; });
  result.status = contacts.coplanar() ? SolveStatus::non_isolated : SolveStatus::undecided;
  return finish(line_index, std::move(result), start);
}

SolveResult MeshOracle::surface_critical(const Vec3& d, const Domain& domain, std::size_t) {
  const auto start = std::chrono::steady_clock::now();
  const Impl& m = *impl_;
  SolveResult result;
  for (std::size_t v = 0; v < m.points.size(); ++v) {
    const Vec3& x = m.points[v];
    if (!in_domain(domain, {x[0], x[1], x[2]}, 0)) continue;
    std::size_t above = 0;
    for (int w : m.link[v]) above += m.higher(w, static_cast<int>(v), d) ? 1 : 0;
    if (above == 0 || above == m.link[v].size()) result.roots.push_back(point_root({x[0], x[1], x[2]}, x));
  }
  result.counters.boxes = m.points.size();
  return finish(critical_index, std::move(result), start);
}

SolveResult MeshOracle::surface_plane_contact(const Vec3& o, const Vec3& a, const Vec3& b, const Domain& domain) {
  const auto start = std::chrono::steady_clock::now();
  const Impl& m = *impl_;
  const Plane plane(o, a, b);
  SolveResult result;
  std::set<int> seen;
  const auto near = m.faces_near(plane, domain);
  result.counters.boxes = near.size();
  for (int f : near)
    for (int k = 0; k < 3; ++k) {
      const int v = m.faces[f][k];
      if (!seen.insert(v).second || plane.exact_side(m.points[v]) != 0) continue;
      const auto uv = plane.uv(m.points[v]);
      if (!in_domain(domain, uv, 0)) continue;
      // Σ ∩ Π is a simple arc through v iff the link changes side exactly twice, none on Π.
      std::vector<int> sides;
      for (int w : m.link[v]) sides.push_back(plane.exact_side(m.points[w]));
      const bool on_plane = std::count(sides.begin(), sides.end(), 0) > 0;
      int changes = 0;
      for (std::size_t i = 0; i < sides.size(); ++i) changes += sides[i] != sides[(i + 1) % sides.size()] ? 1 : 0;
      if (on_plane || changes != 2) result.roots.push_back(point_root(uv, m.points[v]));
    }
  return finish(contact_index, std::move(result), start);
}

SolveResult MeshOracle::curve_critical(const Vec3& o, const Vec3& a, const Vec3& b, const Domain& domain) {
  const auto start = std::chrono::steady_clock::now();
  const Impl& m = *impl_;
  const Plane plane(o, a, b);
  SolveResult result;
  const auto near = m.faces_near(plane, domain);
  result.counters.boxes = near.size();
  const SectionGraph section = m.section(plane, near);
  const auto& next = section.next;
  const auto& at = section.at;
  for (const auto& [e, neighbours] : next) {
    if (neighbours.size() != 2) continue;  // its other face is outside F's bounding box
    const Vec3& x = at.at(e);
    const auto uv = plane.uv(x);
    if (!in_domain(domain, uv, m.face_margin)) continue;
    // The heights of the neighbours relative to e's, exactly (a tie counts both ways).  e is bound by
    // an init-capture: C++17 lambdas cannot capture a structured binding.
    auto relative_height = [&, &e = e](const SectionGraph::Edge& g) {
      return crossing_height_sign(plane, m.points[g.first], m.points[g.second], m.points[e.first],
                                  m.points[e.second], a);
    };
    const int s0 = relative_height(neighbours[0]), s1 = relative_height(neighbours[1]);
    if ((s0 >= 0 && s1 >= 0) || (s0 <= 0 && s1 <= 0)) result.roots.push_back(point_root(uv, x));
  }
  return finish(curve_index, std::move(result), start);
}

SolveResult MeshOracle::silhouette_plane(const Vec3& o, const Vec3& a, const Vec3& b, const Vec3& d,
                                         const Domain& domain) {
  const auto start = std::chrono::steady_clock::now();
  const Impl& m = *impl_;
  const Plane plane(o, a, b);
  SolveResult result;
  std::set<std::pair<int, int>> seen;
  const auto near = m.faces_near(plane, domain);
  result.counters.boxes = near.size();
  for (int f : near)
    for (int k = 0; k < 3; ++k) {
      const int u = m.faces[f][k], w = m.faces[f][(k + 1) % 3];
      if (!seen.insert({std::min(u, w), std::max(u, w)}).second) continue;
      if (plane.side(m.points[u]) == plane.side(m.points[w])) continue;
      const auto fg = m.edge_faces(u, w);
      if (m.facing(fg[0], d) == m.facing(fg[1], d)) continue;
      const Vec3 x = plane.crossing(m.points[std::min(u, w)], m.points[std::max(u, w)]);
      const auto uv = plane.uv(x);
      if (in_domain(domain, uv, 0)) result.roots.push_back(point_root(uv, x));
    }
  return finish(sil_plane_index, std::move(result), start);
}

SolveResult MeshOracle::silhouette_critical(const Vec3& d, const Vec3& d2, const Domain& domain) {
  const auto start = std::chrono::steady_clock::now();
  const Impl& m = *impl_;
  SolveResult result;
  std::set<int> seen;
  const auto near = m.faces_near(domain);
  result.counters.boxes = near.size();
  for (int f : near)
    for (int k = 0; k < 3; ++k) {
      const int v = m.faces[f][k];
      if (!seen.insert(v).second) continue;
      const Vec3& x = m.points[v];
      if (!in_domain(domain, {x[0], x[1], x[2]}, 0)) continue;
      // The silhouette edges at v and whether their other ends lie above v in direction d2.
      std::size_t count = 0, above = 0;
      for (int w : m.link[v]) {
        const auto fg = m.edge_faces(v, w);
        if (m.facing(fg[0], d) == m.facing(fg[1], d)) continue;
        ++count;
        above += m.higher(w, v, d2) ? 1 : 0;
      }
      if (count == 0) continue;
      if (count > 2 || above == 0 || above == count) result.roots.push_back(point_root({x[0], x[1], x[2]}, x));
    }
  return finish(sil_critical_index, std::move(result), start);
}

SolveResult MeshOracle::solve(const std::string& primitive, const std::vector<double>& q, const Domain& domain,
                              std::size_t box_budget) {
  auto need = [&](std::size_t n) {
    if (q.size() != n)
      throw PreconditionViolation("MeshOracle::solve: " + std::to_string(q.size()) + " parameters given, " + primitive +
                                  " has " + std::to_string(n));
  };
  auto at = [&](std::size_t i) { return Vec3{q[i], q[i + 1], q[i + 2]}; };
  if (primitive == "surface_line") throw PreconditionViolation("MeshOracle::solve: use surface_line() for surface_line");
  if (primitive == "surface_critical") {
    need(6);
    return surface_critical(cross(at(0), at(3)), domain, box_budget);
  }
  if (primitive == "surface_plane_contact") {
    need(9);
    return surface_plane_contact(at(0), at(3), at(6), domain);
  }
  if (primitive == "curve_critical") {
    need(9);
    return curve_critical(at(0), at(3), at(6), domain);
  }
  if (primitive == "silhouette_plane") {
    need(12);
    return silhouette_plane(at(0), at(3), at(6), at(9), domain);
  }
  if (primitive == "silhouette_critical") {
    need(6);
    return silhouette_critical(at(0), at(3), domain);
  }
  throw InvalidInput("the mesh oracle answers the six primitives of section 5.2 only, not " + primitive);
}

std::vector<MeshOracle::Polyline> MeshOracle::section(const Vec3& o, const Vec3& a, const Vec3& b) const {
  const Impl& m = *impl_;
  std::vector<int> all(m.faces.size());
  for (std::size_t f = 0; f < all.size(); ++f) all[f] = static_cast<int>(f);
  const SectionGraph g = m.section(Plane(o, a, b), all);
  std::vector<Polyline> out;
  std::set<SectionGraph::Edge> visited;
  for (const auto& [first, unused] : g.next) {
    if (visited.count(first)) continue;
    // Walk from `first` until the walk returns to it (closed) or cannot go on.
    Polyline line;
    SectionGraph::Edge previous{-1, -1}, current = first;
    while (true) {
      visited.insert(current);
      line.points.push_back(g.at.at(current));
      const auto& n = g.next.at(current);
      const auto step = std::find_if(n.begin(), n.end(), [&](const SectionGraph::Edge& e) { return e != previous; });
      if (step == n.end()) break;
      if (*step == first) {
        line.closed = true;
        break;
      }
      if (visited.count(*step)) break;
      previous = current;
      current = *step;
    }
    out.push_back(std::move(line));
  }
  return out;
}

SurfaceOracle::ConeAnswer MeshOracle::prove_gradient_cone(const AffineChart& chart, const Domain& domain,
                                                          const Vec3& w) {
  const Impl& m = *impl_;
  const std::vector<int> near = chart.columns.size() == 2
                                    ? m.faces_near(Plane(chart.origin, chart.columns[0], chart.columns[1]), domain)
                                    : m.faces_near(domain);
  // One strict sign of ⟨n_f, w⟩ on every face near P (none near: Σ misses P).
  int sign = 0;
  bool proved = true;
  for (int f : near) {
    const int s = facing_sign(m.vertex(f, 0), m.vertex(f, 1), m.vertex(f, 2), w);
    if (s == 0 || (sign != 0 && s != sign)) {
      proved = false;
      break;
    }
    sign = s;
  }
  const std::lock_guard<std::mutex> lock(statistics_mutex_);
  ++cone_attempts_;
  cone_proved_ += proved ? 1 : 0;
  ConeAnswer answer;
  answer.proved = proved;
  return answer;
}

int MeshOracle::gradient_sign(const Vec3& a, const Vec3& b, const Vec3& w) const {
  const Impl& m = *impl_;
  std::vector<Face> found;
  if (a == b)
    m.tree.all_intersected_primitives(CGAL::Bbox_3(a[0], a[1], a[2], a[0], a[1], a[2]), std::back_inserter(found));
  else
    m.tree.all_intersected_primitives(Kernel::Segment_3(point(a), point(b)), std::back_inserter(found));
  // One strict sign on every face the segment meets: every crossing goes the same way, so there
  // is at most one (crossings of a closed surface along a line alternate).  No face: vacuous.
  int sign = 0;
  for (Face face : found) {
    const int f = static_cast<int>(face.idx());
    const int s = facing_sign(m.vertex(f, 0), m.vertex(f, 1), m.vertex(f, 2), w);
    if (s == 0 || (sign != 0 && s != sign)) return 0;
    sign = s;
  }
  return sign == 0 ? 1 : sign;
}

int MeshOracle::value_sign(const Vec3& lo, const Vec3& hi) const {
  const Impl& m = *impl_;
  if (lo == hi) return m.side_of(lo);
  if (m.tree.do_intersect(CGAL::Bbox_3(lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]))) return 0;
  return value_sign(lo);
}

Vec3 MeshOracle::normal(const Vec3& x) const {
  const Impl& m = *impl_;
  const auto [c, face] = m.tree.closest_point_and_primitive(point(x));
  const int f = static_cast<int>(face.idx());
  const Vec3 y = vec(c);
  const double tol = m.feature_tolerance;
  // At a vertex of f: the vertex normal; on an edge of f: the mean of its two faces' normals.
  for (int k = 0; k < 3; ++k)
    if (distance(y, m.vertex(f, k)) <= tol) return m.vertex_normal[m.faces[f][k]];
  for (int k = 0; k < 3; ++k) {
    const Vec3 &p = m.vertex(f, k), &q = m.vertex(f, (k + 1) % 3);
    const double s = std::clamp(dot(y - p, q - p) / dot(q - p, q - p), 0.0, 1.0);
    if (distance(y, p + s * (q - p)) <= tol) {
      const auto fg = m.edge_faces(m.faces[f][k], m.faces[f][(k + 1) % 3]);
      const Vec3 n = m.face_normal[fg[0]] + m.face_normal[fg[1]];
      return norm(n) > 0 ? normalized(n) : m.face_normal[f];
    }
  }
  return m.face_normal[f];
}

std::optional<Vec3> MeshOracle::project(const Vec3& x) const {
  const Vec3 y = vec(impl_->tree.closest_point(point(x)));
  if (!box_.contains(y)) return std::nullopt;
  return y;
}

nlohmann::json MeshOracle::statistics_json() const {
  const std::lock_guard<std::mutex> lock(statistics_mutex_);
  nlohmann::json per = nlohmann::json::object();
  Counts total;
  for (int i = 0; i < 6; ++i) {
    const auto& s = stats_[i];
    per[primitive_names[i]] = {
        {"calls", s.calls}, {"certified_roots", s.certified_roots}, {"undecided", s.undecided}, {"seconds", s.seconds}};
    total.calls += s.calls;
    total.certified_roots += s.certified_roots;
    total.undecided += s.undecided;
    total.seconds += s.seconds;
  }
  return {{"systems", total.calls},
          {"certified_roots", total.certified_roots},
          {"undecided", total.undecided},
          {"seconds", total.seconds},
          {"backend", "mesh"},
          {"faces", impl_->faces.size()},
          {"per_primitive", per},
          {"cone_certificates", {{"attempts", cone_attempts_}, {"proved", cone_proved_}}}};
}

}  // namespace delmesh
