#include "meshing/voronoi/voronoi_geometry.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <tuple>

#include "common/errors.h"
#include "common/tolerances.h"
#include "meshing/core/detail/key_order.h"
#include "meshing/core/detail/vec3.h"
#include "meshing/voronoi/detail/convex_polytope.h"
#include "meshing/voronoi/detail/line_clip.h"
#include "solvers/query_geometry.h"
#include "symbolic/scalar_types.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

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

std::vector<std::array<double, 2>> polygon_bounds(const std::vector<P2>& poly) {
  std::vector<std::array<double, 2>> bounds{{poly[0][0], poly[0][0]}, {poly[0][1], poly[0][1]}};
  for (const auto& w : poly)
    for (int k = 0; k < 2; ++k) {
      bounds[k][0] = std::min(bounds[k][0], w[k]);
      bounds[k][1] = std::max(bounds[k][1], w[k]);
    }
  return bounds;
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

// The parameters on e's line of the ends of the Voronoi edge of e.triangle in dimension 3, before
// clipping by the box: the projections of the Voronoi vertices of its two cells (the vertices
// kept), or for a ray (one cell infinite) the finite vertex's at one end and ±∞ at the other.
struct CellEnds {
  double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
  Vec3 lo_vertex{}, hi_vertex{};
};

CellEnds cell_ends(const Delaunay& del, const VoronoiEdge& e, const std::array<VertexId, 2>& apexes) {
  const TriangleKey& t = e.triangle;
  auto vertex = [&](VertexId apex) { return voronoi_vertex(del, {t[0], t[1], t[2], apex}); };
  CellEnds ends;
  if (apexes[0] >= 0 && apexes[1] >= 0) {
    const Vec3 v0 = vertex(apexes[0]), v1 = vertex(apexes[1]);
    const double s0 = dot(v0 - e.point, e.direction), s1 = dot(v1 - e.point, e.direction);
    const bool first_low = s0 <= s1;
    ends.lo = first_low ? s0 : s1;
    ends.hi = first_low ? s1 : s0;
    ends.lo_vertex = first_low ? v0 : v1;
    ends.hi_vertex = first_low ? v1 : v0;
    return ends;
  }
  const VertexId apex = apexes[0] >= 0 ? apexes[0] : apexes[1];
  const Vec3 v = vertex(apex);
  const double s = dot(v - e.point, e.direction);
  // The ray leaves the hull on the side of t away from the finite cell's apex.  The apex's side is
  // the exact orientation of (t0, t1, t2, apex) against the normal (t1 − t0) × (t2 − t0), of which
  // e.direction is the rounded unit vector or its opposite (a sign the triangle's area decides):
  // a cell flat to rounding (samples on a planar part of Σ) puts the apex within rounding of
  // t's plane, where the sign of a dot product in doubles is not reliable.
  const auto exact_point = [&](VertexId v) {
    const auto& x = del.point(v);
    return CGAL::Epick::Point_3(x[0], x[1], x[2]);
  };
  const CGAL::Orientation side = CGAL::orientation(exact_point(t[0]), exact_point(t[1]), exact_point(t[2]), exact_point(apex));
  const bool apex_along_direction =
      side == CGAL::COPLANAR
          ? dot(del.point(apex) - del.point(t[0]), e.direction) > 0
          : (side == CGAL::POSITIVE) == (dot(cross(del.point(t[1]) - del.point(t[0]), del.point(t[2]) - del.point(t[0])), e.direction) > 0);
  if (apex_along_direction) {
    ends.hi = s;
    ends.hi_vertex = v;
  } else {
    ends.lo = s;
    ends.lo_vertex = v;
  }
  return ends;
}

// The edge of t in dimension 3 from the vertices of its two cells: a segment between them, or
// (one cell infinite) a ray from the finite one away from its apex, clipped by the box.
// `shared`, if given, receives the Voronoi vertices of the ends at vertices (valid edges).
void edge_from_cells(const Delaunay& del, const std::array<VertexId, 2>& apexes, const Box3& box, VoronoiEdge& e,
                     std::array<Vec3, 2>* shared) {
  const auto clipped = clip_line_to_box(e.point, e.direction, box);
  if (!clipped) return;
  const CellEnds ends = cell_ends(del, e, apexes);
  if (shared) *shared = {ends.lo_vertex, ends.hi_vertex};
  e.at_vertex0 = ends.lo > (*clipped)[0];
  e.at_vertex1 = ends.hi < (*clipped)[1];
  if (!(ends.lo < ends.hi)) {
    const double m = 0.5 * (ends.lo + ends.hi);
    e.degenerate = m >= (*clipped)[0] && m <= (*clipped)[1];
    e.t0 = e.t1 = m;
    return;
  }
  e.t0 = std::max(ends.lo, (*clipped)[0]);
  e.t1 = std::min(ends.hi, (*clipped)[1]);
  e.valid = e.t0 < e.t1;
}

}  // namespace

