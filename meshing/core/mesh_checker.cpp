#include "meshing/core/mesh_checker.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
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

//! Components below 2^256 and above 2^-256 in magnitude need no scaling: the products of two of
//! them below stay between 2^-512 and 2^512, inside the normal range.
constexpr int unscaled_exponents = 256;

//! The exponent e of the largest component of v in magnitude (2^e ≤ max |v_i| < 2^(e+1)), or 0
//! when |e| < unscaled_exponents or v = 0 (v is then used as it is).
int exponent_of(const Vec& v) {
  const double m = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  const int e = m > 0 ? std::ilogb(m) : 0;
  return std::abs(e) < unscaled_exponents ? 0 : e;
}
//! v · 2^-e, exact while the result stays in the normal range (a power-of-two scaling rounds
//! nothing), so that the squares and products of the measures below neither overflow nor
//! underflow at any scale of the mesh, and give the same bits as unscaled where they would not.
Vec scaled(const Vec& v, int e) {
  if (e == 0) return v;
  return {std::scalbn(v.x, -e), std::scalbn(v.y, -e), std::scalbn(v.z, -e)};
}
//! |v|, computed on v scaled by exponent_of(v): no square overflows or underflows.
double length(const Vec& v) {
  const int e = exponent_of(v);
  return e == 0 ? norm(v) : std::scalbn(norm(scaled(v, e)), e);
}
//! The angle between u and v in [0, π], accurate also near 0 and π, and independent of the
//! lengths of u and v (each is first scaled by 2^-exponent_of: cross and dot scale alike).
double angle_between(const Vec& u, const Vec& v) {
  const Vec su = scaled(u, exponent_of(u)), sv = scaled(v, exponent_of(v));
  return std::atan2(norm(cross(su, sv)), dot(su, sv));
}

