// Tests of Topology / SampleTopology (§5.4) on catalog surfaces: the output is checked by the
// independent mesh checker (it reads only the mesh), and Lemma 5.1 is checked empirically.
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "meshing/del_mesh.h"
#include "meshing/mesh_checker.h"
#include "meshing/sample_topology.h"
#include "meshing/topology.h"
#include "symbolic/catalog.h"

using namespace delmesh;

namespace {

struct TopologyRun {
  SurfaceOracle oracle;
  Topology topology;
  SeedReport seeds;
  TopologyStatus status;
  TopologyRun(const CatalogEntry& entry, std::uint64_t seed)
      : oracle(entry.surface(), entry.box, SolverBackend::subdivision),
        topology(oracle, seed, TopologyLimits{}),
        status(sample_topology(topology, seeds)) {}
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

// Lemma 5.1 (λ = λ0 = 0.06): every non-seed point inserted by Topology is at distance ≥ λ·lfs(p)
// from its nearest sample p at insertion time.
void check_lemma_5_1(const std::string& name) {
  const auto& entry = catalog_entry(name);
  TopologyRun run(entry, 1);
  BOOST_TEST(run.status == TopologyStatus::complete);
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

}  // namespace

BOOST_AUTO_TEST_SUITE(topology)

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

BOOST_AUTO_TEST_SUITE_END()