namespace {

// A kept Voronoi vertex: its centre and, once asked for, its error radius (negative before).
struct VertexMemo {
  std::uint64_t serial = 0;  // no Delaunay has serial 0
  std::array<VertexId, 4> cell{};
  Vec3 centre{};
  double radius = -1;
  bool tight = false;  // radius is the interval bound (else the static one, or none)
};

void settle_centre(VertexMemo& m, const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s);

// The memo entry of the cell (ids in ascending order on return), filled with its centre.  A
// direct-mapped memo per thread: the faces at a Voronoi vertex ask for it one after another.
VertexMemo& vertex_memo(const Delaunay& del, std::array<VertexId, 4>& cell) {
  // Ascending ids by a sorting network of four.
  auto order = [&](int i, int j) {
    if (cell[j] < cell[i]) std::swap(cell[i], cell[j]);
  };
  order(0, 1);
  order(2, 3);
  order(0, 2);
  order(1, 3);
  order(1, 2);
  constexpr std::size_t memo_size = 1024;
  thread_local std::array<VertexMemo, memo_size> memo;
  std::uint64_t hash = 0;
  for (VertexId v : cell) hash = (hash ^ static_cast<std::uint32_t>(v)) * 0x100000001b3ull;
  VertexMemo& m = memo[(hash >> 20) % memo_size];
  if (m.serial != del.serial() || !detail::KeyEqual{}(m.cell, cell)) {
    m.serial = del.serial();
    m.cell = cell;
    m.centre = circumcentre(del.point(cell[0]), del.point(cell[1]), del.point(cell[2]), del.point(cell[3]));
    m.radius = -1;
    m.tight = false;
    settle_centre(m, del.point(cell[0]), del.point(cell[1]), del.point(cell[2]), del.point(cell[3]));
  }
  return m;
}

// Upper bound of √(x0² + x1² + x2²) for non-negative doubles (under the caller's upward rounding).
double upper_norm(const std::array<double, 3>& x) {
  return CGAL::sqrt(Interval(x[0]) * x[0] + Interval(x[1]) * x[1] + Interval(x[2]) * x[2]).sup();
}

// A forward error bound on circumcentre(p, q, r, s) = centre, from the standard model
// fl(x ∘ y) = (x ∘ y)(1 + δ), |δ| ≤ u = 2⁻⁵³, or nothing where it does not apply (M below or
// above the range where no intermediate underflows or overflows, or d not safely away from 0).
// With M* = 1.001 M bounding every |component| of the exact differences a*, b*, c* (M the
// largest computed one): the cross products are off by at most 9uM*² (|b×c| ≤ 2M*²), d = 2⟨a, b×c⟩
// by Δd ≤ 128uM*³, |a|² by 16uM*², each numerator component n by Δn ≤ 256uM*⁴ (so |n*| ≤
// |n| + Δn); then n/d is off by Δn/|d| + (|n| + Δn)Δd/(|d|(|d| − Δd)), its two roundings add 2.01u|n/d|
// and the final sum 1.01u|centre_k|.  The bound of each coordinate is doubled to cover the
// rounding of its own evaluation.
std::optional<double> static_circumcentre_radius(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s,
                                                 const Vec3& centre) {
  const Vec3 a = q - p, b = r - p, c = s - p;
  double m = 0;
  for (int k = 0; k < 3; ++k) m = std::max({m, std::abs(a[k]), std::abs(b[k]), std::abs(c[k])});
  if (!(m > 1e-30 && m < 1e30)) return std::nullopt;
  constexpr double u = 0x1p-53;
  const double ms = 1.001 * m, m3 = ms * ms * ms, m4 = m3 * ms;
  const double d = 2 * dot(a, cross(b, c));
  const double dd = 128 * u * m3;
  if (!(std::abs(d) > 2 * dd)) return std::nullopt;
  const Vec3 num = dot(a, a) * cross(b, c) + dot(b, b) * cross(c, a) + dot(c, c) * cross(a, b);
  const double dn = 256 * u * m4;
  double sum = 0;
  for (int k = 0; k < 3; ++k) {
    const double quotient_error = dn / std::abs(d) + (std::abs(num[k]) + dn) * dd / (std::abs(d) * (std::abs(d) - dd));
    const double e = 2 * (quotient_error + 2.01 * u * std::abs(num[k] / d) + 1.01 * u * std::abs(centre[k]));
    sum += e * e;
  }
  return 1.01 * std::sqrt(sum);
}

// The interval bound of certified_voronoi_vertex() on |centre − c*|, c* the exact circumcentre
// of pqrs.
double circumcentre_radius(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s, const Vec3& centre) {
  std::array<double, 3> far{};  // |centre − c*| per coordinate, bounded above
  {
    // Step 1: the formula of circumcentre() in intervals; its box holds c*.
    RoundingGuard guard;
    using I3 = std::array<Interval, 3>;
    auto minus = [](const Vec3& x, const Vec3& y) {
      return I3{Interval(x[0]) - y[0], Interval(x[1]) - y[1], Interval(x[2]) - y[2]};
    };
    auto cross3 = [](const I3& x, const I3& y) {
      return I3{x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]};
    };
    auto dot3 = [](const I3& x, const I3& y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; };
    const I3 a = minus(q, p), b = minus(r, p), c = minus(s, p);
    const I3 bc = cross3(b, c), ca = cross3(c, a), ab = cross3(a, b);
    const Interval d = 2 * dot3(a, bc);
    if (d.inf() > 0 || d.sup() < 0) {
      const Interval aa = dot3(a, a), bb = dot3(b, b), cc = dot3(c, c);
      for (int k = 0; k < 3; ++k) {
        const Interval x = Interval(p[k]) + (aa * bc[k] + bb * ca[k] + cc * ab[k]) / d;
        far[k] = std::max(x.sup() - centre[k], centre[k] - x.inf());  // rounded upwards
      }
      const double radius = upper_norm(far);
      if (std::isfinite(radius)) return radius;
    }
  }
  // Step 2: the sites are coplanar up to the intervals' rounding: c* constructed exactly (none
  // if the sites are coplanar).
  using Exact = CGAL::Exact_predicates_exact_constructions_kernel;
  auto exact = [](const Vec3& x) { return Exact::Point_3(x[0], x[1], x[2]); };
  if (CGAL::coplanar(exact(p), exact(q), exact(r), exact(s))) return std::numeric_limits<double>::infinity();
  const Exact::Point_3 star = CGAL::circumcenter(exact(p), exact(q), exact(r), exact(s));
  for (int k = 0; k < 3; ++k) far[k] = CGAL::to_interval(CGAL::exact(CGAL::abs(star[k] - centre[k]))).second;
  RoundingGuard guard;
  return upper_norm(far);
}

