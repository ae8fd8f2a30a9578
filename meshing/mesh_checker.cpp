#include "meshing/mesh_checker.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <queue>
#include <string>
#include <tuple>

#include <boost/math/constants/constants.hpp>

#include "common/errors.h"

namespace delmesh {
namespace {

constexpr double pi = boost::math::constants::pi<double>();
using Triangle = std::array<std::size_t, 3>;

struct Vec {
  double x, y, z;
};
Vec operator-(const Vec& a, const Vec& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
double dot(const Vec& a, const Vec& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec cross(const Vec& a, const Vec& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double norm(const Vec& a) { return std::sqrt(dot(a, a)); }
//! The angle between u and v in [0, π], accurate also near 0 and π.
double angle_between(const Vec& u, const Vec& v) { return std::atan2(norm(cross(u, v)), dot(u, v)); }

class UnionFind {
 public:
  explicit UnionFind(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  std::size_t find(std::size_t i) {
    while (parent_[i] != i) {
      parent_[i] = parent_[parent_[i]];
      i = parent_[i];
    }
    return i;
  }
  void unite(std::size_t a, std::size_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<std::size_t> parent_;
};

//! One use of an undirected edge {lo, hi} by a triangle; forward iff the triangle goes lo → hi.
struct EdgeUse {
  std::size_t lo, hi, triangle;
  bool forward;
};

//! Kind of the link of a vertex: one cycle (interior vertex of a manifold), one path (boundary
//! vertex of a manifold with boundary), or anything else.
enum class LinkKind { cycle, path, other };

LinkKind link_kind(std::vector<std::pair<std::size_t, std::size_t>>& link) {
  std::vector<std::size_t> nodes;
  nodes.reserve(2 * link.size());
  for (const auto& [a, b] : link) {
    nodes.push_back(a);
    nodes.push_back(b);
  }
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  auto local = [&nodes](std::size_t v) {
    return static_cast<std::size_t>(std::lower_bound(nodes.begin(), nodes.end(), v) - nodes.begin());
  };
  std::vector<int> degree(nodes.size(), 0);
  UnionFind pieces(nodes.size());
  for (const auto& [a, b] : link) {
    const std::size_t la = local(a), lb = local(b);
    ++degree[la];
    ++degree[lb];
    pieces.unite(la, lb);
  }
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (pieces.find(i) != 0) return LinkKind::other;  // disconnected link
  }
  const auto ends = std::count(degree.begin(), degree.end(), 1);
  const bool degrees_ok =
      std::all_of(degree.begin(), degree.end(), [](int d) { return d == 1 || d == 2; });
  if (!degrees_ok) return LinkKind::other;
  if (ends == 0) return LinkKind::cycle;
  if (ends == 2) return LinkKind::path;
  return LinkKind::other;
}

}  // namespace

bool MeshReport::has_topology(const std::vector<int>& expected_genera) const {
  std::vector<int> sorted = expected_genera;
  std::sort(sorted.begin(), sorted.end());
  return closed && manifold && orientable && genus_per_component == sorted;
}

MeshReport check_mesh(const std::vector<Point3>& input_points,
                      const std::vector<Triangle>& triangles) {
  const std::size_t n_points = input_points.size();
  const std::size_t n_triangles = triangles.size();
  // Validation: indices in range, three distinct indices, finite referenced coordinates.
  std::vector<char> referenced(n_points, 0);
  for (std::size_t t = 0; t < n_triangles; ++t) {
    const Triangle& tri = triangles[t];
    for (std::size_t v : tri) {
      if (v >= n_points) {
        throw InvalidInput("check_mesh: triangle " + std::to_string(t) + " has vertex index " +
                           std::to_string(v) + " but there are " + std::to_string(n_points) +
                           " points");
      }
      referenced[v] = 1;
    }
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) {
      throw InvalidInput("check_mesh: triangle " + std::to_string(t) + " repeats a vertex index");
    }
  }
  std::vector<Vec> p(n_points);
  for (std::size_t i = 0; i < n_points; ++i) {
    p[i] = {input_points[i].x(), input_points[i].y(), input_points[i].z()};
    if (referenced[i] && !(std::isfinite(p[i].x) && std::isfinite(p[i].y) && std::isfinite(p[i].z))) {
      throw InvalidInput("check_mesh: point " + std::to_string(i) + " has a non-finite coordinate");
    }
  }

  MeshReport report;
  report.triangles = n_triangles;
  report.vertices = static_cast<std::size_t>(std::count(referenced.begin(), referenced.end(), 1));
  report.unreferenced_vertices = n_points - report.vertices;
  if (n_triangles == 0) return report;

  // Vertex → incident triangles (CSR).
  std::vector<std::size_t> first(n_points + 1, 0);
  for (const Triangle& tri : triangles)
    for (std::size_t v : tri) ++first[v + 1];
  std::partial_sum(first.begin(), first.end(), first.begin());
  std::vector<std::size_t> incident(3 * n_triangles);
  {
    std::vector<std::size_t> fill(first.begin(), first.end() - 1);
    for (std::size_t t = 0; t < n_triangles; ++t)
      for (std::size_t v : triangles[t]) incident[fill[v]++] = t;
  }

  // Components: triangles sharing a vertex.
  UnionFind faces(n_triangles);
  for (std::size_t v = 0; v < n_points; ++v)
    for (std::size_t k = first[v] + 1; k < first[v + 1]; ++k) faces.unite(incident[first[v]], incident[k]);
  std::vector<int> component_of(n_triangles, -1);
  std::vector<ComponentReport> components;
  for (std::size_t t = 0; t < n_triangles; ++t) {
    const std::size_t root = faces.find(t);
    if (component_of[root] < 0) {
      component_of[root] = static_cast<int>(components.size());
      components.emplace_back();
    }
    component_of[t] = component_of[root];
    ++components[component_of[t]].triangles;
  }
  for (std::size_t v = 0; v < n_points; ++v)
    if (first[v + 1] > first[v]) ++components[component_of[incident[first[v]]]].vertices;

  // Edges, grouped by their undirected key.
  std::vector<EdgeUse> uses;
  uses.reserve(3 * n_triangles);
  for (std::size_t t = 0; t < n_triangles; ++t) {
    for (int k = 0; k < 3; ++k) {
      const std::size_t a = triangles[t][k], b = triangles[t][(k + 1) % 3];
      uses.push_back({std::min(a, b), std::max(a, b), t, a < b});
    }
  }
  std::sort(uses.begin(), uses.end(), [](const EdgeUse& u, const EdgeUse& w) {
    return std::tie(u.lo, u.hi, u.triangle) < std::tie(w.lo, w.hi, w.triangle);
  });

  // Per-component flags start true and are cleared by counter-examples.
  std::vector<char> comp_closed(components.size(), 1), comp_manifold(components.size(), 1),
      comp_orientable(components.size(), 1);
  // Edge adjacency for the orientation BFS: neighbour across each of the 3 edges, with whether
  // the two triangles traverse the edge in the same direction.
  struct Neighbour {
    std::size_t triangle;
    bool same_direction;
  };
  std::vector<std::vector<Neighbour>> across(n_triangles);
  std::vector<Vec> normal(n_triangles);
  for (std::size_t t = 0; t < n_triangles; ++t) {
    const Vec& a = p[triangles[t][0]];
    normal[t] = cross(p[triangles[t][1]] - a, p[triangles[t][2]] - a);
  }

  // Boundary loops: the connected pieces of the graph of boundary edges.
  UnionFind boundary_graph(n_points);
  std::vector<char> on_boundary(n_points, 0);
  bool oriented = true;
  report.min_edge_length = std::numeric_limits<double>::infinity();
  report.max_edge_length = 0;
  for (std::size_t begin = 0; begin < uses.size();) {
    std::size_t end = begin;
    while (end < uses.size() && uses[end].lo == uses[begin].lo && uses[end].hi == uses[begin].hi) ++end;
    const std::size_t count = end - begin;
    const int c = component_of[uses[begin].triangle];
    ++report.edges;
    ++components[c].edges;
    const double length = norm(p[uses[begin].hi] - p[uses[begin].lo]);
    report.min_edge_length = std::min(report.min_edge_length, length);
    report.max_edge_length = std::max(report.max_edge_length, length);
    if (count != 2) {
      comp_closed[c] = 0;
      if (count == 1) {
        if (!report.first_boundary_edge) report.first_boundary_edge = {{uses[begin].lo, uses[begin].hi}};
        ++report.boundary_edges;
        ++components[c].boundary_edges;
        boundary_graph.unite(uses[begin].lo, uses[begin].hi);
        on_boundary[uses[begin].lo] = 1;
      }
      if (count >= 3) {
        if (!report.first_nonmanifold_edge) report.first_nonmanifold_edge = {{uses[begin].lo, uses[begin].hi}};
        ++report.nonmanifold_edges;
        ++components[c].nonmanifold_edges;
        comp_orientable[c] = 0;
        oriented = false;
      }
    } else {
      const EdgeUse& u = uses[begin];
      const EdgeUse& w = uses[begin + 1];
      const bool same = u.forward == w.forward;
      if (same) {
        oriented = false;
        ++report.misoriented_edges;
        if (!report.first_misoriented_edge) report.first_misoriented_edge = {{u.lo, u.hi}};
      }
      across[u.triangle].push_back({w.triangle, same});
      across[w.triangle].push_back({u.triangle, same});
      // Roughness: the angle between the normals of the consistently oriented pair.
      const Vec& nu = normal[u.triangle];
      Vec nw = normal[w.triangle];
      if (same) nw = {-nw.x, -nw.y, -nw.z};
      const bool degenerate = dot(nu, nu) == 0.0 || dot(nw, nw) == 0.0;
      const double roughness = degenerate ? pi : angle_between(nu, nw);
      report.max_roughness_rad = std::max(report.max_roughness_rad, roughness);
    }
    begin = end;
  }
  report.oriented = oriented;
  for (std::size_t v = 0; v < n_points; ++v) {
    // One count per piece, at its smallest vertex (UnionFind keeps the smallest index as the
    // root); that vertex lies on a boundary edge, so it has an incident triangle.
    if (!on_boundary[v] || boundary_graph.find(v) != v) continue;
    ++report.boundary_loops;
    ++components[component_of[incident[first[v]]]].boundary_loops;
  }

  // Orientation BFS per component.
  std::vector<signed char> flip(n_triangles, -1);
  for (std::size_t seed = 0; seed < n_triangles; ++seed) {
    if (flip[seed] >= 0) continue;
    flip[seed] = 0;
    std::queue<std::size_t> queue;
    queue.push(seed);
    while (!queue.empty()) {
      const std::size_t t = queue.front();
      queue.pop();
      for (const Neighbour& nb : across[t]) {
        // Consistent iff the effective directions differ: flip_nb = flip_t XOR same_direction.
        const signed char wanted = static_cast<signed char>(flip[t] ^ (nb.same_direction ? 1 : 0));
        if (flip[nb.triangle] < 0) {
          flip[nb.triangle] = wanted;
          queue.push(nb.triangle);
        } else if (flip[nb.triangle] != wanted) {
          comp_orientable[component_of[t]] = 0;
        }
      }
    }
  }

  // Vertex links.
  std::vector<std::pair<std::size_t, std::size_t>> link;
  for (std::size_t v = 0; v < n_points; ++v) {
    if (first[v + 1] == first[v]) continue;
    link.clear();
    for (std::size_t k = first[v]; k < first[v + 1]; ++k) {
      const Triangle& tri = triangles[incident[k]];
      const int at = tri[0] == v ? 0 : (tri[1] == v ? 1 : 2);
      link.emplace_back(tri[(at + 1) % 3], tri[(at + 2) % 3]);
    }
    const LinkKind kind = link_kind(link);
    if (kind == LinkKind::other) {
      if (!report.first_nonmanifold_vertex) report.first_nonmanifold_vertex = v;
      ++report.nonmanifold_vertices;
      ++components[component_of[incident[first[v]]]].nonmanifold_vertices;
    }
    if (kind != LinkKind::cycle) comp_manifold[component_of[incident[first[v]]]] = 0;
  }

  // Triangle quality.
  report.min_angle_deg = 180.0;
  for (std::size_t t = 0; t < n_triangles; ++t) {
    const Vec& a = p[triangles[t][0]];
    const Vec& b = p[triangles[t][1]];
    const Vec& c = p[triangles[t][2]];
    const double twice_area = norm(normal[t]);
    report.signed_volume += dot(a, cross(b, c)) / 6.0;
    const double ab = norm(b - a), bc = norm(c - b), ca = norm(a - c);
    double smallest_angle = 0, ratio = std::numeric_limits<double>::infinity();
    if (twice_area > 0) {
      smallest_angle = std::min({angle_between(b - a, c - a), angle_between(c - b, a - b),
                                 angle_between(a - c, b - c)});
      const double circumradius = ab * bc * ca / (2.0 * twice_area);
      ratio = circumradius / std::min({ab, bc, ca});
    }
    report.min_angle_deg = std::min(report.min_angle_deg, smallest_angle * 180.0 / pi);
    report.max_radius_edge_ratio = std::max(report.max_radius_edge_ratio, ratio);
  }

  // Per-component results.
  bool all_closed = true, all_manifold = true, all_orientable = true;
  for (std::size_t c = 0; c < components.size(); ++c) {
    ComponentReport& comp = components[c];
    comp.euler_characteristic = static_cast<int>(comp.vertices) - static_cast<int>(comp.edges) +
                                static_cast<int>(comp.triangles);
    comp.closed = comp_closed[c];
    comp.manifold = comp.closed && comp_manifold[c];
    comp.orientable = comp_orientable[c];
    comp.genus = (comp.manifold && comp.orientable) ? (2 - comp.euler_characteristic) / 2 : -1;
    all_closed = all_closed && comp.closed;
    all_manifold = all_manifold && comp.manifold;
    all_orientable = all_orientable && comp.orientable;
  }
  std::sort(components.begin(), components.end(), [](const ComponentReport& a, const ComponentReport& b) {
    return std::make_tuple(a.genus, -static_cast<long long>(a.triangles), -static_cast<long long>(a.vertices)) <
           std::make_tuple(b.genus, -static_cast<long long>(b.triangles), -static_cast<long long>(b.vertices));
  });
  report.components = static_cast<int>(components.size());
  report.euler_characteristic = static_cast<int>(report.vertices) - static_cast<int>(report.edges) +
                                static_cast<int>(report.triangles);
  for (const ComponentReport& comp : components) report.genus_per_component.push_back(comp.genus);
  report.component_reports = std::move(components);
  report.closed = all_closed;
  report.manifold = all_manifold;
  report.orientable = all_orientable;
  return report;
}

void mesh_to_soup(const SurfaceMesh& mesh, std::vector<Point3>& points, std::vector<Triangle>& triangles) {
  points.clear();
  triangles.clear();
  std::vector<std::size_t> index(mesh.number_of_vertices() + mesh.number_of_removed_vertices(),
                                 std::numeric_limits<std::size_t>::max());
  for (SurfaceMesh::Vertex_index v : mesh.vertices()) {
    index[static_cast<std::size_t>(v)] = points.size();
    points.push_back(mesh.point(v));
  }
  for (SurfaceMesh::Face_index f : mesh.faces()) {
    Triangle tri{};
    std::size_t k = 0;
    for (SurfaceMesh::Vertex_index v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) {
      if (k == 3) {
        k = 4;
        break;
      }
      tri[k++] = index[static_cast<std::size_t>(v)];
    }
    if (k != 3) {
      throw InvalidInput("check_mesh: face " + std::to_string(static_cast<std::size_t>(f)) +
                         " is not a triangle");
    }
    triangles.push_back(tri);
  }
}

MeshReport check_mesh(const SurfaceMesh& mesh) {
  std::vector<Point3> points;
  std::vector<Triangle> triangles;
  mesh_to_soup(mesh, points, triangles);
  return check_mesh(points, triangles);
}

nlohmann::json to_json(const MeshReport& r) {
  auto finite_or_null = [](double value) -> nlohmann::json {
    return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
  };
  const auto genus = [](int g) { return g >= 0 ? nlohmann::json(g) : nlohmann::json(nullptr); };
  nlohmann::json components = nlohmann::json::array();
  for (const ComponentReport& c : r.component_reports) {
    components.push_back({{"vertices", c.vertices},
                          {"edges", c.edges},
                          {"triangles", c.triangles},
                          {"euler_characteristic", c.euler_characteristic},
                          {"closed", c.closed},
                          {"manifold", c.manifold},
                          {"orientable", c.orientable},
                          {"genus", genus(c.genus)},
                          {"boundary_edges", c.boundary_edges},
                          {"boundary_loops", c.boundary_loops},
                          {"nonmanifold_edges", c.nonmanifold_edges},
                          {"nonmanifold_vertices", c.nonmanifold_vertices}});
  }
  nlohmann::json genera = nlohmann::json::array();
  for (int g : r.genus_per_component) genera.push_back(genus(g));
  return {{"vertices", r.vertices},
          {"edges", r.edges},
          {"triangles", r.triangles},
          {"unreferenced_vertices", r.unreferenced_vertices},
          {"components", r.components},
          {"euler_characteristic", r.euler_characteristic},
          {"genus_per_component", genera},
          {"component_reports", components},
          {"closed", r.closed},
          {"manifold", r.manifold},
          {"closed_manifold", r.closed && r.manifold},
          {"orientable", r.orientable},
          {"oriented", r.oriented},
          {"boundary_edges", r.boundary_edges},
          {"boundary_loops", r.boundary_loops},
          {"nonmanifold_edges", r.nonmanifold_edges},
          {"nonmanifold_vertices", r.nonmanifold_vertices},
          {"signed_volume", r.signed_volume},
          {"min_angle_deg", r.min_angle_deg},
          {"max_radius_edge_ratio", finite_or_null(r.max_radius_edge_ratio)},
          {"max_roughness_rad", r.max_roughness_rad},
          {"min_edge_length", finite_or_null(r.min_edge_length)},
          {"max_edge_length", r.max_edge_length}};
}

std::ostream& operator<<(std::ostream& out, const MeshReport& r) {
  out << "V=" << r.vertices << " E=" << r.edges << " F=" << r.triangles << " components=" << r.components
      << " chi=" << r.euler_characteristic << " genus=[";
  for (std::size_t i = 0; i < r.genus_per_component.size(); ++i)
    out << (i ? "," : "") << r.genus_per_component[i];
  return out << "] closed=" << r.closed << " manifold=" << r.manifold << " orientable=" << r.orientable
             << " oriented=" << r.oriented << " min_angle_deg=" << r.min_angle_deg
             << " max_radius_edge_ratio=" << r.max_radius_edge_ratio
             << " max_roughness_rad=" << r.max_roughness_rad;
}

}  // namespace delmesh
