// Tests of the check registry (meshing/checks/check_registry.h): the paper's rows in the driver's order
// with their kinds, faces, rules and phases; VorEdge's may_fire; registration after the registry
// was read and unknown names are refused; the certificate times exactly the topology rows.

#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include <boost/test/unit_test.hpp>

#include "common/errors.h"
#include "meshing/checks/check_registry.h"
#include "meshing/verify/certificate.h"
#include "symbolic/catalog.h"

using namespace delmesh;

BOOST_AUTO_TEST_SUITE(check_registry_suite)

BOOST_AUTO_TEST_CASE(paper_rows_in_the_drivers_order) {
  const auto& rows = builtin_checks();
  const std::vector<std::string> names{"vor_edge", "facet_contact", "topo_disk", "facet_cycle",
                                       "silhouette", "quality", "smooth"};
  BOOST_TEST_REQUIRE(rows.size() == names.size());
  // meshing_tests registers no check: the registry is the paper's rows.
  BOOST_TEST(check_registry().size() == rows.size());
  BOOST_TEST(check_kind_count() == static_cast<int>(CheckKind::distance) + 1);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    BOOST_TEST(rows[i].name == names[i]);
    BOOST_TEST(check_kind_name(rows[i].kind) == names[i]);
    BOOST_TEST(static_cast<bool>(rows[i].check));
    BOOST_TEST((rows[i].phase == (i < 5 ? CheckPhase::topology : CheckPhase::geometry)), names[i]);
    if (rows[i].dirtied == Dirtied::restricted_star) BOOST_TEST((rows[i].face == FaceKind::vertex));
    if (rows[i].dirtied == Dirtied::restricted_triangles) BOOST_TEST((rows[i].face == FaceKind::triangle));
  }
  BOOST_TEST((find_check("vor_edge").face == FaceKind::triangle));
  BOOST_TEST((find_check("facet_contact").face == FaceKind::edge));
  BOOST_TEST((find_check("facet_cycle").face == FaceKind::edge));
  BOOST_TEST(find_check("facet_cycle").after_clean_predecessors);
  BOOST_TEST((find_check("topo_disk").dirtied == Dirtied::restricted_star));
  BOOST_TEST((find_check("silhouette").dirtied == Dirtied::new_faces));
  BOOST_TEST((find_check("quality").dirtied == Dirtied::restricted_triangles));
  BOOST_TEST(find_check("smooth").runs_at(0.06));
  BOOST_TEST(!find_check("smooth").runs_at(0.2));
  BOOST_TEST(check_kind_name(CheckKind::seed) == "seed");
  BOOST_TEST(check_kind_name(CheckKind::size) == "size");
  BOOST_TEST(check_kind_name(CheckKind::distance) == "distance");
}

// VorEdge is a function of the record: it can fire on a tangency candidate or on two crossings,
// not on one crossing or none.
BOOST_AUTO_TEST_CASE(vor_edge_may_fire_only_on_a_candidate_or_two_crossings) {
  const auto& may_fire = find_check("vor_edge").may_fire;
  BOOST_TEST_REQUIRE(static_cast<bool>(may_fire));
  VoronoiEdgeRecord record;
  BOOST_TEST(!may_fire(record));
  VoronoiEdgeLists lists;
  lists.crossings = {{0, 0, 1}};
  lists.crossing_range = {{0, 0}};
  record.set_lists(lists);
  BOOST_TEST(!may_fire(record));
  lists.crossings.push_back({0, 0, -1});
  lists.crossing_range.push_back({1, 1});
  record.set_lists(lists);
  BOOST_TEST(may_fire(record));
  lists.crossings.resize(1);
  lists.crossing_range.resize(1);
  lists.candidates = {{1, 0, 0}};
  lists.candidate_range = {{2, 2}};
  record.set_lists(lists);
  BOOST_TEST(may_fire(record));
}

BOOST_AUTO_TEST_CASE(late_registration_and_unknown_names_are_refused) {
  (void)check_registry();
  CheckInfo row{"late_check", "registered too late", FaceKind::vertex, Dirtied::new_faces, CheckPhase::topology,
                [](const CheckContext&, const DelaunayFace&) { return CheckResult{}; }};
  BOOST_CHECK_THROW(CheckRegistration{row}, PreconditionViolation);
  BOOST_CHECK_THROW(find_check("late_check"), InvalidInput);
  try {
    (void)find_check("no_such_check");
  } catch (const InvalidInput& e) {
    BOOST_TEST(std::string(e.what()).find("known checks: vor_edge, facet_contact") != std::string::npos, e.what());
  }
}

// The certificate runs the topology rows of the registry on every face: its per-check seconds
// are keyed by exactly their names, and every Voronoi face of the octahedron's Del S is checked.
BOOST_AUTO_TEST_CASE(certificate_runs_the_topology_rows) {
  const std::vector<Point3> points{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  const std::vector<std::array<std::size_t, 3>> triangles{{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                                          {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  const CatalogEntry& sphere = catalog_entry("sphere");
  const Certificate c = certify_mesh(points, triangles, sphere.surface(), sphere.box);
  std::vector<std::string> expected, keys;
  for (const CheckInfo& row : check_registry())
    if (row.phase == CheckPhase::topology) expected.push_back(row.name);
  const nlohmann::json j = to_json(c);
  for (const auto& [key, value] : j.at("seconds_per_check").items()) keys.push_back(key);
  std::sort(expected.begin(), expected.end());
  BOOST_TEST(keys == expected, boost::test_tools::per_element());
  BOOST_TEST(c.voronoi_cells == 6u);
  BOOST_TEST(c.restricted_matches_mesh);
}

BOOST_AUTO_TEST_SUITE_END()
