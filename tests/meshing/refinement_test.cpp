// Tests of the refinement driver (Topology, §5.4) and SampleTopology on catalog surfaces: the output is checked by the
// independent mesh checker (it reads only the mesh), and Lemma 5.1 is checked empirically.
#include <boost/test/unit_test.hpp>

#include <chrono>
#include <cmath>
#include <iomanip>
#include <map>
#include <sstream>
#include <string>

#include "forwarding_oracle.h"
#include "meshing/core/detail/vec3.h"
#include "meshing/core/mesh_checker.h"
#include "meshing/core/theorem_bounds.h"
#include "meshing/driver/del_mesh.h"
#include "meshing/driver/refinement.h"
#include "meshing/driver/sample_topology.h"
#include "meshing/inputs/implicit_oracle.h"
#include "symbolic/catalog.h"

using namespace delmesh;

namespace {

// Reports, once switched on, the first transversal crossing of every SurfaceLine as an undecided
// tangency region (singular_root) at the same point: what the real solver answers at a tangency.
class TangencyOracle final : public test::ForwardingOracle {
 public:
  using ForwardingOracle::ForwardingOracle;
  bool on = false;
  SolveResult surface_line(const Vec3& p, const Vec3& v, double t0, double t1) override {
    SolveResult r = ForwardingOracle::surface_line(p, v, t0, t1);
    if (!on || r.roots.empty()) return r;
    const CertifiedRoot root = r.roots.front();
    r.roots.erase(r.roots.begin());
    r.undecided.push_back({root.box, UndecidedReason::singular_root, root.world});
    r.status = SolveStatus::undecided;
    return r;
  }
};

struct TopologyRun {
  ImplicitOracle oracle;
  Refinement topology;
  SeedReport seeds;
  MeshStatus status;
  TopologyRun(const CatalogEntry& entry, std::uint64_t seed, RecheckPolicy policy = RecheckPolicy::new_faces)
      : oracle(entry.surface(), entry.box, SolverBackend::subdivision), topology(oracle, seed, RefinementLimits{}, policy) {
    const SampleTopologyResult run = sample_topology(topology);
    seeds = run.seeds;
    status = run.status;
  }
};

MeshReport topology_report(const std::string& name, std::uint64_t seed) {
  const auto& entry = catalog_entry(name);
  DelMeshOptions options;
  options.phase = MeshPhase::topology;
  options.seed = seed;
  const auto result = del_mesh(entry.surface(), entry.box, options);
  BOOST_TEST(result.status == MeshStatus::complete);
  return check_mesh(result.mesh);
}

void check_catalog_topology(const std::string& name, std::uint64_t seed) {
  const auto& entry = catalog_entry(name);
  const MeshReport r = topology_report(name, seed);
  BOOST_TEST_MESSAGE(name << " seed " << seed << ": " << r.vertices << " vertices, " << r.triangles << " triangles");
  BOOST_TEST(r.closed);
  BOOST_TEST(r.manifold);
  BOOST_TEST(r.orientable);
  BOOST_TEST(r.components == entry.components);
  BOOST_TEST(r.genus_per_component == entry.genus_per_component, boost::test_tools::per_element());
}

// Lemma 5.1 (λ = λ0 = 0.06): every non-seed point inserted by the driver is at distance ≥ λ·lfs(p)
// from its nearest sample p at insertion time.
void check_lemma_5_1(const std::string& name) {
  const auto& entry = catalog_entry(name);
  TopologyRun run(entry, 1);
  BOOST_TEST(run.status == MeshStatus::complete);
  std::size_t checked = 0;
  for (const auto& rec : run.topology.insertion_log()) {
    if (rec.kind == CheckKind::seed || rec.nearest < 0) continue;
    const auto& p = run.topology.delaunay().point(rec.nearest);
    const double lfs = entry.local_feature_size(p);
    BOOST_TEST(rec.nearest_distance >= 0.06 * lfs, name << ": insertion by " << rec.kind << " at distance "
                                                        << rec.nearest_distance << " < 0.06 lfs = " << 0.06 * lfs);
    ++checked;
  }
  BOOST_TEST(checked > 0u);
}

// The lemma of refinement.h: re-checking every shrunk face as well as the new ones inserts the
// same points, except where the full recheck finds a candidate in an undecided solver region (the
// lemma covers clean results only); from the first such insertion on the runs may differ.
void check_recheck_lemma(const std::string& name) {
  const auto& entry = catalog_entry(name);
  TopologyRun fresh(entry, 1, RecheckPolicy::new_faces);
  TopologyRun full(entry, 1, RecheckPolicy::changed_faces);
  BOOST_TEST(fresh.status == MeshStatus::complete);
  BOOST_TEST(full.status == MeshStatus::complete);
  const auto& a = fresh.topology.insertion_log();
  const auto& b = full.topology.insertion_log();
  // Root estimates refined on different edge lengths may differ in the last digits.
  const double tolerance = 1e-9 * entry.box.diagonal();
  auto same = [&](const Vec3& p, const Vec3& q) {
    return std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]) <= tolerance;
  };
  std::size_t i = 0;
  while (i < a.size() && i < b.size() && same(a[i].point, b[i].point)) ++i;
  if (i < b.size() && (i >= a.size() || !same(a[i].point, b[i].point))) {
    BOOST_TEST(b[i].from_undecided, name << ": insertion " << i << " of the full recheck (by " << b[i].kind
                                          << ") is not from an undecided region");
    BOOST_TEST_MESSAGE(name << ": runs agree on " << i << " insertions, then the full recheck inserts an undecided candidate");
  } else {
    BOOST_TEST(a.size() == b.size());
  }
  // The full recheck examined more faces.
  BOOST_TEST(full.topology.checks(CheckKind::silhouette) >= fresh.topology.checks(CheckKind::silhouette));
}

}  // namespace

