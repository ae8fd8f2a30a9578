#include "meshing/voronoi_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/tolerances.h"
#include "meshing/detail/convex_polytope.h"
#include "meshing/detail/vec3.h"
#include "solvers/query_geometry.h"

namespace delmesh {

using namespace detail;

namespace {

using P2 = std::array<double, 2>;

// Sutherland–Hodgman: keeps {w : <n, w> <= c} of a convex polygon, written to `out`.
void clip_polygon(const std::vector<P2>& poly, const P2& n, double c, std::vector<P2>& out) {
  out.clear();
  const std::size_t m = poly.size();
  for (std::size_t i = 0; i < m; ++i) {
    const P2& a = poly[i];
    const P2& b = poly[(i + 1) % m];
    const double sa = n[0] * a[0] + n[1] * a[1] - c, sb = n[0] * b[0] + n[1] * b[1] - c;
    if (sa <= 0) out.push_back(a);
    if ((sa < 0 && sb > 0) || (sa > 0 && sb < 0)) {
      const double s = sa / (sa - sb);
      out.push_back({a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])});
    }
  }
}

double polygon_area(const std::vector<P2>& poly) {
  double area = 0;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const P2& a = poly[i];
    const P2& b = poly[(i + 1) % poly.size()];
    area += a[0] * b[1] - a[1] * b[0];
  }
  return 0.5 * area;
}

Vec3 circumcentre(const Vec3& p, const Vec3& q, const Vec3& r) {
  const Vec3 a = q - p, b = r - p;
  const Vec3 axb = cross(a, b);
  const double d = 2 * dot(axb, axb);
  const Vec3 num = cross(dot(a, a) * b - dot(b, b) * a, axb);
  return p + (1.0 / d) * num;
}

// Circumcentre of the tetrahedron pqrs (floating point).
Vec3 circumcentre(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s) {
  const Vec3 a = q - p, b = r - p, c = s - p;
  const double d = 2 * dot(a, cross(b, c));
  const Vec3 num = dot(a, a) * cross(b, c) + dot(b, b) * cross(c, a) + dot(c, c) * cross(a, b);
  return p + (1.0 / d) * num;
}

// The edge of t in dimension 3 from the circumcentres of its two cells: a segment between them,
// or (one cell infinite) a ray from the finite one away from its apex, clipped by the box.
void edge_from_cells(const Delaunay& del, const std::array<VertexId, 2>& apexes, const Box3& box, VoronoiEdge& e) {
  const auto clipped = clip_line_to_box(e.point, e.direction, box);
  if (!clipped) return;
  const Vec3& p = del.point(e.triangle[0]);
  const Vec3& q = del.point(e.triangle[1]);
  const Vec3& r = del.point(e.triangle[2]);
  double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
  if (apexes[0] >= 0 && apexes[1] >= 0) {
    const double s0 = dot(circumcentre(p, q, r, del.point(apexes[0])) - e.point, e.direction);
    const double s1 = dot(circumcentre(p, q, r, del.point(apexes[1])) - e.point, e.direction);
    lo = std::min(s0, s1);
    hi = std::max(s0, s1);
  } else {
    const VertexId apex = apexes[0] >= 0 ? apexes[0] : apexes[1];
    const Vec3& o = del.point(apex);
    const double s = dot(circumcentre(p, q, r, o) - e.point, e.direction);
    // The ray leaves the hull on the side of t away from the finite cell's apex.
    if (dot(o - p, e.direction) > 0)
      hi = s;
    else
      lo = s;
  }
  e.at_vertex0 = lo > (*clipped)[0];
  e.at_vertex1 = hi < (*clipped)[1];
  if (!(lo < hi)) {
    const double m = 0.5 * (lo + hi);
    e.degenerate = m >= (*clipped)[0] && m <= (*clipped)[1];
    e.t0 = e.t1 = m;
    return;
  }
  e.t0 = std::max(lo, (*clipped)[0]);
  e.t1 = std::min(hi, (*clipped)[1]);
  e.valid = e.t0 < e.t1;
}

}  // namespace

bool half_spaces_contain(const Domain& domain, const std::vector<double>& u, double tolerance) {
  for (const auto& h : domain.half_spaces) {
    double s = 0, nn = 0;
    for (std::size_t k = 0; k < u.size() && k < h.normal.size(); ++k) {
      s += h.normal[k] * u[k];
      nn += h.normal[k] * h.normal[k];
    }
    if (nn == 0) continue;
    if ((s - h.offset) / std::sqrt(nn) > tolerance) return false;
  }
  return true;
}

Vec3 VoronoiFacet::world(double u, double v) const { return origin + u * a + v * b; }

std::array<double, 2> VoronoiFacet::plane_coordinates(const Vec3& x) const {
  return {dot(x - origin, a), dot(x - origin, b)};
}

bool VoronoiFacet::contains(double u, double v, double tolerance) const {
  return valid && half_spaces_contain(domain, {u, v}, tolerance);
}

