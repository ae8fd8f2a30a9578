#include "meshing/voronoi/restricted_voronoi_mesh.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <utility>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_rational.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include "common/errors.h"

namespace delmesh {
namespace {

using IA = CGAL::Interval_nt_advanced;
using ER = CGAL::Exact_rational;

// 0, ±1 if certain; 2 if the interval holds 0 and something else.
int interval_sign(const IA& x) {
  if (x.inf() > 0) return 1;
  if (x.sup() < 0) return -1;
  if (x.inf() == 0 && x.sup() == 0) return 0;
  return 2;
}

template <class NT>
struct H4 {  // a point (x, y, z) = (X, Y, Z) / W
  NT x, y, z, w;
};

template <class NT>
struct P3 {
  NT x, y, z;
};

template <class NT>
P3<NT> lift(const Point3& p) {
  return {NT(p.x()), NT(p.y()), NT(p.z())};
}

// The input to the exact evaluations: the samples and the corners of the input.
struct Input {
  const std::vector<Point3>& samples;
  const SurfaceMesh& mesh;
  const Point3& vertex(std::size_t v) const { return mesh.point(SurfaceMesh::Vertex_index(static_cast<std::uint32_t>(v))); }
  std::array<std::size_t, 3> corners(std::size_t f) const {
    const auto h = mesh.halfedge(SurfaceMesh::Face_index(static_cast<std::uint32_t>(f)));
    return {std::size_t(mesh.source(h)), std::size_t(mesh.target(h)), std::size_t(mesh.target(mesh.next(h)))};
  }
};

template <class NT>
NT det3(const NT& a, const NT& b, const NT& c, const NT& d, const NT& e, const NT& f, const NT& g, const NT& h,
        const NT& i) {
  const NT m1 = e * i - f * h;
  const NT m2 = d * i - f * g;
  const NT m3 = d * h - e * g;
  return a * m1 - b * m2 + c * m3;
}

// The homogeneous coordinates of v (file comment of the header), every intermediate an NT.
template <class NT>
H4<NT> coordinates(const RvdVertex& v, const Input& in) {
  switch (v.kind) {
    case RvdVertexKind::input_vertex: {
      const P3<NT> x = lift<NT>(in.vertex(v.input[0]));
      return {x.x, x.y, x.z, NT(1)};
    }
    case RvdVertexKind::edge_cut: {
      // x = u + (a / b)(w − u) on B(p, q): 2⟨x, q − p⟩ = |q|² − |p|².
      const P3<NT> u = lift<NT>(in.vertex(v.input[0])), w = lift<NT>(in.vertex(v.input[1]));
      const P3<NT> p = lift<NT>(in.samples[v.sites[0]]), q = lift<NT>(in.samples[v.sites[1]]);
      const NT dx = q.x - p.x, dy = q.y - p.y, dz = q.z - p.z;
      const NT rhs = (q.x * q.x + q.y * q.y + q.z * q.z) - (p.x * p.x + p.y * p.y + p.z * p.z);
      const NT a = rhs - NT(2) * (u.x * dx + u.y * dy + u.z * dz);
      const NT ex = w.x - u.x, ey = w.y - u.y, ez = w.z - u.z;
      const NT b = NT(2) * (ex * dx + ey * dy + ez * dz);
      return {u.x * b + a * ex, u.y * b + a * ey, u.z * b + a * ez, b};
    }
    case RvdVertexKind::face_cut: {
      const auto c = in.corners(v.input[0]);
      const P3<NT> a = lift<NT>(in.vertex(c[0])), b = lift<NT>(in.vertex(c[1])), d = lift<NT>(in.vertex(c[2]));
      const NT e1x = b.x - a.x, e1y = b.y - a.y, e1z = b.z - a.z;
      const NT e2x = d.x - a.x, e2y = d.y - a.y, e2z = d.z - a.z;
      const NT nx = e1y * e2z - e1z * e2y, ny = e1z * e2x - e1x * e2z, nz = e1x * e2y - e1y * e2x;
      const NT r0 = nx * a.x + ny * a.y + nz * a.z;
      const P3<NT> p = lift<NT>(in.samples[v.sites[0]]), q = lift<NT>(in.samples[v.sites[1]]),
                   r = lift<NT>(in.samples[v.sites[2]]);
      const NT pp = p.x * p.x + p.y * p.y + p.z * p.z;
      const NT qx = NT(2) * (q.x - p.x), qy = NT(2) * (q.y - p.y), qz = NT(2) * (q.z - p.z);
      const NT rx = NT(2) * (r.x - p.x), ry = NT(2) * (r.y - p.y), rz = NT(2) * (r.z - p.z);
      const NT r1 = (q.x * q.x + q.y * q.y + q.z * q.z) - pp;
      const NT r2 = (r.x * r.x + r.y * r.y + r.z * r.z) - pp;
      const NT W = det3(nx, ny, nz, qx, qy, qz, rx, ry, rz);
      const NT X = det3(r0, ny, nz, r1, qy, qz, r2, ry, rz);
      const NT Y = det3(nx, r0, nz, qx, r1, qz, rx, r2, rz);
      const NT Z = det3(nx, ny, r0, qx, qy, r1, rx, ry, r2);
      return {X, Y, Z, W};
    }
  }
  return {NT(0), NT(0), NT(0), NT(0)};
}

// |x − p|² − |x − s|² times W² (a sign of the same meaning: < 0 nearer to p), with x = v's point.
template <class NT>
NT bisector_value(const RvdVertex& v, const Point3& p_, const Point3& s_, const Input& in) {
  const H4<NT> x = coordinates<NT>(v, in);
  const P3<NT> p = lift<NT>(p_), s = lift<NT>(s_);
  const NT dx = s.x - p.x, dy = s.y - p.y, dz = s.z - p.z;
  const NT rhs = (s.x * s.x + s.y * s.y + s.z * s.z) - (p.x * p.x + p.y * p.y + p.z * p.z);
  // |x − p|² − |x − s|² = 2⟨x, s − p⟩ − (|s|² − |p|²); times W (and once more W for the sign).
  const NT value = NT(2) * (x.x * dx + x.y * dy + x.z * dz) - rhs * x.w;
  return value * x.w;
}

struct Counters {
  std::size_t sign_tests = 0, exact = 0;
};

// The exact sign of |x − p|² − |x − s|² at v's point: −1 nearer to p, +1 nearer to s, 0 on B(p, s).
int side(const RvdVertex& v, std::size_t p, std::size_t s, const Input& in, Counters& counters) {
  ++counters.sign_tests;
  {
    CGAL::Protect_FPU_rounding<true> guard;
    const int sign = interval_sign(bisector_value<IA>(v, in.samples[p], in.samples[s], in));
    if (sign != 2) return sign;
  }
  ++counters.exact;
  return static_cast<int>(CGAL::sign(bisector_value<ER>(v, in.samples[p], in.samples[s], in)));
}

std::array<double, 3> point_of(const RvdVertex& v, const Input& in) {
  {
    CGAL::Protect_FPU_rounding<true> guard;
    const H4<IA> x = coordinates<IA>(v, in);
    if (interval_sign(x.w) == 1 || interval_sign(x.w) == -1) {
      const IA a = x.x / x.w, b = x.y / x.w, c = x.z / x.w;
      return {CGAL::to_double(a), CGAL::to_double(b), CGAL::to_double(c)};
    }
  }
  const H4<ER> x = coordinates<ER>(v, in);
  if (CGAL::is_zero(x.w)) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return {nan, nan, nan};
  }
  return {CGAL::to_double(x.x / x.w), CGAL::to_double(x.y / x.w), CGAL::to_double(x.z / x.w)};
}

RvdVertex input_vertex(std::size_t v) {
  RvdVertex x;
  x.kind = RvdVertexKind::input_vertex;
  x.input = {v, rvd_none};
  return x;
}

RvdVertex edge_cut(std::size_t u, std::size_t w, std::size_t p, std::size_t q) {
  RvdVertex x;
  x.kind = RvdVertexKind::edge_cut;
  x.input = {std::min(u, w), std::max(u, w)};
  x.sites = {std::min(p, q), std::max(p, q), rvd_none};
  return x;
}

RvdVertex face_cut(std::size_t t, std::size_t p, std::size_t q, std::size_t r) {
  std::array<std::size_t, 3> s{p, q, r};
  std::sort(s.begin(), s.end());
  RvdVertex x;
  x.kind = RvdVertexKind::face_cut;
  x.input = {t, rvd_none};
  x.sites = s;
  return x;
}

// A polygon being clipped: vertices and the supports of the edges that leave them.
struct Work {
  std::vector<RvdVertex> vertices;
  std::vector<RvdEdgeSupport> edges;
  std::vector<std::array<double, 3>> points;  // the vertices rounded