BOOST_AUTO_TEST_SUITE(refinement)

BOOST_AUTO_TEST_CASE(recheck_lemma_sphere) { check_recheck_lemma("sphere"); }

BOOST_AUTO_TEST_CASE(recheck_lemma_torus) { check_recheck_lemma("torus"); }

BOOST_AUTO_TEST_CASE(recheck_lemma_every_catalog_surface, *boost::unit_test::label("slow")) {
  for (const auto& entry : catalog()) check_recheck_lemma(entry.name);
}

BOOST_AUTO_TEST_CASE(sphere_topology_phase_is_a_sphere) { check_catalog_topology("sphere", 1); }

BOOST_AUTO_TEST_CASE(torus_topology_phase_is_a_torus) { check_catalog_topology("torus", 1); }

BOOST_AUTO_TEST_CASE(lemma_5_1_sphere) { check_lemma_5_1("sphere"); }

BOOST_AUTO_TEST_CASE(lemma_5_1_torus) { check_lemma_5_1("torus"); }

BOOST_AUTO_TEST_CASE(seeds_are_deleted) {
  TopologyRun run(catalog_entry("sphere"), 2);
  BOOST_TEST(run.seeds.seeds >= 2u);
  BOOST_TEST(run.topology.seeds_deleted() == run.seeds.seeds);
  for (auto v : run.topology.delaunay().vertices()) BOOST_TEST(!run.topology.delaunay().is_seed(v));
}

BOOST_AUTO_TEST_CASE(every_catalog_surface_three_seeds, *boost::unit_test::label("slow")) {
  for (const auto& entry : catalog())
    for (std::uint64_t seed : {1, 2, 3}) check_catalog_topology(entry.name, seed);
}

// A complete run on a catalog surface leaves nothing unsettled and certifies as complete.
BOOST_AUTO_TEST_CASE(clean_run_certifies_complete) {
  TopologyRun run(catalog_entry("torus"), 1);
  BOOST_TEST_REQUIRE(run.status == MeshStatus::complete);
  BOOST_TEST(run.topology.unsettled().empty());
  const Certification c = run.topology.certify(run.status, false);
  BOOST_TEST(c.status == MeshStatus::complete);
  BOOST_TEST(c.unsettled.empty());
  BOOST_TEST(c.unresolved_edge_regions == 0u);
  // A defective output alone makes it uncertified; a limit status is never upgraded.
  BOOST_TEST(run.topology.certify(run.status, true).status == MeshStatus::uncertified);
  BOOST_TEST(run.topology.certify(MeshStatus::point_limit, true).status == MeshStatus::point_limit);
  // The driver skips the queued checks of triangles without a record; records that are not one
  // per Delaunay triangle at the end (here one dropped by hand) keep the run from complete.
  const auto& del = run.topology.delaunay();
  BOOST_TEST_REQUIRE(run.topology.restricted().record_count() == del.triangle_count());
  BOOST_TEST(del.triangle_count() == del.triangles().size());
  run.topology.restricted().forget({del.triangles().front()}, {});
  const Certification broken = run.topology.certify(run.status, false);
  BOOST_TEST(broken.status == MeshStatus::uncertified);
  BOOST_TEST_REQUIRE(broken.unsettled.size() == 1u);
  BOOST_TEST(broken.unsettled.front().reason == UnsettledReason::record_count_mismatch);
}

