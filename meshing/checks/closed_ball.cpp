#include "meshing/checks/closed_ball.h"

#include <algorithm>
#include <iterator>
#include <chrono>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <sstream>
#include <string>
#include <utility>

#include "common/errors.h"

namespace delmesh {
namespace {

// Union–find over 0..n−1.
class Partition {
 public:
  explicit Partition(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), std::size_t(0)); }
  std::size_t find(std::size_t x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  void unite(std::size_t a, std::size_t b) { parent_[find(a)] = find(b); }
  //! The number of classes among `members`.
  std::size_t classes(const std::vector<std::size_t>& members) {
    std::set<std::size_t> roots;
    for (const std::size_t m : members) roots.insert(find(m));
    return roots.size();
  }

 private:
  std::vector<std::size_t> parent_;
};

double distance(const std::array<double, 3>& x, const Point3& p) {
  return std::sqrt((x[0] - p.x()) * (x[0] - p.x()) + (x[1] - p.y()) * (x[1] - p.y()) + (x[2] - p.z()) * (x[2] - p.z()));
}

// Keeps the point farthest from p.
struct Farthest {
  const Point3& from;
  std::array<double, 3> point{};
  double distance = -1;
  void offer(const std::array<double, 3>& x) {
    const double d = delmesh::distance(x, from);
    if (d > distance) {
      distance = d;
      point = x;
    }
  }
};

// The topology of one restricted cell, glued from its polygons.
struct CellShape {
  bool manifold = true;
  std::size_t components = 0, boundary_cycles = 0;
  long euler = 0;
};

CellShape cell_shape(const std::vector<RvdPolygon>& polygons) {
  std::map<RvdVertex, std::size_t> vertex_index;
  std::map<std::tuple<std::size_t, std::size_t, RvdEdgeSupport>, std::size_t> edge_index;
  std::vector<std::vector<std::size_t>> edge_faces;
  std::vector<std::array<std::size_t, 2>> edge_ends;
  // Per vertex, the pairs of its edges that are consecutive in a polygon (its link's edges).
  std::vector<std::vector<std::array<std::size_t, 2>>> link;
  const auto vertex = [&](const RvdVertex& v) {
    const auto [it, added] = vertex_index.emplace(v, vertex_index.size());
    if (added) link.emplace_back();
    return it->second;
  };
  for (std::size_t f = 0; f < polygons.size(); ++f) {
    const RvdPolygon& polygon = polygons[f];
    const std::size_t n = polygon.vertices.size();
    std::vector<std::size_t> ids(n), edges(n);
    for (std::size_t i = 0; i < n; ++i) ids[i] = vertex(polygon.vertices[i]);
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t a = ids[i], b = ids[(i + 1) % n];
      const auto key = std::make_tuple(std::min(a, b), std::max(a, b), polygon.edges[i]);
      const auto [it, added] = edge_index.emplace(key, edge_faces.size());
      if (added) {
        edge_faces.emplace_back();
        edge_ends.push_back({a, b});
      }
      edge_faces[it->second].push_back(f);
      edges[i] = it->second;
    }
    for (std::size_t i = 0; i < n; ++i) link[ids[i]].push_back({edges[(i + n - 1) % n], edges[i]});
  }
  CellShape shape;
  const std::size_t V = vertex_index.size(), E = edge_faces.size(), F = polygons.size();
  shape.euler = long(V) - long(E) + long(F);

  Partition faces(F), boundary(V);
  std::vector<std::size_t> boundary_vertices;
  for (std::size_t e = 0; e < E; ++e) {
    const auto& fs = edge_faces[e];
    if (fs.size() > 2) shape.manifold = false;
    for (std::size_t k = 1; k < fs.size(); ++k) faces.unite(fs[0], fs[k]);
    if (fs.size() == 1) {
      boundary.unite(edge_ends[e][0], edge_ends[e][1]);
      boundary_vertices.push_back(edge_ends[e][0]);
    }
  }
  std::vector<std::size_t> all_faces(F);
  std::iota(all_faces.begin(), all_faces.end(), std::size_t(0));
  shape.components = faces.classes(all_faces);
  shape.boundary_cycles = boundary.classes(boundary_vertices);

