#include <boost/test/unit_test.hpp>

#include "meshing/delaunay.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <set>

using namespace delmesh;

namespace {

std::set<EdgeKey> all_edges(const Delaunay& del) {
  std::set<EdgeKey> out;
  for (VertexId v : del.vertices())
    for (const auto& e : del.incident_edges(v)) out.insert(e);
  return out;
}

template <class Key>
std::set<Key> as_set(const std::vector<Key>& keys) {
  return {keys.begin(), keys.end()};
}

}  // namespace

BOOST_AUTO_TEST_SUITE(delaunay)

BOOST_AUTO_TEST_CASE(ids_are_insertion_order_and_never_reused) {
  Delaunay del;
  const auto a = del.insert({0, 0, 0}, true);
  const auto b = del.insert({1, 0, 0}, false);
  BOOST_TEST(*a == 0);
  BOOST_TEST(*b == 1);
  BOOST_TEST(!del.insert({1, 0, 0}, false).has_value());  // duplicate point
  BOOST_TEST(del.is_seed(0));
  BOOST_TEST(!del.is_seed(1));
  del.remove(0);
  BOOST_TEST(!del.contains(0));
  const auto c = del.insert({0, 1, 0}, false);
  BOOST_TEST(*c == 2);
  BOOST_TEST(del.size() == 2u);
}

BOOST_AUTO_TEST_CASE(low_dimensions_have_the_right_simplices) {
  Delaunay del;
  del.insert({0, 0, 0}, false);
  del.insert({1, 0, 0}, false);
  BOOST_TEST(del.dimension() == 1);
  BOOST_TEST(del.triangles().empty());
  BOOST_TEST(del.is_edge({0, 1}));
  del.insert({0, 1, 0}, false);
  del.insert({1, 1.2, 0}, false);  // coplanar: dimension 2, two triangles
  BOOST_TEST(del.dimension() == 2);
  BOOST_TEST(del.triangles().size() == 2u);
  BOOST_TEST(del.incident_triangles(0).size() + del.incident_triangles(3).size() >= 2u);
  del.insert({0.3, 0.3, 1}, false);
  BOOST_TEST(del.dimension() == 3);
  BOOST_TEST(del.is_triangle(make_triangle_key(0, 1, 4)));
}

BOOST_AUTO_TEST_CASE(removal_restores_the_triangulation) {
  Delaunay del;
  for (auto p : std::vector<std::array<double, 3>>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}) del.insert(p, false);
  const auto before = del.triangles();
  const auto id = del.insert({0.2, 0.2, 0.2}, true);
  BOOST_TEST(del.neighbours(*id).size() == 4u);
  BOOST_TEST(del.triangles().size() == 10u);  // 4 hull + 6 interior
  del.remove(*id);
  BOOST_TEST((del.triangles() == before));
  BOOST_TEST(del.nearest({0.9, 0.1, 0}).first == 1);
}

BOOST_AUTO_TEST_CASE(keys_are_sorted) {
  BOOST_TEST((make_triangle_key(5, 2, 9) == TriangleKey{2, 5, 9}));
  BOOST_TEST((make_edge_key(7, 3) == EdgeKey{3, 7}));
}

// Bowyer–Watson, checked against the triangulation before and after: the triangles (edges) before
// are those after without the ones containing x, plus the destroyed ones; the shrunk ones survive
// and are exactly the link of x; the closed star lists both with the apexes of triangle_apexes.
BOOST_AUTO_TEST_CASE(insertion_change_is_the_cavity) {
  Delaunay del;
  // A deterministic cloud (golden-ratio spiral on a sphere plus an inner shell).
  for (int k = 0; k < 60; ++k) {
    const double z = 1 - (2 * k + 1) / 60.0, r = std::sqrt(1 - z * z), phi = 2.399963 * k;
    const double s = k % 3 == 0 ? 0.6 : 1.0;
    const auto before_triangles = as_set(del.triangles());
    const auto before_edges = all_edges(del);
    const int dimension = del.dimension();
    const auto [x, change] = del.insert_tracking({s * r * std::cos(phi), s * r * std::sin(phi), s * z}, false, k > 0 ? 0 : -1);
    BOOST_TEST_REQUIRE(x.has_value());
    BOOST_TEST(change.local == (dimension == 3));
    if (!change.local) continue;
    const auto after_triangles = as_set(del.triangles());
    const auto after_edges = all_edges(del);
    std::set<TriangleKey> expected_triangles;
    for (const auto& t : after_triangles)
      if (std::find(t.begin(), t.end(), *x) == t.end()) expected_triangles.insert(t);
    for (const auto& t : change.destroyed_triangles) {
      BOOST_TEST(!after_triangles.count(t));
      expected_triangles.insert(t);
    }
    BOOST_TEST((expected_triangles == before_triangles));
    std::set<EdgeKey> expected_edges;
    for (const auto& e : after_edges)
      if (e[0] != *x && e[1] != *x) expected_edges.insert(e);
    for (const auto& e : change.destroyed_edges) expected_edges.insert(e);
    BOOST_TEST((expected_edges == before_edges));
    for (const auto& e : change.shrunk_edges) BOOST_TEST((after_edges.count(e) && before_edges.count(e)));
    std::set<TriangleKey> link, with_x;
    for (const auto& s : del.closed_star(*x)) {
      (s.contains_vertex ? with_x : link).insert(s.key);
      const auto apexes = del.triangle_apexes(s.key);
      BOOST_TEST_REQUIRE(apexes.has_value());
      auto a = *apexes, b = s.apexes;
      std::sort(a.begin(), a.end());
      std::sort(b.begin(), b.end());
      BOOST_TEST((a == b));
    }
    BOOST_TEST((link == as_set(change.shrunk_triangles)));
    BOOST_TEST((with_x == as_set(del.incident_triangles(*x))));
    // The cells read in the same walk are incident_cells(x), in its order.
    std::vector<std::array<VertexId, 4>> cells;
    del.closed_star(*x, &cells);
    BOOST_TEST((cells == del.incident_cells(*x)));
    for (const auto& t : change.shrunk_triangles) BOOST_TEST(before_triangles.count(t));
  }
}

BOOST_AUTO_TEST_CASE(edge_triangles_are_the_triangles_around_an_edge) {
  Delaunay del;
  for (const auto& p : std::vector<std::array<double, 3>>{
           {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}, {-1, 0.2, 0.3}, {0.4, -1, 0.2}})
    del.insert(p, false);
  for (const auto& t : del.triangles())
    for (const auto& e : {EdgeKey{t[0], t[1]}, EdgeKey{t[0], t[2]}, EdgeKey{t[1], t[2]}}) {
      const auto around = del.edge_triangles(e);
      BOOST_TEST(std::binary_search(around.begin(), around.end(), t));
      for (const auto& s : around) BOOST_TEST((std::find(s.begin(), s.end(), e[0]) != s.end() &&
                                               std::find(s.begin(), s.end(), e[1]) != s.end()));
    }
  BOOST_TEST(del.edge_triangles({0, 99}).empty());
}

BOOST_AUTO_TEST_SUITE_END()