// A Voronoi-edge record solved again is a new answer: when it holds a tangency candidate the run
// cannot be complete, whether or not VorEdge ran on it since (every final record is judged).
BOOST_AUTO_TEST_CASE(a_record_solved_again_with_a_tangency_keeps_the_run_from_complete) {
  const auto& entry = catalog_entry("torus");
  ImplicitOracle inner(entry.surface(), entry.box, SolverBackend::subdivision);
  TangencyOracle oracle(inner);
  Refinement topology(oracle, 1, RefinementLimits{});
  const MeshStatus status = sample_topology(topology).status;
  BOOST_TEST_REQUIRE(status == MeshStatus::complete);
  BOOST_TEST_REQUIRE(topology.certify(status, false).status == MeshStatus::complete);
  std::optional<TriangleKey> restricted_triangle;
  for (const TriangleKey& t : topology.delaunay().triangles())
    if (topology.restricted().voronoi_edge_record(t).restricted) {
      restricted_triangle = t;
      break;
    }
  BOOST_TEST_REQUIRE(restricted_triangle.has_value());
  oracle.on = true;
  topology.restricted().forget({*restricted_triangle}, {});
  const VoronoiEdgeRecord& solved_again = topology.restricted().voronoi_edge_record(*restricted_triangle);
  BOOST_TEST_REQUIRE(!solved_again.candidates().empty());
  BOOST_TEST(solved_again.unresolved().empty());
  const Certification c = topology.certify(status, false);
  BOOST_TEST(c.status == MeshStatus::uncertified);
  BOOST_TEST_REQUIRE(c.unsettled.size() == 1u);
  BOOST_TEST(c.unsettled.front().check == CheckKind::vor_edge);
  BOOST_TEST(c.unsettled.front().reason == UnsettledReason::vor_edge_fires);
  BOOST_TEST(detail::distance(c.unsettled.front().location, solved_again.candidates().front()) == 0.0);
}

// Silhouette's premise fails exactly at the samples with a facet left unsettled by FacetContact or
// FacetCycle (on genus2: witnesses rejected as duplicates within 15 % of the box diagonal), and holds at
// every sample of a run with nothing unsettled.
BOOST_AUTO_TEST_CASE(unsettled_facets_break_silhouette_premise) {
  const auto& entry = catalog_entry("genus2");
  TopologyRun settled(entry, 1);
  BOOST_TEST_REQUIRE(settled.status == MeshStatus::complete);
  for (VertexId p = 0; p < static_cast<VertexId>(settled.topology.delaunay().size()); ++p)
    BOOST_TEST_REQUIRE(settled.topology.silhouette_premise(p));

  ImplicitOracle oracle(entry.surface(), entry.box, SolverBackend::subdivision);
  RefinementLimits limits;
  limits.duplicate_relative_distance = 0.15;
  Refinement refinement(oracle, 1, limits);
  BOOST_TEST_REQUIRE(sample_topology(refinement).status == MeshStatus::complete);
  std::size_t facet_findings = 0;
  for (const auto& u : refinement.unsettled())
    facet_findings += u.check == CheckKind::facet_contact || u.check == CheckKind::facet_cycle ? 1 : 0;
  BOOST_TEST_REQUIRE(facet_findings > 0u);
  std::size_t without_premise = 0;
  for (VertexId p = 0; p < static_cast<VertexId>(refinement.delaunay().size()); ++p)
    without_premise += refinement.silhouette_premise(p) ? 0 : 1;
  BOOST_TEST(without_premise > 0u);
  BOOST_TEST(without_premise <= 2 * facet_findings);
}