  // The link of each vertex: its edges, joined by the polygons at it, must form one component
  // (with edges of one or two polygons it is then a path or a cycle).
  for (std::size_t v = 0; v < V && shape.manifold; ++v) {
    std::map<std::size_t, std::size_t> local;
    for (const auto& [a, b] : link[v]) {
      local.emplace(a, local.size());
      local.emplace(b, local.size());
    }
    Partition around(local.size());
    for (const auto& [a, b] : link[v]) around.unite(local[a], local[b]);
    std::vector<std::size_t> nodes(local.size());
    std::iota(nodes.begin(), nodes.end(), std::size_t(0));
    if (around.classes(nodes) != 1) shape.manifold = false;
  }
  // A boundary vertex of a manifold has exactly two boundary edges.
  if (shape.manifold) {
    std::vector<int> boundary_degree(V, 0);
    for (std::size_t e = 0; e < E; ++e)
      if (edge_faces[e].size() == 1) {
        ++boundary_degree[edge_ends[e][0]];
        ++boundary_degree[edge_ends[e][1]];
      }
    for (const int d : boundary_degree)
      if (d != 0 && d != 2) shape.manifold = false;
  }
  return shape;
}

//! Per pair p < q, the polygon edges of V_p on B(p, q), as vertex pairs, with the vertices' points.
struct FacetEdges {
  std::vector<std::pair<RvdVertex, RvdVertex>> edges;
  std::vector<std::array<double, 3>> points;
};
using FacetMap = std::map<std::pair<std::size_t, std::size_t>, FacetEdges>;
//! Per Voronoi edge (site triple), the faces of Σ where it crosses Σ, with the crossing points.
using CrossingMap = std::map<std::array<std::size_t, 3>, std::map<std::size_t, std::array<double, 3>>>;

//! The cells: each restricted cell must be a closed disk.  Collects, on the way, the restricted
//! facets' edges and the Voronoi edges' crossings that the next steps check.
std::vector<ClosedBallViolation> check_cells(const RestrictedVoronoiMesh& diagram, const std::vector<Point3>& samples,
                                             ClosedBallResult& result, FacetMap& facets, CrossingMap& crossings) {
  std::vector<ClosedBallViolation> cells;
  for (std::size_t p = 0; p < diagram.cells.size(); ++p) {
    const auto& polygons = diagram.cells[p];
    if (polygons.empty()) continue;
    ++result.cells_checked;
    result.polygons += polygons.size();
    Farthest far{samples[p]};
    for (const RvdPolygon& polygon : polygons) {
      const std::size_t n = polygon.vertices.size();
      for (std::size_t i = 0; i < n; ++i) {
        far.offer(polygon.points[i]);
        const RvdVertex& v = polygon.vertices[i];
        if (v.kind == RvdVertexKind::face_cut) crossings[v.sites].emplace(v.input[0], polygon.points[i]);
        const RvdEdgeSupport& e = polygon.edges[i];
        if (e.on_bisector && p < e.a) {
          FacetEdges& facet = facets[{p, e.a}];
          facet.edges.emplace_back(v, polygon.vertices[(i + 1) % n]);
          facet.points.push_back(polygon.points[i]);
          facet.points.push_back(polygon.points[(i + 1) % n]);
        }
      }
    }
    const CellShape shape = cell_shape(polygons);
    const bool disk = shape.manifold && shape.components == 1 && shape.boundary_cycles == 1 && shape.euler == 1;
    if (disk) continue;
    ClosedBallViolation v;
    v.dimension = 3;
    v.sites = {p};
    v.components = shape.components;
    v.euler_characteristic = shape.euler;
    v.boundary_cycles = shape.boundary_cycles;
    v.defect = !shape.manifold                  ? ClosedBallDefect::cell_not_manifold
               : shape.components > 1          ? ClosedBallDefect::cell_components
               : shape.boundary_cycles == 0    ? ClosedBallDefect::cell_closed
               : shape.boundary_cycles == 2 && shape.euler == 0 ? ClosedBallDefect::cell_annulus
                                                                : ClosedBallDefect::cell_not_disk;
    v.witness = far.point;
    v.witness_distance = far.distance;
    cells.push_back(std::move(v));
  }
  return cells;
}