  void add(const RvdVertex& v, const RvdEdgeSupport& e, const std::array<double, 3>& x) {
    vertices.push_back(v);
    edges.push_back(e);
    points.push_back(x);
  }
};

class Builder {
 public:
  Builder(const std::vector<Point3>& samples, const SurfaceMesh& mesh) : in_{samples, mesh} {}

  RestrictedVoronoiMesh run();

 private:
  using Tr = CGAL::Delaunay_triangulation_3<
      Kernel, CGAL::Triangulation_data_structure_3<CGAL::Triangulation_vertex_base_with_info_3<std::size_t, Kernel>,
                                                   CGAL::Delaunay_triangulation_cell_base_3<Kernel>>>;

  const std::vector<std::size_t>& neighbours(std::size_t p);
  // t ∩ V_p, or an empty Work; appends to `touching` every s whose bisector holds a vertex.
  Work clip(std::size_t t, std::size_t p, std::vector<std::size_t>& touching);
  void record_contact(const RvdVertex& v, std::size_t p, std::size_t s);

  Input in_;
  Tr tr_;
  std::vector<Tr::Vertex_handle> handles_;
  std::vector<std::vector<std::size_t>> neighbours_;
  std::vector<bool> neighbours_known_;
  // Keyed by kind, sites and the input feature (vertex, edge or face), so that one contact found
  // from several cells is listed once.
  std::map<std::tuple<RvdContactKind, std::vector<std::size_t>, std::array<std::size_t, 2>>, RvdVertex> contacts_;
  Counters counters_;
};

const std::vector<std::size_t>& Builder::neighbours(std::size_t p) {
  if (neighbours_known_[p]) return neighbours_[p];
  std::vector<Tr::Vertex_handle> adjacent;
  tr_.finite_adjacent_vertices(handles_[p], std::back_inserter(adjacent));
  std::vector<std::pair<double, std::size_t>> by_distance;
  for (const auto& h : adjacent)
    by_distance.emplace_back(CGAL::squared_distance(in_.samples[p], in_.samples[h->info()]), h->info());
  std::sort(by_distance.begin(), by_distance.end());
  for (const auto& [d, q] : by_distance) neighbours_[p].push_back(q);
  neighbours_known_[p] = true;
  return neighbours_[p];
}

void Builder::record_contact(const RvdVertex& v, std::size_t p, std::size_t s) {
  std::vector<std::size_t> sites{p, s};
  RvdContactKind kind = RvdContactKind::input_vertex_on_bisector;
  if (v.kind == RvdVertexKind::edge_cut) {
    kind = RvdContactKind::voronoi_edge_through_input_edge;
    sites.assign(v.sites.begin(), v.sites.begin() + 2);
    sites.push_back(s);
  } else if (v.kind == RvdVertexKind::face_cut) {
    kind = RvdContactKind::voronoi_vertex_on_surface;
    sites.assign(v.sites.begin(), v.sites.end());
    sites.push_back(s);
  }
  std::sort(sites.begin(), sites.end());
  sites.erase(std::unique(sites.begin(), sites.end()), sites.end());
  contacts_.emplace(std::make_tuple(kind, std::move(sites), v.input), v);
}

Work Builder::clip(std::size_t t, std::size_t p, std::vector<std::size_t>& touching) {
  const auto c = in_.corners(t);
  Work w;
  for (int k = 0; k < 3; ++k) {
    const std::size_t u = c[k], v = c[(k + 1) % 3];
    const Point3& x = in_.vertex(u);
    w.add(input_vertex(u), {false, std::min(u, v), std::max(u, v)}, {x.x(), x.y(), x.z()});
  }
  const Point3& site = in_.samples[p];
  std::vector<int> signs;
  for (const std::size_t s : neighbours(p)) {
    // Skip s (and every farther neighbour) once the polygon lies in a ball around p of radius
    // below |ps|/2 (rounded distances, with a margin that covers their rounding).
    double radius2 = 0;
    for (const auto& x : w.points) {
      radius2 = std::max(radius2, (x[0] - site.x()) * (x[0] - site.x()) + (x[1] - site.y()) * (x[1] - site.y()) +
                                      (x[2] - site.z()) * (x[2] - site.z()));
    }
    const double half2 = CGAL::squared_distance(site, in_.samples[s]) / 4;
    if (half2 > radius2 * (1 + 1e-6) + 1e-300) break;

    const std::size_t n = w.vertices.size();
    signs.assign(n, 0);
    bool any_out = false, any_in = false;
    for (std::size_t i = 0; i < n; ++i) {
      signs[i] = side(w.vertices[i], p, s, in_, counters_);
      if (signs[i] == 0) {
        record_contact(w.vertices[i], p, s);
        touching.push_back(s);
      }
      any_out |= signs[i] > 0;
      any_in |= signs[i] <= 0;
    }
    if (!any_out) continue;
    if (!any_in) return {};
    Work out;
    const RvdEdgeSupport on_s{true, s, rvd_none};
    const auto cut = [&](const RvdEdgeSupport& e) {
      return e.on_bisector ? face_cut(t, p, e.a, s) : edge_cut(e.a, e.b, p, s);
    };
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t j = (i + 1) % n;
      if (signs[i] <= 0) {
        out.add(w.vertices[i], w.edges[i], w.points[i]);
        if (signs[j] > 0) {
          if (signs[i] < 0) {
            const RvdVertex x = cut(w.edges[i]);
            out.add(x, on_s, point_of(x, in_));
          } else {
            out.edges.back() = on_s;
          }
        }
      } else if (signs[j] < 0) {
        const RvdVertex x = cut(w.edges[i]);
        out.add(x, w.edges[i], point_of(x, in_));
      }
    }
    if (out.vertices.size() < 3) return {};
    w = std::move(out);
  }
  return w;
}