// Replaces a wild centre (voronoi_vertex()): when neither the static nor the interval bound is
// within tolerances::voronoi_vertex_exact_relative_error of the centre's distance to p (or the
// centre is not finite), the exact circumcentre rounded to doubles, with the bound of that
// rounding; nothing if the sites are coplanar (the cell is flat; its radius stays unknown).
void settle_centre(VertexMemo& m, const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s) {
  const bool finite = std::isfinite(m.centre[0]) && std::isfinite(m.centre[1]) && std::isfinite(m.centre[2]);
  const double allowed = tolerances::voronoi_vertex_exact_relative_error * distance(m.centre, p);
  if (finite) {
    if (const auto bound = static_circumcentre_radius(p, q, r, s, m.centre)) {
      m.radius = *bound;
      if (*bound <= allowed) return;
    }
    const double tight = circumcentre_radius(p, q, r, s, m.centre);
    m.radius = m.radius >= 0 ? std::min(m.radius, tight) : tight;
    m.tight = true;
    if (m.radius <= allowed) return;
  }
  using Exact = CGAL::Exact_predicates_exact_constructions_kernel;
  auto exact = [](const Vec3& x) { return Exact::Point_3(x[0], x[1], x[2]); };
  if (CGAL::coplanar(exact(p), exact(q), exact(r), exact(s))) return;
  const Exact::Point_3 star = CGAL::circumcenter(exact(p), exact(q), exact(r), exact(s));
  std::array<double, 3> far{};
  for (int k = 0; k < 3; ++k) {
    const auto x = CGAL::exact(star[k]);
    m.centre[k] = CGAL::to_double(x);
    far[k] = CGAL::to_interval(CGAL::exact(CGAL::abs(star[k] - m.centre[k]))).second;
  }
  RoundingGuard guard;
  m.radius = upper_norm(far);
  m.tight = true;
}

}  // namespace

Vec3 voronoi_vertex(const Delaunay& del, std::array<VertexId, 4> cell) { return vertex_memo(del, cell).centre; }

VoronoiVertex certified_voronoi_vertex(const Delaunay& del, std::array<VertexId, 4> cell, double enough) {
  VertexMemo& m = vertex_memo(del, cell);
  if (m.tight || (m.radius >= 0 && m.radius <= enough)) return {m.centre, m.radius};
  const Vec3 &p = del.point(cell[0]), &q = del.point(cell[1]), &r = del.point(cell[2]), &s = del.point(cell[3]);
  // A centre that is not finite (a flat cell in doubles) has no bound.
  if (!std::isfinite(m.centre[0]) || !std::isfinite(m.centre[1]) || !std::isfinite(m.centre[2])) {
    m.radius = std::numeric_limits<double>::infinity();
    m.tight = true;
    return {m.centre, m.radius};
  }
  // Step 1: the static bound, enough if it is within `enough`.
  if (m.radius < 0)
    if (const auto bound = static_circumcentre_radius(p, q, r, s, m.centre)) m.radius = *bound;
  if (m.radius >= 0 && m.radius <= enough) return {m.centre, m.radius};
  // Step 2: the interval bound (exact construction as its fallback), the tighter of the two.
  const double tight = circumcentre_radius(p, q, r, s, m.centre);
  m.radius = m.radius >= 0 ? std::min(m.radius, tight) : tight;
  m.tight = true;
  return {m.centre, m.radius};
}

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

