// DelMesh (§6.2): the entry point of the mesher.  See del_mesh.h.
//
// Choices (beyond the paper):
// - SampleTopology, then the same refinement driver with Quality and Smooth turned on
//   (meshing/driver/refinement.h): its table runs the topology checks before Quality, Quality before
//   Smooth, and every witness sends it back to step (a).
// - λ ≥ 1/6 leaves β(λ) undefined: Smooth is then skipped (statistics: "smooth_enabled": false).
// - Output vertices are sorted by insertion id and triangles by their sorted ids, so a given
//   surface, box and seed give the same mesh byte for byte.
#include "meshing/driver/del_mesh.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <sstream>
#include <variant>

#include "common/errors.h"
#include "common/tolerances.h"
#include "meshing/core/detail/key_order.h"
#include "meshing/core/detail/vec3.h"
#include "meshing/core/mesh_checker.h"
#include "meshing/core/theorem_bounds.h"
#include "meshing/driver/closed_ball_refinement.h"
#include "meshing/driver/detail/run_knobs.h"
#include "meshing/driver/refinement.h"
#include "meshing/driver/sample_topology.h"
#include "meshing/driver/scaled_run.h"
#include "meshing/inputs/make_oracle.h"
#include "meshing/inputs/mesh_oracle.h"
#include "meshing/inputs/sharp_features.h"
#include "meshing/verify/gradient_flow_certificate.h"

