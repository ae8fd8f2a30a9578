// The certificate of a finished mesh (certificate.h): Del S of the mesh's vertices, the topology
// rows of the check registry (the five checks of §5.3, and any registered topology check) on
// every Voronoi face of a fresh RestrictedDelaunay, and Tri S|Σ against the mesh's triangles.
//
// Steps:
//  1. validate Σ (smooth, strictly inside B) and read the soup into S (referenced points only);
//  2. on every Delaunay triangle the triangle rows (VorEdge); the triangle's record also says
//     whether it is in Tri S|Σ, and its unresolved regions are unsettled findings (vor_edge.h
//     leaves them to the caller);
//  3. on every Delaunay edge the edge rows (FacetContact, then FacetCycle where FacetContact was
//     clean); the facet's geometry is released after them;
//  4. on every vertex the vertex rows (TopoDisk, then Silhouette with the facet shortcut only
//     where everything so far was clean on every face of the cell);
//  5. Tri S|Σ against the soup.
// A witness counts as proved unless it comes from an undecided region, or its row reads the
// restricted status (VorEdge, TopoDisk) and a triangle containing its face has an unresolved
// record (the crossings or the restricted star may then be wrong).
#include "meshing/verify/certificate.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>

#include "common/errors.h"
#include "common/run_limits.h"
#include "meshing/checks/check_registry.h"
#include "meshing/inputs/implicit_oracle.h"
#include "meshing/inputs/input_validation.h"
#include "meshing/voronoi/delaunay.h"
#include "meshing/voronoi/restricted_delaunay.h"

namespace delmesh {

namespace {

using Clock = std::chrono::steady_clock;

template <class T>
std::string text_of(const T& value) {
  std::ostringstream s;
  s << value;
  return s.str();
}

//! Collects the findings of the checks and the per-vertex "some face of V_p is not clean" marks.
class Findings {
 public:
  Findings(Certificate& c, const std::vector<std::size_t>& soup_index, std::size_t samples)
      : c_(c), soup_index_(soup_index), dirty_(samples, false) {}

  //! Records `result` of a check on the face dual to `simplex` (Delaunay ids); `proved` says
  //! whether its certified witnesses prove the check's condition fails (file comment).
  void add(const std::vector<VertexId>& simplex, const CheckResult& result, bool proved = true) {
    if (result.clean()) return;
    std::vector<std::size_t> face;
    for (VertexId v : simplex) {
      face.push_back(soup_index_[v]);
      dirty_[v] = true;
    }
    for (const auto& w : result.witnesses) c_.witnesses.push_back({w, proved && !w.from_undecided, face});
    for (const auto& u : result.unsettled) c_.unsettled.push_back({u, face});
  }
  bool dirty(VertexId v) const { return dirty_[v]; }

 private:
  Certificate& c_;
  const std::vector<std::size_t>& soup_index_;
  std::vector<bool> dirty_;
};

// Step 1 for the soup: which points its triangles refer to; throws InvalidInput for an index out
// of range, a triangle repeating an index, or a referenced point with a non-finite coordinate.
std::vector<bool> referenced_points(const std::vector<Point3>& points,
                                    const std::vector<std::array<std::size_t, 3>>& triangles) {
  if (triangles.empty()) throw InvalidInput("the mesh has no triangle to certify");
  std::vector<bool> referenced(points.size(), false);
  for (const auto& t : triangles) {
    for (std::size_t i : t)
      if (i >= points.size())
        throw InvalidInput("a triangle refers to vertex " + std::to_string(i) + " of " + std::to_string(points.size()));
    if (t[0] == t[1] || t[0] == t[2] || t[1] == t[2]) throw InvalidInput("a triangle repeats a vertex index");
    for (std::size_t i : t) referenced[i] = true;
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Point3& p = points[i];
    if (referenced[i] && !(std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z())))
      throw InvalidInput("vertex " + std::to_string(i) + " has a non-finite coordinate");
  }
  return referenced;
}

// Step 1 for Σ: validates it and builds its oracle into `built`; false, with the certificate
// marked stopped, when the command's limits stop the compilation of E's systems
// (RunLimits::current()): the certificate then ends before its first face, with nothing decided.
bool build_oracle(const Surface& surface, const Box3& box, std::optional<ImplicitOracle>& built, Certificate& c) {
  try {
    c.seconds_validation = validate_input(surface, box).seconds;
    built.emplace(surface, box, SolverBackend::subdivision);
  } catch (const RunStopped& stopped) {
    c.interrupted = stopped.reason() == StopReason::interrupted;
    c.time_limited = stopped.reason() == StopReason::time_limit;
    return false;
  }
  return true;
}

// S: the referenced points inserted into `del`, each soup index's Delaunay id in `id_of` (a
// coincident point gets the earlier vertex's), and each Delaunay id's first soup index.
std::vector<std::size_t> insert_samples(const std::vector<Point3>& points, const std::vector<bool>& referenced,
                                        Delaunay& del, std::vector<VertexId>& id_of, Certificate& c) {
  std::vector<std::size_t> soup_index;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!referenced[i]) {
      ++c.unreferenced_vertices;
      continue;
    }
    const Vec3 p{points[i].x(), points[i].y(), points[i].z()};
    if (const auto id = del.insert(p, false)) {
      id_of[i] = *id;
      soup_index.resize(*id + 1);
      soup_index[*id] = i;
    } else {
      id_of[i] = del.nearest(p).first;  // the earlier vertex at the same point
      ++c.coincident_vertices;
    }
  }
  return soup_index;
}