//! The facets: each restricted facet must be one simple arc.
std::vector<ClosedBallViolation> check_facets(const FacetMap& facets, const std::vector<Point3>& samples) {
  std::vector<ClosedBallViolation> facet_violations;
  for (const auto& [pq, facet] : facets) {
    std::map<RvdVertex, std::size_t> index;
    for (const auto& [a, b] : facet.edges) {
      index.emplace(a, index.size());
      index.emplace(b, index.size());
    }
    Partition parts(index.size());
    std::vector<int> degree(index.size(), 0);
    for (const auto& [a, b] : facet.edges) {
      const std::size_t i = index[a], j = index[b];
      parts.unite(i, j);
      ++degree[i];
      ++degree[j];
    }
    std::vector<std::size_t> nodes(index.size());
    std::iota(nodes.begin(), nodes.end(), std::size_t(0));
    const std::size_t components = parts.classes(nodes);
    const int max_degree = *std::max_element(degree.begin(), degree.end());
    const auto ends = std::count(degree.begin(), degree.end(), 1);
    if (components == 1 && max_degree <= 2 && ends == 2) continue;
    ClosedBallViolation v;
    v.dimension = 2;
    v.sites = {pq.first, pq.second};
    v.components = components;
    v.defect = max_degree > 2      ? ClosedBallDefect::facet_branching
               : components > 1    ? ClosedBallDefect::facet_components
                                   : ClosedBallDefect::facet_closed_loop;
    Farthest far{samples[pq.first]};
    for (const auto& x : facet.points) far.offer(x);
    v.witness = far.point;
    v.witness_distance = far.distance;
    facet_violations.push_back(std::move(v));
  }
  return facet_violations;
}

//! The Voronoi edges: each meets Σ at most once; those that meet it are Del S|Σ's triangles.
std::vector<ClosedBallViolation> check_edges(const CrossingMap& crossings, const std::vector<Point3>& samples,
                                             ClosedBallResult& result) {
  std::vector<ClosedBallViolation> edge_violations;
  for (const auto& [pqr, where] : crossings) {
    result.restricted_delaunay.push_back(pqr);
    if (where.size() <= 1) continue;
    ClosedBallViolation v;
    v.dimension = 1;
    v.sites = {pqr[0], pqr[1], pqr[2]};
    v.defect = ClosedBallDefect::edge_points;
    v.points = where.size();
    v.components = where.size();
    Farthest far{samples[pqr[0]]};
    for (const auto& [face, x] : where) far.offer(x);
    v.witness = far.point;
    v.witness_distance = far.distance;
    edge_violations.push_back(std::move(v));
  }
  return edge_violations;
}

}  // namespace