Domain VoronoiFacet::polygon_hull(double margin) const {
  if (polygon.empty()) throw PreconditionViolation("VoronoiFacet::polygon_hull: the facet has no points");
  std::vector<std::array<double, 2>> bounds(2, {std::numeric_limits<double>::infinity(),
                                                -std::numeric_limits<double>::infinity()});
  for (const auto& w : polygon)
    for (int j = 0; j < 2; ++j) {
      bounds[j][0] = std::min(bounds[j][0], w[j] - margin);
      bounds[j][1] = std::max(bounds[j][1], w[j] + margin);
    }
  return Domain::from_box(std::move(bounds));
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

namespace {

// Sets e to voronoi_edge_line(del, t); returns whether t has a normal in doubles.
bool set_edge_line(const Delaunay& del, const TriangleKey& t, VoronoiEdge& e) {
  e.triangle = t;
  const Vec3& p = del.point(t[0]);
  const Vec3& q = del.point(t[1]);
  const Vec3& r = del.point(t[2]);
  const Vec3 n = cross(q - p, r - p);
  if (!(norm(n) > 0)) return false;
  e.point = circumcentre(p, q, r);
  e.direction = normalized(n);
  return true;
}

}  // namespace

VoronoiEdge voronoi_edge_line(const Delaunay& del, const TriangleKey& t) {
  VoronoiEdge e;
  set_edge_line(del, t, e);
  return e;
}

VoronoiEdge voronoi_edge(const Delaunay& del, const TriangleKey& t, const Box3& box,
                         const std::array<VertexId, 2>* known_apexes, std::array<Vec3, 2>* shared) {
  VoronoiEdge e;
  if (!set_edge_line(del, t, e)) return e;
  const Vec3& p = del.point(t[0]);
  if (const auto apexes = known_apexes ? std::optional(*known_apexes) : del.triangle_apexes(t)) {
    edge_from_cells(del, *apexes, box, e, shared);
    if (shared) {
      if (!e.at_vertex0) (*shared)[0] = e.at(e.t0);
      if (!e.at_vertex1) (*shared)[1] = e.at(e.t1);
    }
    return e;
  }
  const auto clipped = clip_line_to_box(e.point, e.direction, box);
  if (!clipped) return e;
  LineClip line((*clipped)[0], (*clipped)[1]);
  for (VertexId s : del.neighbours(t[0])) {
    if (s == t[1] || s == t[2]) continue;
    const Vec3& x = del.point(s);
    const Vec3 w = x - p;
    line.keep(dot(w, e.direction), dot(w, 0.5 * (x + p) - e.point), norm(w));
    if (line.emptied) return e;  // the whole line is outside V_p
  }
  e.t0 = line.t0;
  e.t1 = line.t1;
  e.at_vertex0 = line.cut0;
  e.at_vertex1 = line.cut1;
  e.valid = line.nonempty();
  if (shared) *shared = {e.at(e.t0), e.at(e.t1)};
  return e;
}

std::array<Vec3, 2> voronoi_edge_ends(const Delaunay& del, const VoronoiEdge& e,
                                      const std::array<VertexId, 2>* known_apexes) {
  std::array<Vec3, 2> out{e.at(e.t0), e.at(e.t1)};
  if (!e.at_vertex0 && !e.at_vertex1) return out;
  const auto apexes = known_apexes ? std::optional(*known_apexes) : del.triangle_apexes(e.triangle);
  if (!apexes) return out;  // below dimension 3 the ends are cut by bisectors, not cells
  const CellEnds ends = cell_ends(del, e, *apexes);
  if (e.at_vertex0) out[0] = ends.lo_vertex;
  if (e.at_vertex1) out[1] = ends.hi_vertex;
  return out;
}

namespace {

// Sets the plane frame of the facet of pq (origin, a, b, normal: the frame of Π ∩ B rotated by
// `rotation` in Π) and returns Π ∩ B in it; nothing if Π misses B.
std::optional<std::vector<P2>> facet_frame(const Vec3& p, const Vec3& q, const Box3& box, double rotation,
                                           VoronoiFacet& f) {
  f.origin = 0.5 * (p + q);
  const auto section = plane_box_section(f.origin, q - p, box);
  if (!section) return std::nullopt;
  const double c = std::cos(rotation), s = std::sin(rotation);
  f.a = c * section->frame.a + s * section->frame.b;
  f.b = (-s) * section->frame.a + c * section->frame.b;
  f.normal = section->frame.d;
  f.origin = section->origin;
  std::vector<P2> polygon;
  polygon.reserve(section->polygon.size());
  for (const auto& w : section->polygon) polygon.push_back({c * w[0] + s * w[1], -s * w[0] + c * w[1]});
  return polygon;
}

// The samples r whose bisectors with p cut the facet of pq, by increasing id: the third vertices
// of the triangles pqr with their apexes (`ring` if given) in dimension 3, all of N(p) (without
// apexes) below.
std::vector<Delaunay::RingTriangle> facet_cutters(const Delaunay& del, const EdgeKey& edge,
                                                  const std::vector<Delaunay::RingTriangle>* ring) {
  std::vector<Delaunay::RingTriangle> cutting;
  if (del.dimension() == 3) {
    cutting = ring ? *ring : del.edge_ring(edge);
    std::sort(cutting.begin(), cutting.end(),
              [](const Delaunay::RingTriangle& x, const Delaunay::RingTriangle& y) { return x.third < y.third; });
  } else {
    for (VertexId r : del.neighbours(edge[0])) cutting.push_back({r, {-1, -1}});
  }
  return cutting;
}

// The largest |u| or |v| of a polygon's corners.
double extent_of(const std::vector<P2>& poly) {
  double extent = 0;
  for (const auto& w : poly) extent = std::max({extent, std::abs(w[0]), std::abs(w[1])});
  return extent;
}

// The polygon without (numerically) repeated corners: consecutive ones closer than eps are one.
std::vector<P2> without_repeated_corners(const std::vector<P2>& poly, double eps) {
  std::vector<P2> clean;
  for (const auto& w : poly)
    if (clean.empty() || std::hypot(w[0] - clean.back()[0], w[1] - clean.back()[1]) > eps) clean.push_back(w);
  while (clean.size() >= 2 && std::hypot(clean.front()[0] - clean.back()[0], clean.front()[1] - clean.back()[1]) <= eps)
    clean.pop_back();
  return clean;
}

// Whether w lies in the closed counter-clockwise polygon Π ∩ B (on the inner side of every side
// ab, whose outward normal is (b_v − a_v, a_u − b_u)); a corner that is not finite does not.
bool in_section(const std::vector<P2>& section_polygon, const P2& w) {
  const std::size_t m = section_polygon.size();
  for (std::size_t i = 0; i < m; ++i) {
    const P2& a = section_polygon[i];
    const P2& b = section_polygon[(i + 1) % m];
    if (!((b[1] - a[1]) * (w[0] - a[0]) + (a[0] - b[0]) * (w[1] - a[1]) <= 0)) return false;  // NaN: outside
  }
  return true;
}

// The solver domain of a facet in dimension 3: the box of the polygon and of F's Voronoi vertices
// in B (which the rounded corners of the polygon may miss by a few units in the last place), the
// cutting half-planes, and the sides of Π ∩ B that the polygon reaches (the others are
// redundant).  Π ∩ B is counter-clockwise: the outward normal of its side ab is
// (b_v − a_v, a_u − b_u).
Domain facet_domain(const std::vector<P2>& polygon, std::vector<HalfSpace> cuts,
                    const std::vector<std::pair<std::array<VertexId, 2>, P2>>& corners,
                    const std::vector<P2>& section_polygon, double eps) {
  Domain domain;
  auto bounds = polygon_bounds(polygon);
  domain.half_spaces = std::move(cuts);
  const std::size_t m = section_polygon.size();
  for (const auto& [key, w] : corners) {
    if (!in_section(section_polygon, w)) continue;
    for (int k = 0; k < 2; ++k) {
      bounds[k][0] = std::min(bounds[k][0], w[k]);
      bounds[k][1] = std::max(bounds[k][1], w[k]);
    }
  }
  domain.box.bounds = std::move(bounds);
  for (std::size_t i = 0; i < m; ++i) {
    const P2& a = section_polygon[i];
    const P2& b = section_polygon[(i + 1) % m];
    const P2 n{b[1] - a[1], a[0] - b[0]};
    const double off = n[0] * a[0] + n[1] * a[1];
    const double reach = eps * std::hypot(n[0], n[1]);
    if (std::any_of(polygon.begin(), polygon.end(),
                    [&](const P2& w) { return n[0] * w[0] + n[1] * w[1] - off >= -reach; }))
      domain.half_spaces.push_back(HalfSpace{{n[0], n[1]}, off});
  }
  return domain;
}

// The Voronoi vertices of F (the corners of the cells around pq, projected into Π) that lie in
// the counter-clockwise polygon Π ∩ B.  F ∩ B holds them, so a facet whose clipped polygon comes out
// empty while they exist is not empty: it has no area in doubles (every cut passes through one
// point, e.g. for cospherical samples) and these points stand for it as a degenerate facet.
template <class Corner>
std::vector<P2> corners_in_section(const std::vector<Delaunay::RingTriangle>& cutting,
                                   const std::vector<P2>& section_polygon, Corner& corner) {
  std::vector<P2> inside;
  for (const auto& [r, apexes] : cutting)
    for (VertexId apex : apexes) {
      if (apex < 0) continue;
      const P2 w = corner(r, apex);
      if (in_section(section_polygon, w) && std::find(inside.begin(), inside.end(), w) == inside.end())
        inside.push_back(w);
    }
  return inside;
}

}  // namespace

VoronoiFacet voronoi_facet(const Delaunay& del, const EdgeKey& edge, const Box3& box, double rotation,
                           const std::vector<Delaunay::RingTriangle>* ring) {
  VoronoiFacet f;
  f.edge = edge;
  const Vec3& p = del.point(edge[0]);
  const auto section = facet_frame(p, del.point(edge[1]), box, rotation, f);
  if (!section) return f;
  const std::vector<P2>& section_polygon = *section;
  std::vector<P2> poly = section_polygon, scratch;
  poly.reserve(section_polygon.size() + 8);
  scratch.reserve(section_polygon.size() + 8);
  // F = Π ∩ V_p ∩ B is cut out by the bisectors of p and the third vertices r of the triangles
  // pqr (each edge of the convex polygon F is the Voronoi edge of one pqr, and a convex polygon
  // is the intersection of the half-planes of its edges); other neighbours of p are redundant.
  // In dimension 3 the half-plane of pqr is moved outwards to hold the Voronoi vertices of pqr's
  // cells (projected into Π), the ends of that Voronoi edge.
  const std::vector<Delaunay::RingTriangle> cutting = facet_cutters(del, edge, ring);
  std::vector<HalfSpace> cuts;
  cuts.reserve(cutting.size());
  // The Voronoi vertices of F projected into Π, by the pair {r, apex} of their cell pqr·apex (each
  // is met twice, from the two triangles of that cell around pq).
  std::vector<std::pair<std::array<VertexId, 2>, P2>> corners;
  corners.reserve(cutting.size());
  auto corner = [&](VertexId r, VertexId apex) {
    const std::array<VertexId, 2> key{std::min(r, apex), std::max(r, apex)};
    for (const auto& [k, w] : corners)
      if (k == key) return w;
    corners.push_back({key, f.plane_coordinates(voronoi_vertex(del, {edge[0], edge[1], r, apex}))});
    return corners.back().second;
  };
  for (const auto& [r, apexes] : cutting) {
    if (r == edge[1]) continue;
    const Vec3& x = del.point(r);
    const Vec3 w = x - p;
    const P2 n{dot(w, f.a), dot(w, f.b)};
    double off = dot(w, 0.5 * (x + p) - f.origin);
    if (std::abs(n[0]) + std::abs(n[1]) <= tolerances::parallel_half_space_relative_slope * norm(w)) {
      if (off < 0) return f;
      continue;
    }
    for (VertexId apex : apexes) {
      if (apex < 0) continue;  // the edge of pqr is a ray (or there are no cells: dimension < 3)
      const P2 v = corner(r, apex);
      off = std::max(off, n[0] * v[0] + n[1] * v[1]);
    }
    cuts.push_back(HalfSpace{{n[0], n[1]}, off});
    clip_polygon(poly, n, off, scratch);
    poly.swap(scratch);
    if (poly.size() < 3) {
      if (poly.empty()) poly = corners_in_section(cutting, section_polygon, corner);
      f.degenerate = !poly.empty();
      f.polygon = std::move(poly);
      return f;
    }
  }
  const double eps = tolerances::facet_repeated_corner_relative_distance * std::max(extent_of(poly), box.diagonal());
  std::vector<P2> clean = without_repeated_corners(poly, eps);
  if (clean.size() < 3 || polygon_area(clean) <= eps * eps) {
    f.degenerate = true;
    f.polygon = std::move(poly);
    return f;
  }
  f.polygon = std::move(clean);
  f.domain = del.dimension() == 3 ? facet_domain(f.polygon, std::move(cuts), corners, section_polygon, eps)
                                  : polygon_domain(f.polygon);
  f.valid = true;
  return f;
}

namespace {

// The half-space {x : |x − p| ≤ |x − q|} of the sites p and q: ⟨q − p, x⟩ ≤ ⟨q − p, (p + q)/2⟩.
HalfSpace bisector(const Vec3& p, const Vec3& q) {
  const Vec3 w = q - p;
  return HalfSpace{{w[0], w[1], w[2]}, dot(w, 0.5 * (q + p))};
}

// The Voronoi vertices of the cells of p (unused entries for infinite cells), and the largest
// error radius among them (certified_voronoi_vertex()).
// Radii up to `enough` may be the static ones (certified_voronoi_vertex()).
std::vector<Vec3> cell_corners(const Delaunay& del, const std::vector<std::array<VertexId, 4>>& cells, double enough,
                               double& largest_radius) {
  std::vector<Vec3> corners(cells.size());
  largest_radius = 0;
  for (std::size_t k = 0; k < cells.size(); ++k)
    if (cells[k][1] >= 0 && cells[k][2] >= 0 && cells[k][3] >= 0) {
      const VoronoiVertex v = certified_voronoi_vertex(del, cells[k], enough);
      corners[k] = v.centre;
      largest_radius = std::max(largest_radius, v.radius);
    }
  return corners;
}

// Moves the half-space of each facet neighbour q (cell.domain.half_spaces[i] for
// cell.facet_neighbours[i]) outwards to hold the Voronoi vertices of the finite cells of p that
// contain q, and widens the box to hold those of them in B.
void hold_vertices(const std::vector<std::array<VertexId, 4>>& cells, const std::vector<Vec3>& corners, const Box3& box,
                   VoronoiCell& cell) {
  const auto& neighbours = cell.facet_neighbours;
  auto& bounds = cell.domain.box.bounds;
  for (std::size_t k = 0; k < cells.size(); ++k) {
    const auto& c = cells[k];
    if (c[1] < 0 || c[2] < 0 || c[3] < 0) continue;
    const Vec3& v = corners[k];
    for (int j = 1; j < 4; ++j) {
      const auto it = std::lower_bound(neighbours.begin(), neighbours.end(), c[j]);
      if (it == neighbours.end() || *it != c[j]) continue;  // F_pq lies outside B
      HalfSpace& h = cell.domain.half_spaces[it - neighbours.begin()];
      h.offset = std::max(h.offset, h.normal[0] * v[0] + h.normal[1] * v[1] + h.normal[2] * v[2]);
    }
    if (!box.contains(v)) continue;
    for (int i = 0; i < 3; ++i) {
      bounds[i][0] = std::min(bounds[i][0], v[i]);
      bounds[i][1] = std::max(bounds[i][1], v[i]);
    }
  }
}

// The cell of `site` on the box `points` (a bounding box of V_p ∩ B up to the errors of the
// points), enlarged by `enlargement` (at least those errors) and intersected with B, cut by the
// bisectors of p and all its `neighbours` (a neighbour whose facet in B has no area adds a
// redundant half-space).  Nothing if the box ∩ B is empty.
std::optional<VoronoiCell> cell_in_bounds(const Delaunay& del, VertexId site, const Box3& box, BoundingBox points,
                                          std::vector<VertexId> neighbours, double enlargement) {
  points.enlarge(enlargement);
  std::vector<std::array<double, 2>> bounds;
  bounds.reserve(3);
  for (int k = 0; k < 3; ++k) {
    bounds.push_back({std::max(points.lo[k], box.lo[k]), std::min(points.hi[k], box.hi[k])});
    if (!(bounds[k][0] < bounds[k][1])) return std::nullopt;
  }
  VoronoiCell cell;
  cell.site = site;
  cell.domain = Domain::from_box(std::move(bounds));
  cell.facet_neighbours = std::move(neighbours);
  const Vec3& p = del.point(site);
  cell.domain.half_spaces.reserve(cell.facet_neighbours.size());
  for (VertexId s : cell.facet_neighbours) cell.domain.half_spaces.push_back(bisector(p, del.point(s)));
  cell.valid = true;
  return cell;
}

// V_p from its vertices, when it is bounded: in dimension 3 the vertices of V_p are the Voronoi
// vertices of the cells incident to p, so V_p ∩ B lies in their exact bounding box ∩ B, which
// the bounding box of the computed vertices enlarged by their largest error radius holds.
// `enlargement` is max(membership margin, 2 · that radius) (voronoi_geometry.h).  Nothing if a
// cell of p is infinite (V_p is unbounded) or the box ∩ B is empty.
std::optional<VoronoiCell> cell_from_vertices(const Delaunay& del, VertexId site, const Box3& box,
                                              const std::vector<std::array<VertexId, 4>>& cells,
                                              const std::vector<Vec3>& corners,
                                              const std::vector<VertexId>& neighbours, double enlargement) {
  if (del.dimension() != 3) return std::nullopt;
  BoundingBox vertices;
  for (std::size_t k = 0; k < cells.size(); ++k) {
    if (cells[k][1] < 0 || cells[k][2] < 0 || cells[k][3] < 0) return std::nullopt;
    vertices.add(corners[k]);
  }
  return cell_in_bounds(del, site, box, vertices, neighbours, enlargement);
}

// Adds to `points` the ends of the part of the segment {a + t v : t ∈ [t0, t1]} in B (t1 = +∞
// for a ray), if it has positive length.
void add_clipped(const Vec3& a, const Vec3& v, double t0, double t1, const Box3& box, BoundingBox& points) {
  if (!(norm(v) > 0)) return;
  const auto inside = clip_line_to_box(a, v, box);
  if (!inside) return;
  const double lo = std::max(t0, (*inside)[0]), hi = std::min(t1, (*inside)[1]);
  if (!(lo < hi)) return;
  points.add(a + lo * v);
  points.add(a + hi * v);
}

// A triangle pqr of a cell of p (q < r), with the cell it came from and that cell's fourth vertex.
struct CellSide {
  VertexId q, r;
  std::size_t cell;
  VertexId fourth;
  bool operator<(const CellSide& o) const {
    const std::uint64_t a = detail::pair_word(q, r), b = detail::pair_word(o.q, o.r);
    return a < b || (a == b && cell < o.cell);
  }
};

// Whether p's cell `cells[k]` is finite (no infinite vertex).
bool finite_cell(const std::vector<std::array<VertexId, 4>>& cells, std::size_t k) {
  return cells[k][1] >= 0 && cells[k][2] >= 0 && cells[k][3] >= 0;
}

// cell_from_dual()'s points (1), the Voronoi vertices in B, and the triangles of the cells into
// `sides`; false if a Voronoi vertex is not finite.
bool add_voronoi_vertices(const std::vector<std::array<VertexId, 4>>& cells, const std::vector<Vec3>& corners,
                          const Box3& box, BoundingBox& points, std::vector<CellSide>& sides) {
  sides.reserve(3 * cells.size());
  for (std::size_t k = 0; k < cells.size(); ++k) {
    const auto& c = cells[k];
    if (finite_cell(cells, k)) {
      const Vec3& v = corners[k];
      if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2])) return false;
      if (box.contains(v)) points.add(v);
    }
    for (int j = 1; j < 4; ++j) {
      const VertexId q = c[j % 3 + 1], r = c[(j + 1) % 3 + 1];
      sides.push_back({std::min(q, r), std::max(q, r), k, c[j]});
    }
  }
  return true;
}