namespace delmesh {

using namespace detail;

namespace {

// Tri S|Σ as an outward-oriented Surface_mesh with vertices sorted by id.
SurfaceMesh output_mesh(Refinement& refinement, std::size_t& flipped_inconsistent, std::size_t& not_added) {
  auto& restricted = refinement.restricted();
  const auto& del = refinement.delaunay();
  const auto triangles = restricted.triangles();
  std::vector<VertexId> used;
  used.reserve(3 * triangles.size());
  for (const auto& t : triangles) used.insert(used.end(), t.begin(), t.end());
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  SurfaceMesh mesh;
  mesh.reserve(used.size(), 3 * triangles.size() / 2, triangles.size());
  std::vector<SurfaceMesh::Vertex_index> index(used.empty() ? 0 : static_cast<std::size_t>(used.back()) + 1);
  for (VertexId v : used) {
    const auto& p = del.point(v);
    index[v] = mesh.add_vertex(Point3(p[0], p[1], p[2]));
  }
  // Each triangle turned so that its normal agrees with ∇E at its dual point; an edge that two
  // triangles use in the same direction is counted (as pair_word()s, sorted, runs of equals).
  std::vector<std::uint64_t> directed;
  directed.reserve(3 * triangles.size());
  std::vector<std::array<VertexId, 3>> oriented;
  oriented.reserve(triangles.size());
  for (const auto& t : triangles) {
    const Vec3 &p = del.point(t[0]), &q = del.point(t[1]), &r = del.point(t[2]);
    const Vec3 n = cross(q - p, r - p);
    const Vec3 g = refinement.oracle().gradient(restricted.voronoi_edge_record(t).dual_point());
    std::array<VertexId, 3> f = dot(n, g) >= 0 ? std::array<VertexId, 3>{t[0], t[1], t[2]}
                                                : std::array<VertexId, 3>{t[0], t[2], t[1]};
    oriented.push_back(f);
    for (int k = 0; k < 3; ++k) directed.push_back(pair_word(f[k], f[(k + 1) % 3]));
  }
  std::sort(directed.begin(), directed.end());
  flipped_inconsistent = 0;
  for (std::size_t i = 1; i < directed.size(); ++i)
    if (directed[i] == directed[i - 1]) ++flipped_inconsistent;
  not_added = 0;
  std::vector<std::array<VertexId, 3>> added;
  added.reserve(oriented.size());
  for (const auto& f : oriented) {
    const auto face = mesh.add_face(index[f[0]], index[f[1]], index[f[2]]);
    if (face == SurfaceMesh::null_face()) {
      ++not_added;
    } else {
      added.push_back(f);
    }
  }
  if (not_added == 0) return mesh;
  // A vertex whose every triangle was refused would stay in the mesh without a face, and the
  // statistics (check_mesh) count the vertices of faces only: the mesh is built again from the
  // vertices of the added faces, in the same order, with the same faces (add_face depends on the
  // faces added before only, so each one is accepted again).
  SurfaceMesh kept;
  kept.reserve(used.size(), 3 * added.size() / 2, added.size());
  std::vector<SurfaceMesh::Vertex_index> kept_index(index.size());
  for (VertexId v : used)
    if (!mesh.is_isolated(index[v])) kept_index[v] = kept.add_vertex(mesh.point(index[v]));
  for (const auto& f : added) kept.add_face(kept_index[f[0]], kept_index[f[1]], kept_index[f[2]]);
  return kept;
}

// At most this many unsettled items are listed one by one in the statistics (all are counted).
constexpr std::size_t unsettled_listed_max = 1000;

// What the run could not settle on the final Vor S and Tri S|Σ, as statistics; `defects` are
// the output's own (not a closed, consistently oriented 2-manifold).
nlohmann::json unsettled_json(const std::vector<Unsettled>& unsettled, const std::vector<std::string>& defects) {
  nlohmann::json by_reason = nlohmann::json::object(), listed = nlohmann::json::array();
  for (const auto& u : unsettled) {
    std::ostringstream check, reason;
    check << u.check;
    reason << u.reason;
    by_reason[reason.str()] = by_reason.value(reason.str(), 0) + 1;
    if (listed.size() < unsettled_listed_max)
      listed.push_back({{"check", check.str()}, {"reason", reason.str()}, {"location", u.location}});
  }
  return {{"count", unsettled.size()}, {"by_reason", by_reason}, {"regions", listed}, {"output_defects", defects}};
}

void check_options(const Box3& box, const DelMeshOptions& options) {
  if (const auto violation = options.validate())
    throw InvalidInput(std::string(enum_name(violation->option)) + " must " + violation->requirement);
  for (int k = 0; k < 3; ++k)
    if (!(box.lo[k] < box.hi[k])) throw InvalidInput("the box is empty");
}

// The refinement driver's limits from the options; the time limit counts from `start`.
RefinementLimits refinement_limits(const DelMeshOptions& options, std::chrono::steady_clock::time_point start) {
  RefinementLimits limits;
  limits.min_spacing = options.min_spacing;
  limits.max_points = options.max_points;
  limits.deadline = deadline_of(options, start);
  limits.progress = options.progress;
  limits.start = start;
  limits.interrupt = options.interrupt;
  return limits;
}

// What the statistics keep of the topology phase, read when SampleTopology has ended.
struct TopologyPhase {
  std::size_t vertices = 0;
  double seconds = 0;
  nlohmann::json insertions, floor;
};

// The output's defects (statistics names): not a closed 2-manifold, faces Surface_mesh refused,
// edges oriented the same way by both their triangles.
std::vector<std::string> output_defects(const MeshReport& report, std::size_t inconsistent, std::size_t not_added) {
  std::vector<std::string> defects;
  if (!(report.closed && report.manifold)) defects.push_back("not_closed_manifold");
  if (not_added > 0) defects.push_back("faces_not_added");
  if (inconsistent > 0) defects.push_back("orientation_inconsistent_edges");
  return defects;
}

template <class T>
std::string text_of(const T& value) {
  std::ostringstream s;
  s << value;
  return s.str();
}

// The statistics of the output mesh (its topology and quality, as check_mesh measures them) and
// the bounds Theorem 6.1 gives at λ.
void add_output_statistics(nlohmann::json& j, const MeshReport& report, std::size_t inconsistent,
                           std::size_t not_added, double lambda) {
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
  if (lambda < beta_lambda_bound) {
    const auto b = theorem_bounds(lambda);
    j["bounds"] = {{"min_angle_deg", b.min_angle_deg},
                   {"max_radius_edge_ratio", b.max_radius_edge_ratio},
                   {"max_roughness_rad", b.max_roughness_rad}};
  } else {
    j["bounds"] = nlohmann::json::object();
  }
}

// The statistics of the run itself: the refinement's counts and seconds, the oracle's, what was
// left unsettled, the seeds, the topology phase and the termination floor.
void add_run_statistics(nlohmann::json& j, Refinement& refinement, const SurfaceOracle& oracle,
                        const Certification& certification, const std::vector<std::string>& defects,
                        const SeedReport& seeds, const TopologyPhase& topology) {
  j["insertions"] = refinement.insertions_json();
  j["solver"] = oracle.statistics_json();
  j["solver"]["unresolved_edge_regions"] = certification.unresolved_edge_regions;
  j["unsettled"] = unsettled_json(certification.unsettled, defects);
  j["seconds_per_check"] = refinement.seconds_json();
  j["checks"] = refinement.checks_json();
  j["seconds_insertion"] = refinement.seconds_insertion();
  j["edge_records"] = {{"solved", refinement.restricted().records_solved()},
                       {"restricted", refinement.restricted().records_restricted()}};
  j["voronoi_facets"] = {{"built", refinement.restricted().facets_built()},
                         {"missing_surface", refinement.restricted().facets_missing_surface()},
                         {"certified_by_cell", refinement.restricted().facets_certified_by_cell()}};
  j["height_direction"] = seeds.height_direction;
  j["height_direction_attempts"] = seeds.attempts;
  j["seed_undecided"] = seeds.undecided;
  j["threads"] = refinement.threads();
  j["topology_phase"] = {{"vertices", topology.vertices},
                         {"seconds", topology.seconds},
                         {"insertions", topology.insertions},
                         {"min_spacing", topology.floor}};
  j["min_spacing"] = refinement.floor_json();
  j["points"] = refinement.delaunay().size();
}

// The run on a validated input whose clock (time limit, seconds) started at `start`: SampleTopology,
// then (phase all) Quality and Smooth; the output mesh, its defects and the certification; the
// statistics.  With `sigma` (a triangle-mesh input at the oracle's scale), each phase ends with
// the closed-ball refinement and the status follows decide_pl_status (closed_ball_refinement.h).
DelMeshResult run(SurfaceOracle& oracle, const DelMeshOptions& options, double seconds_validation,
                  std::chrono::steady_clock::time_point start, const SurfaceMesh* sigma = nullptr,
                  const RunKnobs& knobs = {}) {
  const RefinementLimits limits = refinement_limits(options, start);
  oracle.set_run_controls(options.seed, limits.deadline);
  Refinement refinement(oracle, options.seed, limits, RecheckPolicy::new_faces, options.threads,
                        knobs.parallel_every_batch);

  const SampleTopologyResult sampled = sample_topology(refinement);
  const SeedReport& seeds = sampled.seeds;
  MeshStatus status = sampled.status;
  ClosedBallRefinement closed_ball;
  if (sigma) status = refine_closed_ball(refinement, *sigma, status, closed_ball);
  const TopologyPhase topology{refinement.delaunay().size(),
                               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                               refinement.insertions_json(), refinement.floor_json()};
  if (status == MeshStatus::complete && options.phase == MeshPhase::all) {
    refinement.enable_geometry(options.lambda, options.size_bound, options.max_distance);
    status = refinement.run();
    if (sigma) status = refine_closed_ball(refinement, *sigma, status, closed_ball);
  }

  DelMeshResult result;
  std::size_t inconsistent = 0, not_added = 0;
  result.mesh = output_mesh(refinement, inconsistent, not_added);
  const MeshReport report = check_mesh(result.mesh);
  const std::vector<std::string> defects = output_defects(report, inconsistent, not_added);
  const Certification certification = refinement.certify(status, !defects.empty());
  result.status = certification.status;
  // Every check's answer must be certified for the run to be: answers of uncertified path
  // tracking may have missed a point of Σ on a face that was then taken as clean.
  const bool solver_certified = !oracle.gave_uncertified_answers();
  if (!solver_certified && result.status == MeshStatus::complete) result.status = MeshStatus::uncertified;
  nlohmann::json closed_ball_statistics;
  if (sigma) {
    const bool geometry = status == MeshStatus::complete && options.phase == MeshPhase::all;
    const PlStatusDecision decision =
        decide_pl_status(refinement, closed_ball, status, certification, !defects.empty(), solver_certified,
                         options.lambda, geometry);
    result.status = decision.status;
    closed_ball_statistics = closed_ball_refinement_json(closed_ball, decision);
  }

  auto& j = result.statistics;
  j["status"] = text_of(result.status);
  j["lambda"] = options.lambda;
  j["theorem_applies"] = options.lambda <= lambda0;
  j["phase"] = text_of(options.phase);
  j["smooth_enabled"] = options.lambda < beta_lambda_bound;
  j["seed"] = options.seed;
  j["seconds_validation"] = seconds_validation;
  j["solver_certified"] = solver_certified;
  const Box3& clip = oracle.clip_box();
  j["clip_box"] = {clip.lo[0], clip.hi[0], clip.lo[1], clip.hi[1], clip.lo[2], clip.hi[2]};
  add_output_statistics(j, report, inconsistent, not_added, options.lambda);
  add_run_statistics(j, refinement, oracle, certification, defects, seeds, topology);
  if (sigma) j["closed_ball"] = std::move(closed_ball_statistics);
  j["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace

void certify_distance(DelMeshResult& result, const Surface& surface, const Box3& box, const DelMeshOptions& options,
                      std::chrono::steady_clock::time_point start) {
  auto& j = result.statistics;
  result.triangle_distance_bounds.clear();
  const bool attempted = (result.status == MeshStatus::complete || result.status == MeshStatus::uncertified) &&
                         result.mesh.number_of_faces() > 0;
  if (!attempted) {
    j["distance"] = {{"status", "not attempted"}, {"reason", "the run ended " + text_of(result.status)}};
  } else {
    if (options.progress) {
      ProgressReport started;
      started.phase = ProgressPhase::certifying;
      started.points = j.value("points", std::size_t{0});
      started.elapsed_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      options.progress(started);
    }
    FlowCertificateOptions flow;
    flow.seed = options.seed;
    flow.interrupt = options.interrupt;
    flow.deadline = deadline_of(options, start);
    flow.distance_radius = options.max_distance.value_or(0);
    flow.surface_validated = true;
    std::vector<Point3> points;
    std::vector<std::array<std::size_t, 3>> triangles;
    mesh_to_soup(result.mesh, points, triangles);
    FlowCertificate certificate = certify_gradient_flow(points, triangles, surface, box, flow);
    j["distance"] = to_json(certificate);
    if (certificate.status == FlowCertificateStatus::certified)
      result.triangle_distance_bounds = std::move(certificate.triangle_distance_bounds);
    const bool within = certificate.status == FlowCertificateStatus::certified &&
                        (!options.max_distance || certificate.hausdorff_upper_bound <= *options.max_distance);
    const bool stopped = certificate.interrupted || certificate.time_limited;
    if (options.max_distance && stopped && result.status == MeshStatus::complete) {
      // The bound is part of the run's end: a limit that stops its proof stops the run.
      result.status = certificate.interrupted ? MeshStatus::interrupted : MeshStatus::time_limit;
      j["status"] = text_of(result.status);
    } else if (options.max_distance && !within) {
      // Unsettled like a check's finding, so that an uncertified run always says why.
      auto& unsettled = j["unsettled"];
      unsettled["count"] = unsettled["count"].get<std::size_t>() + 1;
      unsettled["by_reason"]["distance_not_certified"] = unsettled["by_reason"].value("distance_not_certified", 0) + 1;
      const std::string reason = certificate.status == FlowCertificateStatus::certified
                                     ? "the certified Hausdorff bound exceeds max_distance"
                                     : certificate.reason;
      unsettled["regions"].push_back({{"check", "distance"}, {"reason", reason},
                                      {"location", certificate.location ? nlohmann::json(*certificate.location)
                                                                        : nlohmann::json()}});
      if (result.status == MeshStatus::complete) {
        result.status = MeshStatus::uncertified;
        j["status"] = text_of(result.status);
      }
    }
  }
  j["distance"]["max_distance"] = options.max_distance ? nlohmann::json(*options.max_distance) : nlohmann::json();
  j["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

namespace {

// The options and what they ask of the oracle: max_distance needs its flow_distance().
void check_run(const SurfaceOracle& oracle, const DelMeshOptions& options) {
  check_options(oracle.box(), options);
  if (options.max_distance && !oracle.flow_distance())
    throw InvalidInput("max_distance needs a surface given by E (this input has no gradient field to bound distances by)");
}

// The Smooth check's feature edges (meshing/checks/smooth.h) on the MeshOracle of a triangle-mesh
// input: those of `sigma` (at the oracle's scale) at the feature angle, none without one; and the
// statistics' input_mesh.features at that angle.
void set_feature_edges(PreparedInput& input, const SurfaceMesh& sigma, std::optional<double> angle_deg) {
  auto* oracle = dynamic_cast<MeshOracle*>(input.oracle.get());
  if (!oracle) return;
  if (!angle_deg) {
    oracle->set_feature_edges(FeatureEdges{});
    input.statistics["features"] = {{"angle_deg", nullptr}, {"detected", false}};
    return;
  }
  const auto* triangles = std::get_if<TriangleMeshInput>(&input.input);
  const FeatureSet features = detect_features(sigma, *angle_deg, triangles->mesh->folded_vertices);
  oracle->set_feature_edges(FeatureEdges(sigma, features));
  input.statistics["features"] = features_json(features);
}

// del_mesh on a prepared input, its clock (time limit, seconds) started at `start`.
DelMeshResult mesh_prepared(PreparedInput& input, const DelMeshOptions& options,
                            std::chrono::steady_clock::time_point start, const RunKnobs& knobs = {}) {
  check_run(*input.oracle, options);
  const int k = input.scale_exponent;
  // A triangle mesh's Σ at the oracle's scale (times 2^-k, exactly) for the closed-ball check.
  std::optional<SurfaceMesh> sigma;
  if (const auto* triangles = std::get_if<TriangleMeshInput>(&input.input); triangles && triangles->mesh) {
    sigma = triangles->mesh->mesh;
    scale_mesh(*sigma, -k);
    set_feature_edges(input, *sigma, options.feature_angle_deg);
  }
  DelMeshResult result = run(*input.oracle, unit_scale_options(options, k), input.seconds_validation, start,
                             sigma ? &*sigma : nullptr, knobs);
  restore_scale(result, k);
  result.statistics[input.statistics_key] = input.statistics;
  if (const ImplicitInput* implicit = input.implicit_input())
    if (options.distance_certificate || options.max_distance)
      certify_distance(result, implicit->surface, implicit->box, options, start);
  return result;
}

}  // namespace

DelMeshResult del_mesh(const Surface& surface, const Box3& box, const DelMeshOptions& options) {
  return del_mesh_with(surface, box, options, RunKnobs{});
}

DelMeshResult detail::del_mesh_with(const Surface& surface, const Box3& box, const DelMeshOptions& options,
                                    const RunKnobs& knobs) {
  const auto start = std::chrono::steady_clock::now();
  check_options(box, options);
  PreparedInput input = make_oracle(ImplicitInput{"surface", surface, box, options.solver});
  return mesh_prepared(input, options, start, knobs);
}

DelMeshResult del_mesh(PreparedInput& input, const DelMeshOptions& options) {
  return mesh_prepared(input, options, std::chrono::steady_clock::now());
}

DelMeshResult del_mesh(SurfaceOracle& oracle, const DelMeshOptions& options, double seconds_validation) {
  const auto start = std::chrono::steady_clock::now();
  check_run(oracle, options);
  return run(oracle, options, seconds_validation, start);
}

}  // namespace delmesh