// Witnesses within 15 % of the box diagonal of a sample count as duplicates: the checks' witnesses
// are rejected, the faces that gave them stay unsettled on the final Vor S, and the run cannot
// certify as complete.
BOOST_AUTO_TEST_CASE(rejected_witnesses_leave_the_run_uncertified) {
  const auto& entry = catalog_entry("torus");
  ImplicitOracle oracle(entry.surface(), entry.box, SolverBackend::subdivision);
  RefinementLimits limits;
  limits.duplicate_relative_distance = 0.15;
  Refinement refinement(oracle, 1, limits);
  const MeshStatus status = sample_topology(refinement).status;
  BOOST_TEST_REQUIRE(status == MeshStatus::complete);
  BOOST_TEST_REQUIRE(refinement.rejected_witnesses() > 0u);
  // FacetCycle and Silhouette faces whose witnesses were all rejected were run again with other
  // generic directions; each retry follows a rejection.
  BOOST_TEST(refinement.generic_choice_retries() > 0u);
  BOOST_TEST(refinement.generic_choice_retries() <= refinement.rejected_witnesses());
  BOOST_TEST(refinement.insertions_json().at("generic_choice_retries") == refinement.generic_choice_retries());
  const auto unsettled = refinement.unsettled();
  BOOST_TEST_REQUIRE(!unsettled.empty());
  for (const auto& u : unsettled) {
    BOOST_TEST(u.reason == UnsettledReason::rejected_witness);
    BOOST_TEST(std::abs(oracle.E(u.location)) < 1e-6);  // a witness: a point of Σ
  }
  BOOST_TEST(refinement.certify(status, false).status == MeshStatus::uncertified);
}

// The clock is read once per run of checks of one row (and every checks_per_clock_reading
// checks): every row that examined an item is charged a positive time, and the checks' and the
// insertions' times together do not exceed the run's.  A deadline already past stops run() at
// its first reading, before any check.
BOOST_AUTO_TEST_CASE(check_times_add_up_and_a_past_deadline_stops_the_run) {
  const auto& entry = catalog_entry("torus");
  ImplicitOracle oracle(entry.surface(), entry.box, SolverBackend::subdivision);
  const auto start = std::chrono::steady_clock::now();
  Refinement refinement(oracle, 1, RefinementLimits{});
  BOOST_TEST_REQUIRE(sample_topology(refinement).status == MeshStatus::complete);
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  double charged = refinement.seconds_insertion();
  for (int k = 0; k < check_kind_count(); ++k) {
    const auto kind = static_cast<CheckKind>(k);
    if (refinement.checks(kind) > 0) BOOST_TEST(refinement.seconds(kind) > 0);
    BOOST_TEST(refinement.seconds(kind) >= 0);
    charged += refinement.seconds(kind);
  }
  BOOST_TEST(charged <= elapsed);

  RefinementLimits limits;
  limits.deadline = std::chrono::steady_clock::now();
  Refinement late(oracle, 1, limits);
  BOOST_TEST_REQUIRE(late.insert(Witness{{1.4, 0, 0}, CheckKind::seed}).has_value());
  BOOST_TEST(late.run() == MeshStatus::time_limit);
  for (int k = 0; k < check_kind_count(); ++k) BOOST_TEST(late.checks(static_cast<CheckKind>(k)) == 0u);
}

// Six samples at the vertices of an octahedron centred at (1,0,0) ∈ Σ (the unit sphere) are
// cospherical: the Voronoi edges of the inner triangles shrink to the point (1,0,0), which Σ
// passes through.  Those degenerate edges are unresolved, and the run cannot certify as complete.
BOOST_AUTO_TEST_CASE(degenerate_voronoi_edge_on_the_surface_is_unresolved) {
  ImplicitOracle oracle(Surface::parse("x^2+y^2+z^2-1"), Box3::cube(1.6), SolverBackend::subdivision);
  Refinement refinement(oracle, 1, RefinementLimits{});
  for (const Vec3& x : std::vector<Vec3>{{1.5, 0, 0}, {0.5, 0, 0}, {1, 0.5, 0}, {1, -0.5, 0}, {1, 0, 0.5}, {1, 0, -0.5}})
    BOOST_TEST_REQUIRE(refinement.insert(Witness{x, CheckKind::seed, -1, false}).has_value());
  const Certification c = refinement.certify(MeshStatus::complete, false);
  BOOST_TEST_REQUIRE(c.unresolved_edge_regions > 0u);
  BOOST_TEST(c.status == MeshStatus::uncertified);
  // No check ran, so records with two crossings are listed too (VorEdge would fire on them).
  for (const auto& u : c.unsettled) {
    BOOST_TEST((u.reason == UnsettledReason::unresolved_crossing || u.reason == UnsettledReason::vor_edge_fires));
    if (u.reason == UnsettledReason::unresolved_crossing) BOOST_TEST(detail::distance(u.location, {1, 0, 0}) < 1e-9);
  }
}

