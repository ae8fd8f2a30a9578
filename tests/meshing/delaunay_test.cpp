#include <boost/test/unit_test.hpp>

#include "meshing/voronoi/delaunay.h"

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
    const std::array<double, 3> p{s * r * std::cos(phi), s * r * std::sin(phi), s * z};
    // p's nearest sample, by a search over all of them.
    Nearest expected;
    for (VertexId v : del.vertices()) {
      const auto& q = del.point(v);
      const double d = std::sqrt((q[0] - p[0]) * (q[0] - p[0]) + (q[1] - p[1]) * (q[1] - p[1]) + (q[2] - p[2]) * (q[2] - p[2]));
      if (expected.id < 0 || d < expected.distance) expected = {v, d};
    }
    const auto [x, change, nearest] = del.insert_tracking(p, false, k > 0 ? 0 : -1);
    BOOST_TEST_REQUIRE(x.has_value());
    BOOST_TEST(nearest.id == expected.id);
    BOOST_TEST(nearest.distance == expected.distance);
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

// A point that the test refuses is not inserted and leaves Del S as it was; the test sees p's
// nearest sample, in dimension 3 (read off the cavity) and below.
BOOST_AUTO_TEST_CASE(a_refused_insertion_changes_nothing) {
  Delaunay del;
  for (const auto& p : std::vector<std::array<double, 3>>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}})
    BOOST_TEST_REQUIRE(del.insert(p, false).has_value());
  const NearestTest refuse_near = [](const Nearest& n) { return n.distance > 0.25; };
  auto [none, unchanged, nearest] = del.insert_tracking({0.9, 0.1, 0}, false, -1, refuse_near);
  BOOST_TEST(!none.has_value());
  BOOST_TEST(nearest.id == 1);
  BOOST_TEST(nearest.distance == std::sqrt(0.02), boost::test_tools::tolerance(1e-15));
  BOOST_TEST(del.dimension() == 2);
  for (const auto& p : std::vector<std::array<double, 3>>{{0, 0, 1}, {1, 1, 1}, {-1, 0.2, 0.3}, {0.4, -1, 0.2}})
    BOOST_TEST_REQUIRE(del.insert(p, false).has_value());
  const auto triangles = del.triangles();
  const std::size_t size = del.size();
  std::vector<Nearest> seen;
  const NearestTest record_and_refuse = [&](const Nearest& n) {
    seen.push_back(n);
    return n.distance > 0.25;
  };
  for (const std::array<double, 3>& p : {std::array<double, 3>{0.95, 0.95, 1.05}, {0.1, 0.05, 0.9}}) {
    const auto [id, change, n] = del.insert_tracking(p, false, 0, record_and_refuse);
    BOOST_TEST(!id.has_value());
    BOOST_TEST(change.destroyed_triangles.empty());
    BOOST_TEST(change.shrunk_triangles.empty());
  }
  BOOST_TEST(del.size() == size);
  BOOST_TEST((del.triangles() == triangles));
  BOOST_TEST_REQUIRE(seen.size() == 2u);
  BOOST_TEST(seen[0].id == 4);  // (1, 1, 1)
  BOOST_TEST(seen[1].id == 3);  // (0, 0, 1)
  // A point on a sample is refused with distance 0; one far enough is inserted.
  const auto on_sample = del.insert_tracking({1, 1, 1}, false, 2, record_and_refuse);
  BOOST_TEST(!on_sample.id.has_value());
  BOOST_TEST(on_sample.nearest.id == 4);
  BOOST_TEST(on_sample.nearest.distance == 0);
  const auto far = del.insert_tracking({0.5, 0.5, 0.5}, false, 0, record_and_refuse);
  BOOST_TEST(far.id.has_value());
  BOOST_TEST(far.nearest.id == 0);  // five samples at distance √3/2: the least id
  BOOST_TEST(del.size() == size + 1);
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