// cell_from_dual()'s points (2), where the edges of V_p cross ∂B: each finite triangle pqr lies in
// two cells of p.  False when the cells are not a closed star or a hull triangle is flat (its ray
// has no direction): the caller clips then.
bool add_edge_crossings(const Delaunay& del, const Vec3& p, std::vector<CellSide>& sides,
                        const std::vector<std::array<VertexId, 4>>& cells, const std::vector<Vec3>& corners,
                        const Box3& box, BoundingBox& points) {
  std::sort(sides.begin(), sides.end());
  for (std::size_t i = 0; i + 1 < sides.size(); i += 2) {
    const CellSide &s = sides[i], &t = sides[i + 1];
    if (s.q != t.q || s.r != t.r) return false;  // not a closed star: let the caller clip
    if (s.q < 0) continue;                        // a triangle with the infinite vertex
    const bool fs = finite_cell(cells, s.cell), ft = finite_cell(cells, t.cell);
    if (fs && ft) {
      add_clipped(corners[s.cell], corners[t.cell] - corners[s.cell], 0, 1, box, points);
    } else if (fs || ft) {
      const CellSide& f = fs ? s : t;
      Vec3 n = cross(del.point(f.q) - p, del.point(f.r) - p);
      if (!(norm(n) > 0)) return false;  // a flat hull triangle has no ray: let the caller clip
      if (dot(n, del.point(f.fourth) - p) > 0) n = -1.0 * n;
      add_clipped(corners[f.cell], n, 0, std::numeric_limits<double>::infinity(), box, points);
    }
  }
  return true;
}

