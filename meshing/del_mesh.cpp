// DelMesh (§6.2): the entry point of the mesher.  See del_mesh.h.
//
// Choices (beyond the paper):
// - Quality and Smooth examine the triangles whose dual Voronoi edges changed (a local work list
//   fed by Topology::take_changed_triangles), Quality's list before Smooth's, so the order of
//   steps 2 and 3 holds; after every insertion Topology runs again on its local queues.
// - λ ≥ 1/6 leaves β(λ) undefined: Smooth is then skipped (statistics: "smooth_enabled": false).
// - Output vertices are sorted by insertion id and triangles by their sorted ids, so a given
//   surface, box and seed give the same mesh byte for byte.
#include "meshing/del_mesh.h"

#include <algorithm>
#include <chrono>
#include <map>
#include <set>
#include <sstream>

#include "common/errors.h"
#include "meshing/detail/vec3.h"
#include "meshing/input_validation.h"
#include "meshing/mesh_checker.h"
#include "meshing/quality.h"
#include "meshing/sample_topology.h"
#include "meshing/smooth.h"
#include "meshing/surface_oracle.h"
#include "meshing/theorem_bounds.h"
#include "meshing/topology.h"

namespace delmesh {

using namespace detail;

std::ostream& operator<<(std::ostream& out, MeshPhase phase) {
  return out << (phase == MeshPhase::topology ? "topology" : "all");
}
std::ostream& operator<<(std::ostream& out, SolverBackend backend) {
  return out << (backend == SolverBackend::subdivision ? "subdivision" : "homotopy");
}
std::ostream& operator<<(std::ostream& out, MeshStatus status) {
  switch (status) {
    case MeshStatus::complete: return out << "complete";
    case MeshStatus::point_limit: return out << "point_limit";
    case MeshStatus::time_limit: return out << "time_limit";
  }
  return out << "unknown";
}

namespace {

MeshStatus to_mesh_status(TopologyStatus s) {
  switch (s) {
    case TopologyStatus::complete: return MeshStatus::complete;
    case TopologyStatus::point_limit: return MeshStatus::point_limit;
    case TopologyStatus::time_limit: return MeshStatus::time_limit;
  }
  return MeshStatus::complete;
}

// Steps 2–3 of DelMesh with local work lists.
TopologyStatus refine_geometry(Topology& topology, const DelMeshOptions& options, double smooth_threshold,
                               bool smooth_enabled) {
  auto& restricted = topology.restricted();
  std::set<TriangleKey> quality_list, smooth_list;
  auto absorb = [&] {
    for (const auto& t : topology.take_changed_triangles()) {
      quality_list.insert(t);
      smooth_list.insert(t);
    }
  };
  // Initially every restricted triangle is examined.
  topology.take_changed_triangles();
  for (const auto& t : restricted.triangles()) {
    quality_list.insert(t);
    smooth_list.insert(t);
  }
  while (true) {
    if (auto s = topology.limit_reached("geometry")) return *s;
    absorb();
    std::optional<Witness> w;
    if (!quality_list.empty()) {
      const auto t = *quality_list.begin();
      quality_list.erase(quality_list.begin());
      if (!topology.delaunay().is_triangle(t)) continue;
      const auto start = std::chrono::steady_clock::now();
      w = quality_witness(restricted, t, options.lambda);
      if (!w && options.size_bound) w = size_witness(restricted, t, *options.size_bound);
      topology.add_seconds(CheckKind::quality,
                           std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    } else if (!smooth_list.empty()) {
      const auto t = *smooth_list.begin();
      smooth_list.erase(smooth_list.begin());
      if (!smooth_enabled || !topology.delaunay().is_triangle(t)) continue;
      if (!restricted.edge_record(t).restricted) continue;
      const auto start = std::chrono::steady_clock::now();
      for (const auto& e : {make_edge_key(t[0], t[1]), make_edge_key(t[0], t[2]), make_edge_key(t[1], t[2])}) {
        w = smooth_witness(restricted, e, smooth_threshold);
        if (w) break;
      }
      // The witness may lie on the dual edge of the other triangle at the rough edge, leaving t
      // itself unchanged: t goes back on the list so that its remaining edges are examined too.
      if (w) smooth_list.insert(t);
      topology.add_seconds(CheckKind::smooth,
                           std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    } else {
      return TopologyStatus::complete;
    }
    if (!w) continue;
    if (!topology.insert(*w)) continue;
    if (const auto s = topology.run(); s != TopologyStatus::complete) return s;
  }
}

// Tri S|Σ as an outward-oriented Surface_mesh with vertices sorted by id.
SurfaceMesh output_mesh(Topology& topology, std::size_t& flipped_inconsistent, std::size_t& not_added) {
  auto& restricted = topology.restricted();
  const auto& del = topology.delaunay();
  const auto triangles = restricted.triangles();
  std::set<VertexId> used;
  for (const auto& t : triangles) used.insert(t.begin(), t.end());
  SurfaceMesh mesh;
  std::map<VertexId, SurfaceMesh::Vertex_index> index;
  for (VertexId v : used) {
    const auto& p = del.point(v);
    index[v] = mesh.add_vertex(Point3(p[0], p[1], p[2]));
  }
  std::map<std::pair<VertexId, VertexId>, int> directed;
  std::vector<std::array<VertexId, 3>> oriented;
  for (const auto& t : triangles) {
    const Vec3 &p = del.point(t[0]), &q = del.point(t[1]), &r = del.point(t[2]);
    const Vec3 n = cross(q - p, r - p);
    const Vec3 g = topology.oracle().gradient(restricted.edge_record(t).dual_point);
    std::array<VertexId, 3> f = dot(n, g) >= 0 ? std::array<VertexId, 3>{t[0], t[1], t[2]}
                                                : std::array<VertexId, 3>{t[0], t[2], t[1]};
    oriented.push_back(f);
    for (int k = 0; k < 3; ++k) ++directed[{f[k], f[(k + 1) % 3]}];
  }
  flipped_inconsistent = 0;
  for (const auto& [e, count] : directed)
    if (count > 1) flipped_inconsistent += count - 1;
  not_added = 0;
  for (const auto& f : oriented) {
    const auto face = mesh.add_face(index[f[0]], index[f[1]], index[f[2]]);
    if (face == SurfaceMesh::null_face()) ++not_added;
  }
  return mesh;
}

}  // namespace

DelMeshResult del_mesh(const Surface& surface, const Box3& box, const DelMeshOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (!(options.lambda > 0) || !(options.lambda < 1.0 / 3.0))
    throw InvalidInput("lambda must satisfy 0 < lambda < 1/3 (Theorem 6.1 covers lambda <= 0.06)");
  if (options.size_bound && !(*options.size_bound > 0)) throw InvalidInput("the size bound must be positive");
  if (options.max_points < 1) throw InvalidInput("max_points must be at least 1");
  if (options.time_limit_seconds < 0) throw InvalidInput("the time limit must be non-negative");
  for (int k = 0; k < 3; ++k)
    if (!(box.lo[k] < box.hi[k])) throw InvalidInput("the box is empty");

  const ValidationReport validation = validate_input(surface, box);
  SurfaceOracle oracle(surface, box, options.solver);
  TopologyLimits limits;
  limits.max_points = options.max_points;
  if (options.time_limit_seconds > 0)
    limits.deadline = start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                  std::chrono::duration<double>(options.time_limit_seconds));
  limits.progress = options.progress;
  Topology topology(oracle, options.seed, limits);

  SeedReport seeds;
  TopologyStatus status = sample_topology(topology, seeds);
  const std::size_t topology_vertices = topology.delaunay().size();
  const double topology_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const bool smooth_enabled = options.lambda < 1.0 / 6.0;
  const double smooth_threshold = smooth_enabled ? 2 * beta(options.lambda) : 0;
  if (status == TopologyStatus::complete && options.phase == MeshPhase::all)
    status = refine_geometry(topology, options, smooth_threshold, smooth_enabled);

  DelMeshResult result;
  result.status = to_mesh_status(status);
  std::size_t inconsistent = 0, not_added = 0;
  result.mesh = output_mesh(topology, inconsistent, not_added);

  const MeshReport report = check_mesh(result.mesh);
  auto& j = result.statistics;
  {
    std::ostringstream s;
    s << result.status;
    j["status"] = s.str();
  }
  j["lambda"] = options.lambda;
  j["theorem_applies"] = options.lambda <= 0.06;
  {
    std::ostringstream s;
    s << options.phase;
    j["phase"] = s.str();
  }
  j["vertices"] = report.vertices;
  j["triangles"] = report.triangles;
  j["components"] = report.components;
  j["euler_characteristic"] = report.euler_characteristic;
  j["genus_per_component"] = report.genus_per_component;
  j["closed_manifold"] = report.closed && report.manifold;
  j["orientable"] = report.orientable;
  j["orientation_inconsistent_edges"] = inconsistent;
  j["faces_not_added"] = not_added;
  j["min_angle_deg"] = report.min_angle_deg;
  j["max_radius_edge_ratio"] = report.max_radius_edge_ratio;
  j["max_roughness_rad"] = report.max_roughness_rad;
  if (options.lambda < 1.0 / 6.0) {
    const auto b = theorem_bounds(options.lambda);
    j["bounds"] = {{"min_angle_deg", b.min_angle_deg},
                   {"max_radius_edge_ratio", b.max_radius_edge_ratio},
                   {"max_roughness_rad", b.max_roughness_rad}};
  } else {
    j["bounds"] = nlohmann::json::object();
  }
  j["smooth_enabled"] = smooth_enabled;
  j["insertions"] = topology.insertions_json();
  j["solver"] = oracle.statistics_json();
  j["solver"]["unresolved_edge_regions"] = topology.restricted().unresolved();
  nlohmann::json per_check = nlohmann::json::object();
  for (CheckKind k : {CheckKind::vor_edge, CheckKind::facet_contact, CheckKind::topo_disk, CheckKind::facet_cycle,
                      CheckKind::silhouette, CheckKind::quality, CheckKind::smooth}) {
    std::ostringstream name;
    name << k;
    per_check[name.str()] = topology.seconds(k);
  }
  j["seconds_per_check"] = per_check;
  j["height_direction"] = seeds.height_direction;
  j["height_direction_attempts"] = seeds.attempts;
  j["seed_undecided"] = seeds.undecided;
  j["seed"] = options.seed;
  j["topology_phase"] = {{"vertices", topology_vertices}, {"seconds", topology_seconds}};
  j["seconds_validation"] = validation.seconds;
  j["points"] = topology.delaunay().size();
  j["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace delmesh