class UnionFind {
 public:
  explicit UnionFind(std::size_t n = 0) { reset(n); }
  //! n singletons.
  void reset(std::size_t n) {
    parent_.resize(n);
    std::iota(parent_.begin(), parent_.end(), 0);
  }
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

//! The buffers of link_kind(), kept from one vertex to the next.
struct LinkScratch {
  std::vector<std::size_t> nodes;
  std::vector<int> degree;
  UnionFind pieces;
};

LinkKind link_kind(const std::vector<std::pair<std::size_t, std::size_t>>& link, LinkScratch& scratch) {
  std::vector<std::size_t>& nodes = scratch.nodes;
  nodes.clear();
  for (const auto& [a, b] : link) {
    nodes.push_back(a);
    nodes.push_back(b);
  }
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  auto local = [&nodes](std::size_t v) {
    return static_cast<std::size_t>(std::lower_bound(nodes.begin(), nodes.end(), v) - nodes.begin());
  };
  std::vector<int>& degree = scratch.degree;
  degree.assign(nodes.size(), 0);
  UnionFind& pieces = scratch.pieces;
  pieces.reset(nodes.size());
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

namespace {

//! One run of check_mesh on a soup.  The algorithm, one method per step:
//!  1. validate the soup (indices, distinct corners, finite coordinates) and count its vertices;
//!  2. index the triangles incident to each vertex;
//!  3. components: triangles sharing a vertex;
//!  4. edges, grouped by their undirected key: lengths, boundary and non-manifold edges,
//!     misoriented pairs and the roughness of consistently oriented pairs; boundary loops;
//!  5. orientability: a breadth-first search per component over the manifold edges;
//!  6. vertex links: one cycle at every vertex of a closed manifold;
//!  7. triangle quality: smallest angle, radius-edge ratio, signed volume;
//!  8. per-component results, sorted by genus, then size.
class SoupCheck {
 public:
  SoupCheck(const std::vector<Point3>& points, const std::vector<Triangle>& triangles)
      : points_(points), triangles_(triangles), n_points_(points.size()), n_triangles_(triangles.size()) {}

  MeshReport run() {
    validate();
    if (n_triangles_ == 0) return std::move(report_);
    index_incidences();
    find_components();
    scan_edges();
    count_boundary_loops();
    check_orientability();
    check_vertex_links();
    measure_triangles();
    summarize_components();
    return std::move(report_);
  }

 private:
  //! Neighbour across an edge, and whether the two triangles traverse it in the same direction.
  struct Neighbour {
    std::size_t triangle;
    bool same_direction;
  };

  void validate() {
    std::vector<char> referenced(n_points_, 0);
    for (std::size_t t = 0; t < n_triangles_; ++t) {
      const Triangle& tri = triangles_[t];
      for (std::size_t v : tri) {
        if (v >= n_points_) {
          throw InvalidInput("check_mesh: triangle " + std::to_string(t) + " has vertex index " +
                             std::to_string(v) + " but there are " + std::to_string(n_points_) +
                             " points");
        }
        referenced[v] = 1;
      }
      if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) {
        throw InvalidInput("check_mesh: triangle " + std::to_string(t) + " repeats a vertex index");
      }
    }
    p_.resize(n_points_);
    for (std::size_t i = 0; i < n_points_; ++i) {
      p_[i] = {points_[i].x(), points_[i].y(), points_[i].z()};
      if (referenced[i] && !(std::isfinite(p_[i].x) && std::isfinite(p_[i].y) && std::isfinite(p_[i].z))) {
        throw InvalidInput("check_mesh: point " + std::to_string(i) + " has a non-finite coordinate");
      }
    }
    report_.triangles = n_triangles_;
    report_.vertices = static_cast<std::size_t>(std::count(referenced.begin(), referenced.end(), 1));
    report_.unreferenced_vertices = n_points_ - report_.vertices;
  }

  //! Vertex → incident triangles (CSR: incident_[first_[v] .. first_[v + 1])).
  void index_incidences() {
    first_.assign(n_points_ + 1, 0);
    for (const Triangle& tri : triangles_)
      for (std::size_t v : tri) ++first_[v + 1];
    std::partial_sum(first_.begin(), first_.end(), first_.begin());
    incident_.resize(3 * n_triangles_);
    std::vector<std::size_t> fill(first_.begin(), first_.end() - 1);
    for (std::size_t t = 0; t < n_triangles_; ++t)
      for (std::size_t v : triangles_[t]) incident_[fill[v]++] = t;
  }

  //! The component of the triangles at vertex v (v must have one).
  ComponentReport& component_at(std::size_t v) { return components_[component_of_[incident_[first_[v]]]]; }

  void find_components() {
    UnionFind faces(n_triangles_);
    for (std::size_t v = 0; v < n_points_; ++v)
      for (std::size_t k = first_[v] + 1; k < first_[v + 1]; ++k) faces.unite(incident_[first_[v]], incident_[k]);
    component_of_.assign(n_triangles_, -1);
    for (std::size_t t = 0; t < n_triangles_; ++t) {
      const std::size_t root = faces.find(t);
      if (component_of_[root] < 0) {
        component_of_[root] = static_cast<int>(components_.size());
        components_.emplace_back();
      }
      component_of_[t] = component_of_[root];
      ++components_[component_of_[t]].triangles;
    }
    for (std::size_t v = 0; v < n_points_; ++v)
      if (first_[v + 1] > first_[v]) ++component_at(v).vertices;
    // Per-component flags start true and are cleared by counter-examples.
    closed_.assign(components_.size(), 1);
    manifold_.assign(components_.size(), 1);
    orientable_.assign(components_.size(), 1);
  }

  //! The edges in the order of their keys {lo, hi}, each with its uses in the order of their
  //! triangles: at each vertex lo in turn, the uses by its incident triangles of the edges to
  //! vertices hi > lo, sorted by (hi, triangle) (a few per vertex, not all 3F at once).
  void scan_edges() {
    normal_.resize(n_triangles_);
    frame_exponent_.resize(n_triangles_);
    for (std::size_t t = 0; t < n_triangles_; ++t) {
      const Vec& a = p_[triangles_[t][0]];
      const Vec u = p_[triangles_[t][1]] - a, v = p_[triangles_[t][2]] - a;
      frame_exponent_[t] = std::max(exponent_of(u), exponent_of(v));
      normal_[t] = cross(scaled(u, frame_exponent_[t]), scaled(v, frame_exponent_[t]));
    }
    across_.assign(n_triangles_, {});
    boundary_graph_ = std::make_unique<UnionFind>(n_points_);
    on_boundary_.assign(n_points_, 0);
    bool oriented = true;
    report_.min_edge_length = std::numeric_limits<double>::infinity();
    report_.max_edge_length = 0;
    std::vector<EdgeUse> uses;
    for (std::size_t lo = 0; lo < n_points_; ++lo) {
      uses.clear();
      for (std::size_t k = first_[lo]; k < first_[lo + 1]; ++k) {
        const std::size_t t = incident_[k];
        const Triangle& tri = triangles_[t];
        const int at = tri[0] == lo ? 0 : (tri[1] == lo ? 1 : 2);
        // t runs lo → next and previous → lo.
        const std::size_t next = tri[(at + 1) % 3], previous = tri[(at + 2) % 3];
        if (next > lo) uses.push_back({lo, next, t, true});
        if (previous > lo) uses.push_back({lo, previous, t, false});
      }
      std::sort(uses.begin(), uses.end(), [](const EdgeUse& u, const EdgeUse& w) {
        return u.hi < w.hi || (u.hi == w.hi && u.triangle < w.triangle);
      });
      for (std::size_t begin = 0; begin < uses.size();) {
        std::size_t end = begin;
        while (end < uses.size() && uses[end].hi == uses[begin].hi) ++end;
        oriented = edge(uses.data() + begin, end - begin) && oriented;
        begin = end;
      }
    }
    report_.oriented = oriented;
  }

  //! One edge and its `count` uses, in the order of their triangles.  \return false if it is a
  //! non-manifold edge or two triangles traverse it the same way.
  bool edge(const EdgeUse* uses, std::size_t count) {
    const EdgeUse& u = uses[0];
    const int c = component_of_[u.triangle];
    ++report_.edges;
    ++components_[c].edges;
    const double edge_length = length(p_[u.hi] - p_[u.lo]);
    report_.min_edge_length = std::min(report_.min_edge_length, edge_length);
    report_.max_edge_length = std::max(report_.max_edge_length, edge_length);
    if (count == 2) return pair_edge(u, uses[1]);
    closed_[c] = 0;
    if (count == 1) boundary_edge(u, c);
    if (count >= 3) {
      nonmanifold_edge(u, c);
      return false;
    }
    return true;
  }

  //! An edge of two triangles u and w: adjacency for the orientation search and roughness.
  //! \return whether the two traverse it in opposite directions (consistently oriented).
  bool pair_edge(const EdgeUse& u, const EdgeUse& w) {
    const bool same = u.forward == w.forward;
    if (same) {
      ++report_.misoriented_edges;
      if (!report_.first_misoriented_edge) report_.first_misoriented_edge = {{u.lo, u.hi}};
    }
    across_[u.triangle].add({w.triangle, same});
    across_[w.triangle].add({u.triangle, same});
    // Roughness: the angle between the normals of the consistently oriented pair.
    const Vec& nu = normal_[u.triangle];
    Vec nw = normal_[w.triangle];
    if (same) nw = {-nw.x, -nw.y, -nw.z};
    const bool degenerate = dot(nu, nu) == 0.0 || dot(nw, nw) == 0.0;
    const double roughness = degenerate ? pi : angle_between(nu, nw);
    report_.max_roughness_rad = std::max(report_.max_roughness_rad, roughness);
    return !same;
  }

  void boundary_edge(const EdgeUse& u, int c) {
    if (!report_.first_boundary_edge) report_.first_boundary_edge = {{u.lo, u.hi}};
    ++report_.boundary_edges;
    ++components_[c].boundary_edges;
    boundary_graph_->unite(u.lo, u.hi);
    on_boundary_[u.lo] = 1;
  }

  void nonmanifold_edge(const EdgeUse& u, int c) {
    if (!report_.first_nonmanifold_edge) report_.first_nonmanifold_edge = {{u.lo, u.hi}};
    ++report_.nonmanifold_edges;
    ++components_[c].nonmanifold_edges;
    orientable_[c] = 0;
  }

  //! Boundary loops: the connected pieces of the graph of boundary edges.
  void count_boundary_loops() {
    for (std::size_t v = 0; v < n_points_; ++v) {
      // One count per piece, at its smallest vertex (UnionFind keeps the smallest index as the
      // root); that vertex lies on a boundary edge, so it has an incident triangle.
      if (!on_boundary_[v] || boundary_graph_->find(v) != v) continue;
      ++report_.boundary_loops;
      ++component_at(v).boundary_loops;
    }
  }

  void check_orientability() {
    std::vector<signed char> flip(n_triangles_, -1);
    for (std::size_t seed = 0; seed < n_triangles_; ++seed) {
      if (flip[seed] >= 0) continue;
      flip[seed] = 0;
      std::queue<std::size_t> queue;
      queue.push(seed);
      while (!queue.empty()) {
        const std::size_t t = queue.front();
        queue.pop();
        const Across& across = across_[t];
        for (std::size_t k = 0; k < across.count; ++k) {
          const Neighbour& nb = across.neighbours[k];
          // Consistent iff the effective directions differ: flip_nb = flip_t XOR same_direction.
          const signed char wanted = static_cast<signed char>(flip[t] ^ (nb.same_direction ? 1 : 0));
          if (flip[nb.triangle] < 0) {
            flip[nb.triangle] = wanted;
            queue.push(nb.triangle);
          } else if (flip[nb.triangle] != wanted) {
            orientable_[component_of_[t]] = 0;
          }
        }
      }
    }
  }

  void check_vertex_links() {
    std::vector<std::pair<std::size_t, std::size_t>> link;
    LinkScratch scratch;
    for (std::size_t v = 0; v < n_points_; ++v) {
      if (first_[v + 1] == first_[v]) continue;
      link.clear();
      for (std::size_t k = first_[v]; k < first_[v + 1]; ++k) {
        const Triangle& tri = triangles_[incident_[k]];
        const int at = tri[0] == v ? 0 : (tri[1] == v ? 1 : 2);
        link.emplace_back(tri[(at + 1) % 3], tri[(at + 2) % 3]);
      }
      const LinkKind kind = link_kind(link, scratch);
      if (kind == LinkKind::other) {
        if (!report_.first_nonmanifold_vertex) report_.first_nonmanifold_vertex = v;
        ++report_.nonmanifold_vertices;
        ++component_at(v).nonmanifold_vertices;
      }
      if (kind != LinkKind::cycle) manifold_[component_of_[incident_[first_[v]]]] = 0;
    }
  }

  void measure_triangles() {
    report_.min_angle_deg = 180.0;
    for (std::size_t t = 0; t < n_triangles_; ++t) {
      const Vec& a = p_[triangles_[t][0]];
      const Vec& b = p_[triangles_[t][1]];
      const Vec& c = p_[triangles_[t][2]];
      // Lengths and the area in the triangle's frame scaled by 2^-frame_exponent_[t]: the
      // ratio and the angles do not depend on the scale, and no product overflows or underflows.
      const int e = frame_exponent_[t];
      const double twice_area = norm(normal_[t]);
      report_.signed_volume += dot(a, cross(b, c)) / 6.0;
      const double ab = norm(scaled(b - a, e)), bc = norm(scaled(c - b, e)), ca = norm(scaled(a - c, e));
      double smallest_angle = 0, ratio = std::numeric_limits<double>::infinity();
      if (twice_area > 0) {
        smallest_angle = std::min({angle_between(b - a, c - a), angle_between(c - b, a - b),
                                   angle_between(a - c, b - c)});
        const double circumradius = ab * bc * ca / (2.0 * twice_area);
        ratio = circumradius / std::min({ab, bc, ca});
      }
      report_.min_angle_deg = std::min(report_.min_angle_deg, smallest_angle * 180.0 / pi);
      report_.max_radius_edge_ratio = std::max(report_.max_radius_edge_ratio, ratio);
    }
  }

  void summarize_components() {
    bool all_closed = true, all_manifold = true, all_orientable = true;
    for (std::size_t c = 0; c < components_.size(); ++c) {
      ComponentReport& comp = components_[c];
      comp.euler_characteristic = static_cast<int>(comp.vertices) - static_cast<int>(comp.edges) +
                                  static_cast<int>(comp.triangles);
      comp.closed = closed_[c];
      comp.manifold = comp.closed && manifold_[c];
      comp.orientable = orientable_[c];
      comp.genus = (comp.manifold && comp.orientable) ? (2 - comp.euler_characteristic) / 2 : -1;
      all_closed = all_closed && comp.closed;
      all_manifold = all_manifold && comp.manifold;
      all_orientable = all_orientable && comp.orientable;
    }
    std::sort(components_.begin(), components_.end(), [](const ComponentReport& a, const ComponentReport& b) {
      return std::make_tuple(a.genus, -static_cast<long long>(a.triangles), -static_cast<long long>(a.vertices)) <
             std::make_tuple(b.genus, -static_cast<long long>(b.triangles), -static_cast<long long>(b.vertices));
    });
    report_.components = static_cast<int>(components_.size());
    report_.euler_characteristic = static_cast<int>(report_.vertices) - static_cast<int>(report_.edges) +
                                   static_cast<int>(report_.triangles);
    for (const ComponentReport& comp : components_) report_.genus_per_component.push_back(comp.genus);
    report_.component_reports = std::move(components_);
    report_.closed = all_closed;
    report_.manifold = all_manifold;
    report_.orientable = all_orientable;
  }

  const std::vector<Point3>& points_;
  const std::vector<Triangle>& triangles_;
  const std::size_t n_points_, n_triangles_;
  MeshReport report_;
  std::vector<Vec> p_;                       //!< the points' coordinates
  std::vector<std::size_t> first_, incident_;
  std::vector<int> component_of_;            //!< triangle → index into components_
  std::vector<ComponentReport> components_;
  std::vector<char> closed_, manifold_, orientable_;  //!< per component
  //! The neighbours of a triangle across its edges of two triangles (one per edge, so at most 3).
  struct Across {
    std::array<Neighbour, 3> neighbours;
    unsigned char count = 0;
    void add(const Neighbour& n) { neighbours[count++] = n; }
  };
  std::vector<Across> across_;                        //!< per triangle
  //! Per triangle t = abc: (b − a) × (c − a) scaled by 2^(−2 frame_exponent_[t]), i.e. twice its
  //! area in length in the triangle's frame scaled by 2^(−frame_exponent_[t]).
  std::vector<Vec> normal_;
  //! Per triangle, the exponent of the largest component of b − a and c − a.
  std::vector<int> frame_exponent_;
  std::unique_ptr<UnionFind> boundary_graph_;         //!< over the vertices, by boundary edges
  std::vector<char> on_boundary_;
};

}  // namespace

MeshReport check_mesh(const std::vector<Point3>& points, const std::vector<Triangle>& triangles) {
  return SoupCheck(points, triangles).run();
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