// cell_from_dual()'s points (3) and (4): the ends of the parts of B's edges that the bisectors of
// p and its neighbours leave (a bisector parallel to an edge removes it only when the edge lies
// beyond it by more than `margin`).
void add_box_edge_sections(const Delaunay& del, const Vec3& p, const Box3& box, const std::vector<VertexId>& neighbours,
                           double margin, BoundingBox& points) {
  // The bisector of p and each neighbour x: normal w = x − p through the midpoint m, and |w|.
  struct Bisector {
    Vec3 w, m;
    double scale;
  };
  std::vector<Bisector> bisectors;
  bisectors.reserve(neighbours.size());
  for (VertexId s : neighbours) {
    const Vec3& x = del.point(s);
    const Vec3 w = x - p;
    bisectors.push_back({w, 0.5 * (x + p), norm(w)});
  }
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (int corner = 0; corner < 4; ++corner) {
      Vec3 start{};
      start[u] = corner & 1 ? box.hi[u] : box.lo[u];
      start[v] = corner & 2 ? box.hi[v] : box.lo[v];
      LineClip edge(box.lo[axis], box.hi[axis]);
      for (const auto& [w, m, scale] : bisectors) {
        const double slope = w[axis], rhs = dot(w, m - start);
        if (std::abs(slope) <= tolerances::parallel_half_space_relative_slope * scale) {
          if (rhs < -margin * scale) edge.emptied = true;
          continue;
        }
        edge.keep(slope, rhs, scale);
        if (!edge.nonempty()) break;
      }
      if (edge.emptied || edge.t0 > edge.t1) continue;
      Vec3 a = start, b = start;
      a[axis] = edge.t0;
      b[axis] = edge.t1;
      points.add(a);
      points.add(b);
    }
  }
}
// V_p ∩ B when V_p is unbounded, from the Delaunay dual rather than by clipping.  V_p ∩ B is a
// convex polytope, the hull of its vertices, each of which is
//  (1) a Voronoi vertex of V_p in B (the circumcentre of a finite cell of p),
//  (2) a point where an edge of V_p crosses ∂B: the edge dual to a triangle pqr is the segment
//      between the Voronoi vertices of the two cells at pqr, or, when one of them is infinite
//      (pqr on the convex hull), the ray from the other's Voronoi vertex along pqr's normal away
//      from that cell's fourth vertex, or
//  (3) a point where a facet of V_p crosses an edge of B, or (4) a corner of B in V_p: both are
//      ends of the segment (edge of B) ∩ V_p, cut out of the edge by the bisectors of p and its
//      neighbours.
// So V_p ∩ B lies in the bounding box of these points, which is enlarged and intersected with B
// as in cell_in_bounds().  A bisector parallel to an edge of B (within
// tolerances::parallel_half_space_relative_slope) removes the edge only when the edge lies
// beyond it by more than the enlargement; otherwise it is not applied, which can only widen the
// box.  Nothing if a Voronoi vertex is not finite (a flat cell) or a hull triangle is flat (its
// ray has no direction): the caller clips instead.
std::optional<VoronoiCell> cell_from_dual(const Delaunay& del, VertexId site, const Box3& box,
                                          const std::vector<std::array<VertexId, 4>>& cells,
                                          const std::vector<Vec3>& corners, const std::vector<VertexId>& neighbours) {
  if (del.dimension() != 3) return std::nullopt;
  const Vec3& p = del.point(site);
  BoundingBox points;
  std::vector<CellSide> sides;
  if (!add_voronoi_vertices(cells, corners, box, points, sides)) return std::nullopt;  // (1)
  if (!add_edge_crossings(del, p, sides, cells, corners, box, points)) return std::nullopt;  // (2)
  const double margin = tolerances::face_membership_relative_tolerance * box.diagonal();
  add_box_edge_sections(del, p, box, neighbours, margin, points);  // (3) and (4)
  if (points.empty()) return std::nullopt;
  return cell_in_bounds(del, site, box, points, neighbours, margin);
}