// The largest first-order estimate |E| / |∇E| of a sample's distance to Σ.
double max_vertex_distance_estimate(const Delaunay& del, ImplicitOracle& oracle) {
  double largest = 0;
  for (VertexId v : del.vertices()) {
    const Vec3& p = del.point(v);
    const Vec3 g = oracle.gradient(p);
    const double gn = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    const double e = std::abs(oracle.E(p));
    const double estimate = gn > 0 ? e / gn : (e == 0 ? 0 : std::numeric_limits<double>::infinity());
    largest = std::max(largest, estimate);
  }
  return largest;
}

// Steps 2-4: the topology rows of the check registry on every Voronoi face of a fresh
// RestrictedDelaunay of Del S, their findings recorded in the certificate, until the run's
// limits stop them.
class FaceCertifier {
 public:
  FaceCertifier(Certificate& c, const Delaunay& del, ImplicitOracle& oracle,
                const std::vector<std::size_t>& soup_index, const CertificateOptions& options)
      : c_(c), del_(del), restricted_(del, oracle, options.seed),
        findings_(c, soup_index, static_cast<std::size_t>(del.size())), limits_(options.deadline, options.interrupt),
        unresolved_at_(del.size(), false) {
    for (const CheckInfo& row : check_registry())
      if (row.phase == CheckPhase::topology) rows_of_[static_cast<int>(row.face)].push_back(&row);
    c.seconds_per_check.assign(check_kind_count(), 0.0);
  }

  // 2. The Voronoi edges; Tri S|Σ from the same records.
  void check_voronoi_edges() {
    const std::vector<TriangleKey> all_triangles = del_.triangles();
    for (const auto& t : all_triangles) {
      if (stopped()) break;
      check_face(FaceKind::triangle, t, [&] { return !restricted_.voronoi_edge_record(t).unresolved().empty(); });
      const VoronoiEdgeRecord& record = restricted_.voronoi_edge_record(t);
      CheckResult unresolved;
      for (const auto& x : record.unresolved())
        unresolved.unsettled.push_back({CheckKind::vor_edge, UnsettledReason::unresolved_crossing, x});
      if (!record.unresolved().empty()) {
        for (VertexId v : t) unresolved_at_[v] = true;
        for (const auto& e : {make_edge_key(t[0], t[1]), make_edge_key(t[0], t[2]), make_edge_key(t[1], t[2])})
          unresolved_edges_.insert(e);
      }
      findings_.add({t[0], t[1], t[2]}, unresolved);
      if (record.restricted) restricted_set_.insert(t);
      ++c_.voronoi_edges;
    }
  }

  // 3. The facets, each built once for its rows and released after them.
  void check_facets(const std::vector<VertexId>& vertices) {
    for (VertexId p : vertices) {
      for (VertexId q : del_.neighbours(p)) {
        if (q < p) continue;
        if (stopped()) break;
        const EdgeKey e{p, q};
        check_face(FaceKind::edge, {p, q, -1}, [&] { return unresolved_edges_.count(e) != 0; });
        restricted_.release_facet(e);
        ++c_.voronoi_facets;
      }
    }
  }

  // 4. The cells.
  void check_cells(const std::vector<VertexId>& vertices) {
    for (VertexId p : vertices) {
      if (stopped()) break;
      check_face(FaceKind::vertex, {p, -1, -1}, [&] { return static_cast<bool>(unresolved_at_[p]); });
      ++c_.voronoi_cells;
    }
  }

  // Tri S|Σ as far as step 2 got.
  const std::set<TriangleKey>& restricted_triangles() const { return restricted_set_; }