// The queries that walk the star of a vertex (neighbours, incident triangles and edges, closed
// star, is_edge, is_triangle, triangle_apexes, nearest) against the whole triangulation, listed
// facet by facet, and against a search over all samples.
BOOST_AUTO_TEST_CASE(star_queries_agree_with_the_whole_triangulation) {
  Delaunay del;
  std::vector<std::array<double, 3>> points;
  for (int k = 0; k < 50; ++k) {
    const double z = 1 - (2 * k + 1) / 50.0, r = std::sqrt(1 - z * z), phi = 2.399963 * k;
    const double s = k % 4 == 0 ? 0.5 : 1.0;
    points.push_back({s * r * std::cos(phi), s * r * std::sin(phi), s * z});
    BOOST_TEST_REQUIRE(del.insert(points.back(), false).has_value());
  }
  BOOST_TEST_REQUIRE(del.dimension() == 3);
  const auto triangles = del.triangles();
  std::set<EdgeKey> edges;
  for (const auto& t : triangles) {
    edges.insert({t[0], t[1]});
    edges.insert({t[0], t[2]});
    edges.insert({t[1], t[2]});
    BOOST_TEST(del.is_triangle(t));
    const auto apexes = del.triangle_apexes(t);
    BOOST_TEST_REQUIRE(apexes.has_value());
    for (VertexId a : *apexes) BOOST_TEST((std::find(t.begin(), t.end(), a) == t.end()));
  }
  for (VertexId v : del.vertices()) {
    std::vector<VertexId> neighbours;
    std::vector<TriangleKey> incident;
    for (const auto& e : edges)
      if (e[0] == v || e[1] == v) neighbours.push_back(e[0] == v ? e[1] : e[0]);
    std::sort(neighbours.begin(), neighbours.end());
    for (const auto& t : triangles)
      if (std::find(t.begin(), t.end(), v) != t.end()) incident.push_back(t);
    BOOST_TEST((del.neighbours(v) == neighbours));
    BOOST_TEST((del.incident_triangles(v) == incident));
    const auto star = del.closed_star(v);
    for (std::size_t i = 1; i < star.size(); ++i) BOOST_TEST((star[i - 1].key < star[i].key));
    for (const auto& s : star) {
      BOOST_TEST(std::binary_search(triangles.begin(), triangles.end(), s.key));
      BOOST_TEST(s.contains_vertex == (std::find(s.key.begin(), s.key.end(), v) != s.key.end()));
    }
    for (VertexId w : del.vertices())
      BOOST_TEST(del.is_edge(make_edge_key(v, w)) == (edges.count(make_edge_key(v, w)) > 0));
    BOOST_TEST(!del.is_edge({v, v}));
    BOOST_TEST(!del.is_triangle({v, v, neighbours.front()}));
    BOOST_TEST(!del.triangle_apexes({v, v, neighbours.front()}).has_value());
    BOOST_TEST(del.edge_ring({v, v}).empty());
  }
  // nearest(): a search over all samples, from four start hints (none, and three vertices).
  for (int k = 0; k < 40; ++k) {
    const std::array<double, 3> x{std::cos(1.7 * k) * 0.9, std::sin(2.3 * k) * 0.8, std::cos(0.9 * k) * 0.7};
    std::size_t best = 0;
    auto d2 = [&](std::size_t i) {
      double s = 0;
      for (int c = 0; c < 3; ++c) s += (points[i][c] - x[c]) * (points[i][c] - x[c]);
      return s;
    };
    for (std::size_t i = 1; i < points.size(); ++i)
      if (d2(i) < d2(best)) best = i;
    for (VertexId hint : {-1, 0, 17, 49}) {
      const auto [id, distance] = del.nearest(x, hint);
      BOOST_TEST(id == static_cast<VertexId>(best));
      BOOST_TEST(distance == std::sqrt(d2(best)), boost::test_tools::tolerance(1e-12));
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()