// V_p ∩ B by clipping B with the bisectors of p and its neighbours, nearest first (their
// bisectors cut the box down to about V_p at once, so most later clips find every vertex
// inside and return early); its half-spaces are those of the facets left, in the order of
// facet_neighbours.
VoronoiCell clipped_cell(const Delaunay& del, VertexId site, const Box3& box, const std::vector<VertexId>& neighbours) {
  VoronoiCell cell;
  cell.site = site;
  const Vec3& p = del.point(site);
  // One polytope per thread, reset for each cell: its buffers outlive the call.
  thread_local ConvexPolytope polytope;
  polytope.reset(box);
  std::vector<std::pair<double, VertexId>> by_distance;
  by_distance.reserve(neighbours.size());
  for (VertexId s : neighbours) {
    const Vec3 w = del.point(s) - p;
    by_distance.push_back({dot(w, w), s});
  }
  std::sort(by_distance.begin(), by_distance.end());
  for (const auto& [d, s] : by_distance) {
    const HalfSpace h = bisector(p, del.point(s));
    polytope.clip({h.normal[0], h.normal[1], h.normal[2]}, h.offset, s);
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
  for (VertexId s : cell.facet_neighbours) cell.domain.half_spaces.push_back(bisector(p, del.point(s)));
  cell.valid = true;
  return cell;
}

}  // namespace