ClosedBallResult closed_ball_check(const RestrictedVoronoiMesh& diagram, const std::vector<Point3>& samples) {
  const auto start = std::chrono::steady_clock::now();
  ClosedBallResult result;
  result.contacts = diagram.contacts;
  result.sign_tests = diagram.sign_tests;
  result.exact_evaluations = diagram.exact_evaluations;

  FacetMap facets;
  CrossingMap crossings;
  result.violations = check_cells(diagram, samples, result, facets, crossings);
  result.facets_checked = facets.size();
  const std::vector<ClosedBallViolation> facet_violations = check_facets(facets, samples);
  result.edges_checked = crossings.size();
  const std::vector<ClosedBallViolation> edge_violations = check_edges(crossings, samples, result);
  result.violations.insert(result.violations.end(), facet_violations.begin(), facet_violations.end());
  result.violations.insert(result.violations.end(), edge_violations.begin(), edge_violations.end());
  result.status = !result.contacts.empty()    ? ClosedBallStatus::non_generic
                  : !result.violations.empty() ? ClosedBallStatus::violated
                                               : ClosedBallStatus::holds;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

ClosedBallResult closed_ball_check(const std::vector<Point3>& samples, const SurfaceMesh& mesh) {
  const auto start = std::chrono::steady_clock::now();
  const RestrictedVoronoiMesh diagram = restricted_voronoi_mesh(samples, mesh);
  ClosedBallResult result = closed_ball_check(diagram, samples);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

RestrictedDelaunayComparison compare_with_restricted_delaunay(const ClosedBallResult& result,
                                                              const SurfaceMesh& output) {
  if (output.has_garbage())
    throw PreconditionViolation("compare_with_restricted_delaunay: the mesh has removed elements");
  RestrictedDelaunayComparison c;
  std::vector<std::array<std::size_t, 3>> triangles;
  for (const auto f : output.faces()) {
    std::vector<std::size_t> ids;
    for (const auto v : output.vertices_around_face(output.halfedge(f))) ids.push_back(std::size_t(v));
    if (ids.size() != 3) {
      ++c.only_mesh;
      continue;
    }
    std::sort(ids.begin(), ids.end());
    triangles.push_back({ids[0], ids[1], ids[2]});
  }
  std::sort(triangles.begin(), triangles.end());
  std::vector<std::array<std::size_t, 3>> common;
  std::set_intersection(triangles.begin(), triangles.end(), result.restricted_delaunay.begin(),
                        result.restricted_delaunay.end(), std::back_inserter(common));
  c.only_mesh += triangles.size() - common.size();
  c.only_restricted_delaunay = result.restricted_delaunay.size() - common.size();
  c.equal = c.only_mesh == 0 && c.only_restricted_delaunay == 0;
  return c;
}

nlohmann::json closed_ball_json(const ClosedBallResult& result, std::size_t listed) {
  const auto text = [](const auto& value) {
    std::ostringstream out;
    out << value;
    return out.str();
  };
  nlohmann::json by_defect = nlohmann::json::object(), first = nlohmann::json::array();
  for (const ClosedBallViolation& v : result.violations) {
    by_defect[text(v.defect)] = by_defect.value(text(v.defect), 0) + 1;
    if (first.size() >= listed) continue;
    nlohmann::json entry = {{"kind", text(v.defect)},
                            {"sites", v.sites},
                            {"witness", v.witness},
                            {"witness_distance", v.witness_distance}};
    if (v.dimension == 3) {
      entry["components"] = v.components;
      entry["euler_characteristic"] = v.euler_characteristic;
      entry["boundary_cycles"] = v.boundary_cycles;
    } else if (v.dimension == 2) {
      entry["components"] = v.components;
    } else {
      entry["points"] = v.points;
    }
    first.push_back(std::move(entry));
  }
  nlohmann::json by_contact = nlohmann::json::object(), contacts = nlohmann::json::array();
  for (const RvdContact& c : result.contacts) {
    by_contact[text(c.kind)] = by_contact.value(text(c.kind), 0) + 1;
    if (contacts.size() < listed)
      contacts.push_back({{"kind", text(c.kind)}, {"sites", c.sites}, {"location", c.location}});
  }
  return {{"status", text(result.status)},
          {"cells", result.cells_checked},
          {"facets", result.facets_checked},
          {"edges", result.edges_checked},
          {"polygons", result.polygons},
          {"violations", {{"count", result.violations.size()}, {"by_kind", by_defect}, {"first", first}}},
          {"non_generic", {{"count", result.contacts.size()}, {"by_kind", by_contact}, {"first", contacts}}},
          {"restricted_delaunay_triangles", result.restricted_delaunay.size()},
          {"sign_tests", result.sign_tests},
          {"exact_evaluations", result.exact_evaluations},
          {"seconds", result.seconds}};
}

}  // namespace delmesh