bool VoronoiCell::contains(const Vec3& x, double tolerance) const {
  if (!valid) return false;
  for (int k = 0; k < 3; ++k)
    if (x[k] < domain.box.bounds[k][0] - tolerance || x[k] > domain.box.bounds[k][1] + tolerance)
      return false;
  return half_spaces_contain(domain, {x[0], x[1], x[2]}, tolerance);
}

VoronoiEdge voronoi_edge(const Delaunay& del, const TriangleKey& t, const Box3& box,
                         const std::array<VertexId, 2>* known_apexes) {
  VoronoiEdge e;
  e.triangle = t;
  const Vec3& p = del.point(t[0]);
  const Vec3& q = del.point(t[1]);
  const Vec3& r = del.point(t[2]);
  const Vec3 n = cross(q - p, r - p);
  if (!(norm(n) > 0)) return e;
  e.point = circumcentre(p, q, r);
  e.direction = normalized(n);
  if (const auto apexes = known_apexes ? std::optional(*known_apexes) : del.triangle_apexes(t)) {
    edge_from_cells(del, *apexes, box, e);
    return e;
  }
  const auto clipped = clip_line_to_box(e.point, e.direction, box);
  if (!clipped) return e;
  double t0 = (*clipped)[0], t1 = (*clipped)[1];
  bool v0 = false, v1 = false;
  for (VertexId s : del.neighbours(t[0])) {
    if (s == t[1] || s == t[2]) continue;
    const Vec3& x = del.point(s);
    const Vec3 w = x - p;
    const double slope = dot(w, e.direction);
    const double rhs = dot(w, 0.5 * (x + p) - e.point);
    const double scale = norm(w);
    if (std::abs(slope) <= 1e-15 * scale) {
      if (rhs < 0) return e;  // the whole line is outside V_p
      continue;
    }
    const double bound = rhs / slope;
    if (slope > 0) {
      if (bound < t1) { t1 = bound; v1 = true; }
    } else {
      if (bound > t0) { t0 = bound; v0 = true; }
    }
  }
  e.t0 = t0;
  e.t1 = t1;
  e.at_vertex0 = v0;
  e.at_vertex1 = v1;
  e.valid = t0 < t1;
  return e;
}

VoronoiFacet voronoi_facet(const Delaunay& del, const EdgeKey& edge, const Box3& box, double rotation,
                           const std::vector<VertexId>* ring) {
  VoronoiFacet f;
  f.edge = edge;
  const Vec3& p = del.point(edge[0]);
  const Vec3& q = del.point(edge[1]);
  f.origin = 0.5 * (p + q);
  const auto section = plane_box_section(f.origin, q - p, box);
  if (!section) return f;
  const double c = std::cos(rotation), s = std::sin(rotation);
  f.a = c * section->frame.a + s * section->frame.b;
  f.b = (-s) * section->frame.a + c * section->frame.b;
  f.normal = section->frame.d;
  f.origin = section->origin;
  std::vector<P2> poly, scratch;
  poly.reserve(section->polygon.size() + 8);
  scratch.reserve(section->polygon.size() + 8);
  for (const auto& w : section->polygon) poly.push_back({c * w[0] + s * w[1], -s * w[0] + c * w[1]});
  // F = Π ∩ V_p ∩ B is cut out by the bisectors of p and the third vertices r of the triangles
  // pqr (each edge of the convex polygon F is the Voronoi edge of one pqr, and a convex polygon
  // is the intersection of the half-planes of its edges); other neighbours of p are redundant.
  std::vector<VertexId> cutting;
  if (ring && del.dimension() == 3) {
    cutting = *ring;
  } else if (del.dimension() == 3) {
    for (const auto& t : del.edge_triangles(edge))
      for (VertexId r : t)
        if (r != edge[0] && r != edge[1]) cutting.push_back(r);
  } else {
    cutting = del.neighbours(edge[0]);
  }
  for (VertexId r : cutting) {
    if (r == edge[1]) continue;
    const Vec3& x = del.point(r);
    const Vec3 w = x - p;
    const P2 n{dot(w, f.a), dot(w, f.b)};
    const double off = dot(w, 0.5 * (x + p) - f.origin);
    if (std::abs(n[0]) + std::abs(n[1]) <= 1e-15 * norm(w)) {
      if (off < 0) return f;
      continue;
    }
    clip_polygon(poly, n, off, scratch);
    poly.swap(scratch);
    if (poly.size() < 3) {
      f.degenerate = !poly.empty();
      f.polygon = std::move(poly);
      return f;
    }
  }
  // Drop (numerically) repeated vertices.
  std::vector<P2> clean;
  double extent = 0;
  for (const auto& w : poly) extent = std::max({extent, std::abs(w[0]), std::abs(w[1])});
  const double eps = 1e-12 * std::max(extent, box.diagonal());
  for (const auto& w : poly)
    if (clean.empty() || std::hypot(w[0] - clean.back()[0], w[1] - clean.back()[1]) > eps)
      clean.push_back(w);
  while (clean.size() >= 2 &&
         std::hypot(clean.front()[0] - clean.back()[0], clean.front()[1] - clean.back()[1]) <= eps)
    clean.pop_back();
  if (clean.size() < 3 || polygon_area(clean) <= eps * eps) {
    f.degenerate = true;
    f.polygon = std::move(poly);
    return f;
  }
  f.polygon = std::move(clean);
  f.domain = polygon_domain(f.polygon);
  f.valid = true;
  return f;
}