VoronoiCell voronoi_cell(const Delaunay& del, VertexId site, const Box3& box) {
  return voronoi_cell(del, site, box, del.incident_cells(site), del.neighbours(site));
}

VoronoiCell voronoi_cell(const Delaunay& del, VertexId site, const Box3& box,
                         const std::vector<std::array<VertexId, 4>>& cells, const std::vector<VertexId>& neighbours) {
  // Both ways, the half-spaces and the box are then moved out to hold the cell's Voronoi vertices.
  // Step 1: the vertices and their largest error radius ρ.
  const double margin = tolerances::face_membership_relative_tolerance * box.diagonal();
  double radius = 0;
  const auto corners = cell_corners(del, cells, 0.5 * margin, radius);
  // Step 2: the box from the vertices, enlarged by the membership margin or 2ρ if larger; from
  // the dual only when 2ρ is within the margin (its clip points rest on the margin); else by
  // clipping, which reads no circumcentre.
  auto from_vertices = cell_from_vertices(del, site, box, cells, corners, neighbours, std::max(margin, 2 * radius));
  if (!from_vertices && 2 * radius <= margin) from_vertices = cell_from_dual(del, site, box, cells, corners, neighbours);
  VoronoiCell cell = from_vertices ? std::move(*from_vertices) : clipped_cell(del, site, box, neighbours);
  if (cell.valid) hold_vertices(cells, corners, box, cell);
  return cell;
}

}  // namespace delmesh