// The same octahedron centred at (0.5,0,0), inside the ball: its degenerate edges are far from Σ
// and nothing is unresolved.
BOOST_AUTO_TEST_CASE(degenerate_voronoi_edge_off_the_surface_is_settled) {
  ImplicitOracle oracle(Surface::parse("x^2+y^2+z^2-1"), Box3::cube(1.6), SolverBackend::subdivision);
  Refinement refinement(oracle, 1, RefinementLimits{});
  for (const Vec3& x : std::vector<Vec3>{{1, 0, 0}, {0, 0, 0}, {0.5, 0.5, 0}, {0.5, -0.5, 0}, {0.5, 0, 0.5}, {0.5, 0, -0.5}})
    BOOST_TEST_REQUIRE(refinement.insert(Witness{x, CheckKind::seed, -1, false}).has_value());
  BOOST_TEST(refinement.certify(MeshStatus::complete, false).unresolved_edge_regions == 0u);
}

// Two unit spheres a gap g apart: ((x − 1 − g/2)² + y² + z² − 1)((x + 1 + g/2)² + y² + z² − 1).
Surface spheres_apart(double gap) {
  std::ostringstream c;
  c << std::setprecision(17) << 1 + gap / 2;
  return Surface::parse("((x-" + c.str() + ")^2+y^2+z^2-1)*((x+" + c.str() + ")^2+y^2+z^2-1)");
}
const Box3 spheres_box{{-2.5, -1.5, -1.5}, {2.5, 1.5, 1.5}};

// Opposite-sheet partners (refinement.h): each lies on Σ, on the normal line of the witness it
// pairs, within the witness's nearest-sample distance, with normals |cos| ≥ 1/2, and at least
// half its distance to the witness from every earlier sample (the termination argument's two
// conditions).  Without them the spheres 1e-4 apart need about 38 000 points; with them a few
// hundred.
BOOST_AUTO_TEST_CASE(opposite_sheet_partners_pair_nearly_touching_spheres) {
  ImplicitOracle oracle(spheres_apart(1e-4), spheres_box, SolverBackend::subdivision);
  RefinementLimits limits;
  limits.max_points = 3000;
  Refinement refinement(oracle, 1, limits);
  BOOST_TEST_REQUIRE(sample_topology(refinement).status == MeshStatus::complete);
  BOOST_TEST_REQUIRE(refinement.opposite_sheet_partners() > 0u);
  BOOST_TEST(refinement.insertions_json().at("opposite_sheet") == refinement.opposite_sheet_partners());
  std::map<VertexId, const InsertionRecord*> by_id;
  for (const auto& rec : refinement.insertion_log()) by_id[rec.id] = &rec;
  std::size_t partners = 0;
  for (const auto& rec : refinement.insertion_log()) {
    if (rec.partner_of < 0) continue;
    ++partners;
    const InsertionRecord& w = *by_id.at(rec.partner_of);
    const double gap = detail::distance(rec.point, w.point);
    BOOST_TEST(std::abs(oracle.E(rec.point)) < 1e-12);
    BOOST_TEST(gap <= w.nearest_distance * (1 + 1e-12));
    const Vec3 n = oracle.normal(w.point);
    const Vec3 off = detail::operator-(rec.point, w.point);
    BOOST_TEST(detail::norm(detail::cross(off, n)) <= 1e-9 * gap);  // on w's normal line
    BOOST_TEST(std::abs(detail::dot(oracle.normal(rec.point), n)) >= 0.5);
    BOOST_TEST(rec.nearest_distance >= 0.5 * gap * (1 - 1e-12));
  }
  BOOST_TEST(partners == refinement.opposite_sheet_partners());
}

// The whole of DelMesh on spheres 1e-5 apart: the right topology and Theorem 6.1's bounds with a
// few hundred points (the spacing the gap would force is about 1e-5: some 400 000 points).
BOOST_AUTO_TEST_CASE(nearly_touching_spheres_mesh_with_few_points) {
  DelMeshOptions options;
  options.max_points = 5000;
  options.threads = 1;
  const auto result = del_mesh(spheres_apart(1e-5), spheres_box, options);
  BOOST_TEST_REQUIRE(result.status == MeshStatus::complete);
  const MeshReport r = check_mesh(result.mesh);
  BOOST_TEST(r.closed);
  BOOST_TEST(r.manifold);
  BOOST_TEST(r.components == 2);
  BOOST_TEST(r.genus_per_component == std::vector<int>({0, 0}), boost::test_tools::per_element());
  const TheoremBounds bounds = theorem_bounds(options.lambda);
  BOOST_TEST(r.min_angle_deg >= bounds.min_angle_deg - 1e-9);
  BOOST_TEST(r.max_radius_edge_ratio <= bounds.max_radius_edge_ratio + 1e-9);
}

BOOST_AUTO_TEST_SUITE_END()