 private:
  // Whether the run's limits stopped the certificate (marked in it the first time).
  bool stopped() {
    if (!c_.interrupted && !c_.time_limited) {
      const StopReason reason = limits_.expired();
      c_.interrupted = reason == StopReason::interrupted;
      c_.time_limited = reason == StopReason::time_limit;
    }
    return c_.interrupted || c_.time_limited;
  }

  // Runs the rows of `kind` on one face, in the registry's order (a row marked
  // after_clean_predecessors only where the earlier ones were clean), and records the findings;
  // `unresolved` says whether a triangle containing the face has an unresolved record.  The
  // results are recorded after all rows ran, so a triangle's record can be read in between.
  template <class Unresolved>
  void check_face(FaceKind kind, const DelaunayFace& face, Unresolved&& unresolved) {
    std::vector<VertexId> simplex;
    for (VertexId v : face)
      if (v >= 0) simplex.push_back(v);
    std::vector<std::pair<const CheckInfo*, CheckResult>> results;
    bool clean = true;
    for (const CheckInfo* row : rows_of_[static_cast<int>(kind)]) {
      if (row->after_clean_predecessors && !clean) continue;
      CheckContext context{restricted_, row->kind, 0, std::nullopt, std::nullopt, nullptr, true};
      // A cell's faces are clean if no check so far found anything on a face of V_p.
      if (kind == FaceKind::vertex) context.cell_faces_clean = !findings_.dirty(face[0]) && clean;
      const auto t0 = Clock::now();
      CheckResult result = row->check(context, face);
      c_.seconds_per_check[static_cast<int>(row->kind)] += std::chrono::duration<double>(Clock::now() - t0).count();
      clean = clean && result.clean();
      results.emplace_back(row, std::move(result));
    }
    const bool near_unresolved = unresolved();
    for (const auto& [row, result] : results)
      findings_.add(simplex, result, !(row->reads_restricted_status && near_unresolved));
  }

  Certificate& c_;
  const Delaunay& del_;
  RestrictedDelaunay restricted_;
  Findings findings_;
  const RunLimits limits_;
  // The topology rows of the check registry, by the kind of face they examine.
  std::array<std::vector<const CheckInfo*>, 3> rows_of_;
  std::set<TriangleKey> restricted_set_;
  std::vector<bool> unresolved_at_;      // some triangle at v has an unresolved record
  std::set<EdgeKey> unresolved_edges_;  // some triangle at e has an unresolved record
};

// 5. Tri S|Σ against the soup's triangles (`id_of`: their vertices' Delaunay ids).
void compare_with_soup(const std::vector<std::array<std::size_t, 3>>& triangles, const std::vector<VertexId>& id_of,
                       const std::set<TriangleKey>& restricted_set, Certificate& c) {
  c.restricted_triangles = restricted_set.size();
  std::set<TriangleKey> mesh_set;
  for (const auto& t : triangles) {
    const VertexId a = id_of[t[0]], b = id_of[t[1]], d = id_of[t[2]];
    if (a == b || a == d || b == d) {
      ++c.mesh_not_restricted;  // coincident points made it degenerate
      continue;
    }
    const TriangleKey key = make_triangle_key(a, b, d);
    if (!mesh_set.insert(key).second) {
      ++c.repeated_mesh_triangles;
      continue;
    }
    if (!restricted_set.count(key)) ++c.mesh_not_restricted;
  }
  for (const auto& t : restricted_set)
    if (!mesh_set.count(t)) ++c.restricted_not_in_mesh;
  c.restricted_matches_mesh = !c.interrupted && !c.time_limited && c.coincident_vertices == 0 &&
                              c.repeated_mesh_triangles == 0 &&
                              c.mesh_not_restricted == 0 && c.restricted_not_in_mesh == 0;
}

// The verdict: violated by a proved witness, undecided when stopped or with findings left,
// certified otherwise.
CertificateStatus status_of(const Certificate& c) {
  const bool proved_witness =
      std::any_of(c.witnesses.begin(), c.witnesses.end(), [](const CertificateWitness& w) { return w.proved; });
  if (proved_witness) return CertificateStatus::violated;
  if (c.interrupted || c.time_limited || !c.witnesses.empty() || !c.unsettled.empty())
    return CertificateStatus::undecided;
  return CertificateStatus::certified;
}

}  // namespace