namespace {

// V_p from its vertices, when it is bounded: in dimension 3 the vertices of V_p are the
// circumcentres of the cells incident to p, so V_p ∩ B lies in their bounding box ∩ B; the
// bisectors of p and all its neighbours cut it out (a neighbour whose facet has no area adds a
// redundant half-space).  Nothing if a cell of p is infinite (V_p is unbounded) or the box ∩ B
// is empty.
std::optional<VoronoiCell> cell_from_vertices(const Delaunay& del, VertexId site, const Box3& box) {
  if (del.dimension() != 3) return std::nullopt;
  BoundingBox vertices;
  for (const auto& c : del.incident_cells(site)) {
    if (c[1] < 0 || c[2] < 0 || c[3] < 0) return std::nullopt;
    vertices.add(circumcentre(del.point(c[0]), del.point(c[1]), del.point(c[2]), del.point(c[3])));
  }
  // The computed circumcentres carry rounding errors: the box is enlarged by a margin, then
  // intersected with B.
  vertices.enlarge(tolerances::face_membership_relative_tolerance * box.diagonal());
  std::vector<std::array<double, 2>> bounds;
  for (int k = 0; k < 3; ++k) {
    bounds.push_back({std::max(vertices.lo[k], box.lo[k]), std::min(vertices.hi[k], box.hi[k])});
    if (!(bounds[k][0] < bounds[k][1])) return std::nullopt;
  }
  VoronoiCell cell;
  cell.site = site;
  cell.domain = Domain::from_box(std::move(bounds));
  cell.facet_neighbours = del.neighbours(site);
  const Vec3& p = del.point(site);
  for (VertexId s : cell.facet_neighbours) {
    const Vec3& x = del.point(s);
    const Vec3 w = x - p;
    cell.domain.half_spaces.push_back(HalfSpace{{w[0], w[1], w[2]}, dot(w, 0.5 * (x + p))});
  }
  cell.valid = true;
  return cell;
}

}  // namespace

VoronoiCell voronoi_cell(const Delaunay& del, VertexId site, const Box3& box) {
  if (auto cell = cell_from_vertices(del, site, box)) return std::move(*cell);
  VoronoiCell cell;
  cell.site = site;
  const Vec3& p = del.point(site);
  // One polytope per thread, reset for each cell: its buffers outlive the call.
  thread_local ConvexPolytope polytope;
  polytope.reset(box);
  // Nearest neighbours first: their bisectors cut the box down to about V_p at once, so most
  // later clips find every vertex inside and return early.
  std::vector<VertexId> neighbours = del.neighbours(site);
  std::vector<std::pair<double, VertexId>> by_distance;
  by_distance.reserve(neighbours.size());
  for (VertexId s : neighbours) {
    const Vec3 w = del.point(s) - p;
    by_distance.push_back({dot(w, w), s});
  }
  std::sort(by_distance.begin(), by_distance.end());
  for (std::size_t i = 0; i < neighbours.size(); ++i) neighbours[i] = by_distance[i].second;
  struct Plane {
    VertexId s;
    Vec3 w;
    double off;
  };
  std::vector<Plane> planes;
  planes.reserve(neighbours.size());
  for (VertexId s : neighbours) {
    const Vec3& x = del.point(s);
    const Vec3 w = x - p;
    const double off = dot(w, 0.5 * (x + p));
    polytope.clip(w, off, s);
    planes.push_back({s, w, off});
    if (polytope.empty()) return cell;
  }
  const auto bb = polytope.bounding_box();
  std::vector<std::array<double, 2>> bounds;
  for (int k = 0; k < 3; ++k) {
    if (!(bb[0][k] < bb[1][k])) return cell;
    bounds.push_back({bb[0][k], bb[1][k]});
  }
  cell.domain = Domain::from_box(bounds);
  for (const auto& f : polytope.faces())
    if (f.label >= 0) cell.facet_neighbours.push_back(f.label);
  std::sort(cell.facet_neighbours.begin(), cell.facet_neighbours.end());
  cell.facet_neighbours.erase(std::unique(cell.facet_neighbours.begin(), cell.facet_neighbours.end()),
                              cell.facet_neighbours.end());
  for (const auto& h : planes)
    if (std::binary_search(cell.facet_neighbours.begin(), cell.facet_neighbours.end(), h.s))
      cell.domain.half_spaces.push_back(HalfSpace{{h.w[0], h.w[1], h.w[2]}, h.off});
  cell.valid = true;
  return cell;
}

}  // namespace delmesh