RestrictedVoronoiMesh Builder::run() {
  const std::vector<Point3>& samples = in_.samples;
  const SurfaceMesh& mesh = in_.mesh;
  for (const Point3& s : samples)
    if (!std::isfinite(s.x()) || !std::isfinite(s.y()) || !std::isfinite(s.z()))
      throw PreconditionViolation("restricted_voronoi_mesh: a sample is not finite");
  if (mesh.has_garbage()) throw PreconditionViolation("restricted_voronoi_mesh: the mesh has removed elements");
  for (const auto h : mesh.halfedges())
    if (mesh.is_border(h)) throw PreconditionViolation("restricted_voronoi_mesh: the mesh is not closed");
  for (const auto f : mesh.faces())
    if (mesh.degree(f) != 3) throw PreconditionViolation("restricted_voronoi_mesh: a face is not a triangle");
  for (const auto v : mesh.vertices()) {
    const Point3& x = mesh.point(v);
    if (!std::isfinite(x.x()) || !std::isfinite(x.y()) || !std::isfinite(x.z()))
      throw PreconditionViolation("restricted_voronoi_mesh: a mesh vertex is not finite");
  }

  RestrictedVoronoiMesh result;
  result.cells.resize(samples.size());
  if (samples.empty() || mesh.number_of_faces() == 0) return result;

  std::vector<std::pair<Point3, std::size_t>> points;
  for (std::size_t i = 0; i < samples.size(); ++i) points.emplace_back(samples[i], i);
  tr_.insert(points.begin(), points.end());
  if (tr_.number_of_vertices() != samples.size())
    throw PreconditionViolation("restricted_voronoi_mesh: two samples coincide");
  handles_.resize(samples.size());
  for (auto v = tr_.finite_vertices_begin(); v != tr_.finite_vertices_end(); ++v) handles_[v->info()] = v;
  neighbours_.resize(samples.size());
  neighbours_known_.assign(samples.size(), false);

  Tr::Vertex_handle hint;
  for (const auto f : mesh.faces()) {
    const std::size_t t = std::size_t(f);
    const auto c = in_.corners(t);
    hint = tr_.nearest_vertex(in_.vertex(c[0]), hint == Tr::Vertex_handle() ? Tr::Cell_handle() : hint->cell());
    std::vector<std::size_t> queue{hint->info()};
    std::set<std::size_t> seen{hint->info()};
    std::vector<std::size_t> touching;
    for (std::size_t k = 0; k < queue.size(); ++k) {
      const std::size_t p = queue[k];
      touching.clear();
      Work w = clip(t, p, touching);
      // A cell that touches p's polygon only at a non-generic contact is visited too.
      for (const std::size_t s : touching)
        if (seen.insert(s).second) queue.push_back(s);
      if (w.vertices.empty()) continue;
      for (const RvdEdgeSupport& e : w.edges)
        if (e.on_bisector && seen.insert(e.a).second) queue.push_back(e.a);
      RvdPolygon polygon;
      polygon.site = p;
      polygon.face = t;
      polygon.points = std::move(w.points);
      polygon.vertices = std::move(w.vertices);
      polygon.edges = std::move(w.edges);
      result.cells[p].push_back(std::move(polygon));
    }
  }
  for (const auto& [key, v] : contacts_)
    result.contacts.push_back({std::get<0>(key), v, std::get<1>(key), point_of(v, in_)});
  result.sign_tests = counters_.sign_tests;
  result.exact_evaluations = counters_.exact;
  return result;
}

}  // namespace

RestrictedVoronoiMesh restricted_voronoi_mesh(const std::vector<Point3>& samples, const SurfaceMesh& mesh) {
  Builder builder(samples, mesh);
  return builder.run();
}

std::array<double, 3> rvd_point(const RvdVertex& v, const std::vector<Point3>& samples, const SurfaceMesh& mesh) {
  return point_of(v, Input{samples, mesh});
}

}  // namespace delmesh