Certificate certify_mesh(const std::vector<Point3>& points, const std::vector<std::array<std::size_t, 3>>& triangles,
                         const Surface& surface, const Box3& box, const CertificateOptions& options) {
  const auto start = Clock::now();
  Certificate c;
  c.seed = options.seed;
  c.mesh_triangles = triangles.size();
  auto seconds_since_start = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };

  // 1. The soup and Σ.
  const std::vector<bool> referenced = referenced_points(points, triangles);
  std::optional<ImplicitOracle> built;
  if (!build_oracle(surface, box, built, c)) {
    c.seconds = seconds_since_start();
    return c;
  }
  ImplicitOracle& oracle = *built;
  oracle.set_run_controls(options.seed, options.deadline);
  Delaunay del;
  std::vector<VertexId> id_of(points.size(), -1);
  const std::vector<std::size_t> soup_index = insert_samples(points, referenced, del, id_of, c);
  c.samples = del.size();
  c.max_vertex_distance_estimate = max_vertex_distance_estimate(del, oracle);

  // 2-4. The Voronoi edges, facets and cells.
  FaceCertifier faces(c, del, oracle, soup_index, options);
  faces.check_voronoi_edges();
  const std::vector<VertexId> vertices = del.vertices();
  faces.check_facets(vertices);
  faces.check_cells(vertices);

  // 5. Tri S|Σ against the soup, and the verdict.
  compare_with_soup(triangles, id_of, faces.restricted_triangles(), c);
  c.status = status_of(c);
  c.solver = oracle.statistics_json();
  c.seconds = seconds_since_start();
  return c;
}

nlohmann::json to_json(const Certificate& c) {
  nlohmann::json j;
  j["status"] = text_of(c.status);
  j["restricted_matches_mesh"] = c.restricted_matches_mesh;
  j["faces_checked"] = c.faces_checked();
  j["voronoi_faces"] = {{"edges", c.voronoi_edges}, {"facets", c.voronoi_facets}, {"cells", c.voronoi_cells}};
  j["interrupted"] = c.interrupted;
  j["time_limited"] = c.time_limited;
  j["samples"] = c.samples;
  j["unreferenced_vertices"] = c.unreferenced_vertices;
  j["coincident_vertices"] = c.coincident_vertices;
  j["restricted_triangles"] = c.restricted_triangles;
  j["mesh_triangles"] = c.mesh_triangles;
  j["restricted_not_in_mesh"] = c.restricted_not_in_mesh;
  j["mesh_not_restricted"] = c.mesh_not_restricted;
  j["repeated_mesh_triangles"] = c.repeated_mesh_triangles;

  nlohmann::json by_check = nlohmann::json::object(), listed = nlohmann::json::array();
  std::size_t proved = 0;
  for (const auto& w : c.witnesses) {
    const std::string name = text_of(w.witness.kind);
    by_check[name] = by_check.value(name, 0) + 1;
    if (w.proved) ++proved;
  }
  // Proved witnesses first, each group in the order found.
  for (bool want : {true, false})
    for (const auto& w : c.witnesses)
      if (w.proved == want && listed.size() < certificate_findings_listed)
        listed.push_back(
            {{"check", text_of(w.witness.kind)}, {"face", w.face}, {"point", w.witness.point}, {"proved", w.proved}});
  j["witnesses"] = {{"count", c.witnesses.size()}, {"proved", proved}, {"by_check", by_check}, {"listed", listed}};

  nlohmann::json by_reason = nlohmann::json::object(), unsettled = nlohmann::json::array();
  for (const auto& u : c.unsettled) {
    const std::string reason = text_of(u.what.reason);
    by_reason[reason] = by_reason.value(reason, 0) + 1;
    if (unsettled.size() < certificate_findings_listed)
      unsettled.push_back({{"check", text_of(u.what.check)}, {"reason", reason}, {"face", u.face},
                           {"location", u.what.location}});
  }
  j["unsettled"] = {{"count", c.unsettled.size()}, {"by_reason", by_reason}, {"listed", unsettled}};

  j["max_vertex_distance_estimate"] = c.max_vertex_distance_estimate;
  j["seed"] = c.seed;
  j["seconds"] = c.seconds;
  j["seconds_validation"] = c.seconds_validation;
  nlohmann::json per_check = nlohmann::json::object();
  for (const CheckInfo& row : check_registry()) {
    const auto k = static_cast<std::size_t>(row.kind);
    if (row.phase == CheckPhase::topology) per_check[row.name] = k < c.seconds_per_check.size() ? c.seconds_per_check[k] : 0.0;
  }
  j["seconds_per_check"] = per_check;
  j["solver"] = c.solver;
  return j;
}

}  // namespace delmesh
