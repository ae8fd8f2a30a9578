#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "check_fixture.h"
#include "common/errors.h"
#include "meshing/core/detail/vec3.h"
#include "meshing/voronoi/restricted_delaunay.h"
#include "sliver_fixture.h"

using namespace delmesh;
using delmesh::test::CheckFixture;

BOOST_AUTO_TEST_SUITE(restricted_delaunay)

// The §5.1 rule (restricted_delaunay.h): a Voronoi vertex on Σ.  Tetrahedron around the north pole v = (0,0,1) with its
// apex up: the three side edges leave v upwards (⟨u − v, n_v⟩ > 0) and meet Σ only at v, so their
// triangles are not in Tri S|Σ; the bottom edge goes down through the ball and is kept.
BOOST_AUTO_TEST_CASE(voronoi_vertex_on_the_surface_follows_section_5_1) {
  const double r = 0.3, s = std::sqrt(8.0) / 3, t = std::sqrt(2.0) / 3;
  CheckFixture f(test::unit_sphere, 1.5,
                 {{0, 0, 1 + r}, {r * s, 0, 1 - r / 3}, {-r * t, r * std::sqrt(2.0 / 3), 1 - r / 3},
                  {-r * t, -r * std::sqrt(2.0 / 3), 1 - r / 3}});
  int kept = 0, excluded = 0;
  for (const auto& tri : f.del.triangles()) {
    const auto& rec = f.restricted.voronoi_edge_record(tri);
    const bool bottom = tri == TriangleKey{1, 2, 3};
    if (bottom) {
      BOOST_TEST(rec.restricted);
      ++kept;
    } else {
      // The zero at v is found at v (a §5.1 vertex zero) or, the constructed vertex being
      // rounded to just outside Σ, not at all: either way the triangle is not restricted.
      BOOST_TEST(!rec.restricted);
      BOOST_TEST(rec.crossings().size() <= 1u);
      ++excluded;
    }
  }
  BOOST_TEST(kept == 1);
  BOOST_TEST(excluded == 3);
}

// The octahedron on the sphere: Tri S|Σ is the octahedron's 8 faces; records are cached and
// forgotten on invalidate().
BOOST_AUTO_TEST_CASE(octahedron_is_its_own_restricted_triangulation) {
  CheckFixture f(test::unit_sphere, 1.5, {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}});
  BOOST_TEST(f.restricted.triangles().size() == 8u);
  const auto calls = f.oracle.statistics("surface_line").calls;
  (void)f.restricted.triangles();
  BOOST_TEST(f.oracle.statistics("surface_line").calls == calls);  // cached
  f.restricted.invalidate({0, 2, 4});
  (void)f.restricted.triangles();
  BOOST_TEST(f.oracle.statistics("surface_line").calls == calls + 1);
}

// A record's lists come back as they were set, in order, through copies and moves; empty lists
// leave no block; lists whose ranges do not match are refused.
BOOST_AUTO_TEST_CASE(record_lists_round_trip) {
  VoronoiEdgeLists lists;
  lists.unresolved = {{9, 9, 9}};
  lists.crossings = {{1, 2, 3}, {4, 5, 6}};
  lists.crossing_range = {{0.1, 0.2}, {0.3, 0.4}};
  lists.candidates = {{7, 8, 9}};
  lists.candidate_range = {{0.5, 0.6}};
  VoronoiEdgeRecord record;
  record.set_lists(lists);
  const VoronoiEdgeRecord copy = record;
  VoronoiEdgeRecord assigned;
  assigned = copy;
  const VoronoiEdgeRecord moved = std::move(record);
  for (const VoronoiEdgeRecord* r : std::initializer_list<const VoronoiEdgeRecord*>{&copy, &assigned, &moved}) {
    BOOST_TEST_REQUIRE(r->unresolved().size() == 1u);
    BOOST_TEST(r->unresolved()[0] == (Vec3{9, 9, 9}));
    BOOST_TEST_REQUIRE(r->crossings().size() == 2u);
    BOOST_TEST(r->crossings()[1] == (Vec3{4, 5, 6}));
    BOOST_TEST_REQUIRE(r->crossing_range().size() == 2u);
    BOOST_TEST(r->crossing_range()[1][0] == 0.3);
    BOOST_TEST(r->crossing_range()[1][1] == 0.4);
    BOOST_TEST_REQUIRE(r->candidates().size() == 1u);
    BOOST_TEST(r->candidates().front() == (Vec3{7, 8, 9}));
    BOOST_TEST(r->candidate_range()[0][1] == 0.6);
  }
  assigned.set_lists(VoronoiEdgeLists{});
  BOOST_TEST(assigned.crossings().empty());
  BOOST_TEST(assigned.unresolved().empty());
  lists.crossing_range.pop_back();
  BOOST_CHECK_THROW(assigned.set_lists(lists), PreconditionViolation);
}

// restricted_pair(e) is star(e[0]) filtered to the triangles containing e, when there are two: on
// the octahedron every edge lies in exactly two faces, and a diagonal of it lies in none.
BOOST_AUTO_TEST_CASE(restricted_pair_is_the_filtered_star) {
  CheckFixture f(test::unit_sphere, 1.5, {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}});
  const auto faces = f.restricted.triangles();
  for (bool recorded : {false, true}) {
    if (recorded) f.restricted.assume_every_triangle_recorded();
    int edges = 0;
    for (VertexId p = 0; p < 6; ++p)
      for (VertexId q = p + 1; q < 6; ++q) {
        std::vector<TriangleKey> filtered;
        for (const auto& t : f.restricted.star(p))
          if (std::find(t.begin(), t.end(), q) != t.end()) filtered.push_back(t);
        const auto pair = f.restricted.restricted_pair({p, q});
        if (filtered.size() != 2) {
          BOOST_TEST(!pair.has_value());
          continue;
        }
        ++edges;
        BOOST_REQUIRE(pair.has_value());
        BOOST_TEST((*pair)[0] == filtered[0]);
        BOOST_TEST((*pair)[1] == filtered[1]);
      }
    BOOST_TEST(edges == 12);  // the octahedron's edges; its three diagonals have no face
  }
  BOOST_TEST(faces.size() == 8u);
}

// star_unordered(p) holds the triangles of star(p), in some order, with and without kept stars:
// on the octahedron the four faces at each vertex.
BOOST_AUTO_TEST_CASE(unordered_star_has_the_triangles_of_the_star) {
  CheckFixture f(test::unit_sphere, 1.5, {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}});
  (void)f.restricted.triangles();  // every record computed, so the kept stars are complete
  for (bool recorded : {false, true}) {
    if (recorded) f.restricted.assume_every_triangle_recorded();
    for (VertexId p = 0; p < 6; ++p) {
      const auto sorted = f.restricted.star(p);
      auto unordered = f.restricted.star_unordered(p);
      std::sort(unordered.begin(), unordered.end());
      BOOST_TEST(sorted.size() == 4u);
      BOOST_TEST(unordered == sorted);
    }
  }
}

// An insertion shrinks the dual edges of its cavity's boundary; their records are restricted from
// the old ones (no SurfaceLine solve) and agree with records solved from scratch.
BOOST_AUTO_TEST_CASE(shrunk_records_equal_solved_records) {
  CheckFixture f(test::unit_sphere, 1.5, {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}});
  (void)f.restricted.triangles();
  const auto [x, change, nearest] = f.del.insert_tracking({0.6, 0.6, 0.5291502622129181}, false);
  BOOST_TEST_REQUIRE(x.has_value());
  BOOST_TEST_REQUIRE(change.local);
  BOOST_TEST_REQUIRE(!change.shrunk_triangles.empty());
  f.restricted.shrink(change);
  const auto restricted_before = f.restricted.records_restricted();
  std::vector<VoronoiEdgeRecord> kept;
  for (const auto& t : change.shrunk_triangles) kept.push_back(f.restricted.voronoi_edge_record(t));
  BOOST_TEST(f.restricted.records_restricted() > restricted_before);
  RestrictedDelaunay fresh(f.del, f.oracle, 1);
  for (std::size_t i = 0; i < kept.size(); ++i) {
    const auto& solved = fresh.voronoi_edge_record(change.shrunk_triangles[i]);
    BOOST_TEST(kept[i].restricted == solved.restricted);
    BOOST_TEST(kept[i].crossings().size() == solved.crossings().size());
    for (std::size_t k = 0; k < std::min(kept[i].crossings().size(), solved.crossings().size()); ++k)
      for (int c = 0; c < 3; ++c) BOOST_TEST(std::abs(kept[i].crossings()[k][c] - solved.crossings()[k][c]) < 1e-12);
  }
}

// A facet that shrinks keeps a proved section certificate (the proof over F holds over F′ ⊆ F) and
// loses its geometry; a certificate that failed is forgotten, to be tried on the smaller facet.
BOOST_AUTO_TEST_CASE(a_shrunk_facet_keeps_a_proved_section_certificate) {
  CheckFixture f(test::unit_sphere, 1.5, {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}});
  std::map<EdgeKey, bool> before;
  for (VertexId p : f.del.vertices())
    for (VertexId q : f.del.neighbours(p))
      if (p < q) before[make_edge_key(p, q)] = f.restricted.facet_section_certified(make_edge_key(p, q));
  const auto [x, change, nearest] = f.del.insert_tracking({0.6, 0.6, 0.5291502622129181}, false);
  BOOST_TEST_REQUIRE(x.has_value());
  BOOST_TEST_REQUIRE(change.local);
  f.restricted.shrink(change);
  const auto attempts = [&] { return f.oracle.statistics_json()["cone_certificates"]["attempts"].get<std::size_t>(); };
  const std::size_t attempts_before = attempts(), built_before = f.restricted.facets_built();
  int kept = 0;
  for (const auto& e : change.shrunk_edges) {
    BOOST_TEST_REQUIRE(before.count(e) == 1u);
    BOOST_TEST(f.restricted.has_facet(e) == before[e]);
    if (!before[e]) continue;
    ++kept;
    BOOST_TEST(f.restricted.facet_section_certified(e));
  }
  BOOST_TEST(kept > 0);
  BOOST_TEST(attempts() == attempts_before);            // no cover tried again
  BOOST_TEST(f.restricted.facets_built() == built_before);  // no geometry rebuilt
  for (const auto& e : change.destroyed_edges) BOOST_TEST(!f.restricted.has_facet(e));
}

// add_facets() enters the facets of new edges without building or certifying anything; each
// facet's section certificate is made when first asked, and is the one a fresh table makes.
BOOST_AUTO_TEST_CASE(added_facets_are_certified_when_first_asked) {
  CheckFixture f(test::unit_sphere, 1.5, {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}});
  std::vector<EdgeKey> edges;
  for (VertexId p : f.del.vertices())
    for (VertexId q : f.del.neighbours(p))
      if (p < q) edges.push_back(make_edge_key(p, q));
  BOOST_TEST_REQUIRE(edges.size() >= 12u);  // the octahedron's, and a diagonal inside it
  const auto attempts = [&] { return f.oracle.statistics_json()["cone_certificates"]["attempts"].get<std::size_t>(); };
  const std::size_t attempts_before = attempts(), built_before = f.restricted.facets_built();
  f.restricted.add_facets(edges);
  for (const auto& e : edges) BOOST_TEST(f.restricted.has_facet(e));
  BOOST_TEST(attempts() == attempts_before);
  BOOST_TEST(f.restricted.facets_built() == built_before);
  std::vector<bool> certified;
  for (const auto& e : edges) certified.push_back(f.restricted.facet_section_certified(e));
  BOOST_TEST(attempts() > attempts_before);  // the covers were made when asked for
  RestrictedDelaunay fresh(f.del, f.oracle, 1);
  for (std::size_t i = 0; i < edges.size(); ++i) BOOST_TEST(certified[i] == fresh.facet_section_certified(edges[i]));
}

// The facet of e is certified from the cells alone: no cone attempt, one more facet counted as
// certified by cell, and no facet geometry built.
static void check_facet_follows_from_cells(CheckFixture& f, const EdgeKey& e) {
  const auto attempts = [&] { return f.oracle.statistics_json()["cone_certificates"]["attempts"].get<std::size_t>(); };
  const std::size_t attempts_before = attempts(), by_cell_before = f.restricted.facets_certified_by_cell(),
                    built_before = f.restricted.facets_built();
  BOOST_TEST(f.restricted.facet_section_certified(e));
  BOOST_TEST(attempts() == attempts_before);
  BOOST_TEST(f.restricted.facets_certified_by_cell() == by_cell_before + 1);
  BOOST_TEST(f.restricted.facets_built() == built_before);
}

// A facet across Σ follows from a certified cell whose box around Σ ∩ V_p its plane misses.  On
// the flat ellipsoid x² + y² + 100 z² = 1 (two sheets 0.2 apart), p and q are the poles and six
// samples surround each.  The facet of pq lies in the plane z = 0, between the sheets, while
// Σ ∩ V_p is a small cap at z ≈ 0.1; q − p is along n_p, so no slope could certify it.
BOOST_AUTO_TEST_CASE(a_facet_off_the_cells_surface_box_follows_from_the_cell) {
  std::vector<Vec3> points{{0, 0, 0.1}, {0, 0, -0.1}};
  const double radius = 0.2, height = 0.1 * std::sqrt(1 - radius * radius);
  for (int k = 0; k < 6; ++k) {
    const double phi = k * M_PI / 3;
    points.push_back({radius * std::cos(phi), radius * std::sin(phi), height});
    points.push_back({radius * std::cos(phi + 0.5), radius * std::sin(phi + 0.5), -height});
  }
  CheckFixture f("x^2+y^2+100*z^2-1", 1.5, points);
  const EdgeKey pq = make_edge_key(0, 1);
  const auto around_p = f.del.neighbours(0);
  BOOST_TEST_REQUIRE(std::count(around_p.begin(), around_p.end(), 1) == 1);
  BOOST_TEST_REQUIRE(f.restricted.cell_certified(0));
  check_facet_follows_from_cells(f, pq);
}

// A facet across Σ follows from the signs of two certified cells, where no slope could certify
// it.  On the octahedron inscribed in the unit sphere, p = (1, 0, 0) and q = (0, 1, 0): ⟨∇E, n_p⟩ =
// 2x > 0 on Σ ∩ V_p and ⟨∇E, n_q⟩ = 2y > 0 on Σ ∩ V_q, while q − p has ⟨q − p, n_p⟩ = −1 and
// ⟨q − p, n_q⟩ = +1.  A slope of V_p would have to exceed |⟨n_p, q − p⟩| / |q − p| = 1/√2, but the
// true slope on Σ ∩ V_p is min x = 1/√3; and the plane x = y of the facet meets Σ ∩ V_p.
BOOST_AUTO_TEST_CASE(a_facet_across_a_chord_follows_from_the_signs_of_both_cells) {
  CheckFixture f(test::unit_sphere, 1.5, {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}});
  const EdgeKey pq = make_edge_key(0, 2);
  const auto around_p = f.del.neighbours(0);
  BOOST_TEST_REQUIRE(std::count(around_p.begin(), around_p.end(), 2) == 1);
  BOOST_TEST_REQUIRE(f.restricted.cell_certified(0));
  BOOST_TEST_REQUIRE(f.restricted.cell_certified(2));
  check_facet_follows_from_cells(f, pq);
}

// A kept cell proof whose cell may have grown (a neighbour removed) is completed on the grown
// part only: on the octahedron, V_p of the north pole is proved, then said to have grown into a
// box about the centre, which Σ misses: the proof stands after fewer boxes than the whole cell
// took.
BOOST_AUTO_TEST_CASE(a_grown_cell_proof_is_completed_on_the_grown_part) {
  CheckFixture f(test::unit_sphere, 1.5, {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}});
  const VertexId pole = 4;
  const auto boxes = [&] { return f.oracle.statistics_json()["cone_certificates"]["boxes"].get<std::size_t>(); };
  std::size_t before = boxes();
  BOOST_TEST_REQUIRE(f.restricted.cell_certified(pole));
  const std::size_t whole = boxes() - before;
  auto around = f.del.neighbours(pole);
  std::sort(around.begin(), around.end());
  around.push_back(pole);
  std::sort(around.begin(), around.end());
  const Domain centre = Domain::from_box({{-0.2, 0.2}, {-0.2, 0.2}, {-0.2, 0.2}});
  f.restricted.invalidate(around, &centre);
  BOOST_TEST(!f.restricted.cell_silhouette_point(pole).has_value());
  before = boxes();
  BOOST_TEST(f.restricted.cell_certified(pole));
  const std::size_t part = boxes() - before;
  BOOST_TEST(part >= 1u);
  BOOST_TEST(part < whole);
  // Proved again on all of V_p: nothing more to do.
  before = boxes();
  BOOST_TEST(f.restricted.cell_certified(pole));
  BOOST_TEST(boxes() == before);
}

BOOST_AUTO_TEST_CASE(seeded_uniform_is_deterministic_and_in_range) {
  BOOST_TEST(seeded_uniform(3, 1, 2, 3) == seeded_uniform(3, 1, 2, 3));
  BOOST_TEST(seeded_uniform(3, 1, 2, 3) != seeded_uniform(4, 1, 2, 3));
  for (int k = 0; k < 100; ++k) {
    const double u = seeded_uniform(1, k);
    BOOST_TEST((u >= 0 && u < 1));
  }
}

// A tetrahedron inscribed in the sphere of radius 5/8 about c = (1 − δ, 0, 0), with dyadic
// coordinates so that every construction is exact: the face {0, 1, 2} lies in the plane
// x = 11/8 − δ, and its Voronoi edge is the ray from the Voronoi vertex v = c in direction +x,
// leaving the unit ball.
std::vector<Vec3> tetrahedron_about(double delta) {
  const double x = 1.375 - delta;
  return {{x, 0.5, 0}, {x, -0.5, 0}, {x, 0, 0.5}, {0.375 - delta, 0, 0}};
}

// The finite end of a Voronoi ray.
Vec3 voronoi_vertex(const VoronoiEdge& e) { return e.at(e.at_vertex0 ? e.t0 : e.t1); }

// δ = 0: E(v) = 0 exactly.  The zero at v is the §5.1 case, settled by a proved sign of
// ⟨∇E, u − v⟩ > 0: the face is excluded and nothing is left unresolved.
BOOST_AUTO_TEST_CASE(exact_vertex_zero_is_excluded_by_a_proved_sign) {
  CheckFixture f(test::unit_sphere, 1.6, tetrahedron_about(0));
  const auto& rec = f.restricted.voronoi_edge_record({0, 1, 2});
  const VoronoiEdge edge = rec.edge(f.del, {0, 1, 2});
  BOOST_TEST_REQUIRE(edge.at_vertex0 != edge.at_vertex1);
  BOOST_TEST_REQUIRE(detail::distance(voronoi_vertex(edge), {1, 0, 0}) == 0.0);
  BOOST_TEST(!rec.restricted);
  BOOST_TEST(rec.unresolved().empty());
  BOOST_TEST_REQUIRE(rec.crossings().size() == 1u);
  BOOST_TEST(detail::distance(rec.crossings()[0], {1, 0, 0}) == 0.0);
}

// δ = 2⁻³³: v lies inside the ball, and Σ crosses the ray δ from v — within the Voronoi-vertex
// tolerance, but E(v) < 0 is proved, so it is a true crossing: the face is in Tri S|Σ (taken for
// a zero at v, it would be excluded).
BOOST_AUTO_TEST_CASE(crossing_next_to_a_vertex_is_not_collapsed_onto_it) {
  const double delta = std::ldexp(1.0, -33);
  CheckFixture f(test::unit_sphere, 1.6, tetrahedron_about(delta));
  const auto& rec = f.restricted.voronoi_edge_record({0, 1, 2});
  BOOST_TEST_REQUIRE(detail::distance(voronoi_vertex(rec.edge(f.del, {0, 1, 2})), {1 - delta, 0, 0}) == 0.0);
  BOOST_TEST(rec.restricted);
  BOOST_TEST(rec.unresolved().empty());
  BOOST_TEST_REQUIRE(rec.crossings().size() == 1u);
  BOOST_TEST(std::abs(f.oracle.E(rec.crossings()[0])) < 1e-15);
  BOOST_TEST(rec.crossings()[0][0] > 1 - delta / 2);
}

// facet_misses_surface() against the facets themselves: on points near the unit sphere, every
// facet it clears has E of one sign at its polygon's vertices and on a grid inside it (a facet
// with a sign change is never cleared), and it clears some facets: those deep inside the ball,
// and some that reach the box's boundary (their vertices on ∂B are points of Π ∩ ∂B).
BOOST_AUTO_TEST_CASE(facet_missing_surface_is_claimed_only_off_the_surface) {
  std::vector<Vec3> points;
  const int n = 80;
  for (int i = 0; i < n; ++i) {  // a Fibonacci sphere, radii jittered (cospherical points are degenerate)
    const double z = 1 - (2 * i + 1.0) / n, r = std::sqrt(1 - z * z), phi = i * 2.399963229728653;
    const double rho = 1 + 0.05 * (seeded_uniform(7, i) - 0.5);
    points.push_back({rho * r * std::cos(phi), rho * r * std::sin(phi), rho * z});
  }
  CheckFixture f(test::unit_sphere, 1.5, points);
  int cleared = 0, kept = 0, cleared_reaching_box = 0;
  for (VertexId p = 0; p < n; ++p)
    for (VertexId q : f.del.neighbours(p)) {
      if (q < p) continue;
      const auto ring = f.del.edge_ring({p, q});
      std::vector<const VoronoiEdgeRecord*> boundary;
      for (const auto& t : ring) boundary.push_back(&f.restricted.voronoi_edge_record(make_triangle_key(p, q, t.third)));
      const bool misses = f.restricted.facet_misses_surface({p, q}, ring, boundary);
      const VoronoiFacet facet = voronoi_facet(f.del, {p, q}, f.box, 0.0);
      if (misses) ++cleared;
      if (!facet.valid) continue;  // F ∩ B is empty (a facet of two hull points, outside B)
      int positive = 0, negative = 0;
      auto sample = [&](double u, double v) { (f.oracle.E(facet.world(u, v)) > 0 ? positive : negative)++; };
      const auto& poly = facet.polygon;
      for (const auto& w : poly) sample(w[0], w[1]);
      for (std::size_t i = 0; i < poly.size(); ++i)  // fans of the polygon from its first vertex
        for (int a = 1; a < 8; ++a)
          for (int b = 1; a + b < 8; ++b) {
            const auto& w0 = poly[0];
            const auto& w1 = poly[i];
            const auto& w2 = poly[(i + 1) % poly.size()];
            const double s = a / 8.0, t = b / 8.0;
            sample(w0[0] + s * (w1[0] - w0[0]) + t * (w2[0] - w0[0]), w0[1] + s * (w1[1] - w0[1]) + t * (w2[1] - w0[1]));
          }
      if (misses)
        BOOST_TEST((positive == 0 || negative == 0));
      else
        ++kept;
      const bool reaches_box = std::any_of(poly.begin(), poly.end(), [&](const auto& w) {
        const Vec3 x = facet.world(w[0], w[1]);
        return std::any_of(x.begin(), x.end(), [](double c) { return std::abs(std::abs(c) - 1.5) < 1e-9; });
      });
      if (misses && reaches_box) ++cleared_reaching_box;
    }
  BOOST_TEST(cleared > 0);
  BOOST_TEST(cleared_reaching_box > 0);
  BOOST_TEST(kept > 0);
  BOOST_TEST(f.restricted.facets_missing_surface() == static_cast<std::size_t>(cleared));
}

// A Voronoi edge of a sliver, with Σ a plane between the edge's line and the circumcentre by
// the formula in doubles v′, which lies off that line by several times the membership margin: E
// has one sign on the whole segment and the other at v′.  Were v′ the Voronoi vertex shared with
// the other faces at it, the edge as they see it would cross Σ on the connector from v′ to the
// line, which SurfaceLine never searches.  The record's crossings have the parity of the change of
// sign of E between the edge's shared ends (voronoi_edge_ends()).
BOOST_AUTO_TEST_CASE(a_plane_between_a_sliver_vertex_and_its_edge_keeps_the_crossing_parity) {
  using namespace delmesh::detail;
  const std::vector<Vec3> points = test::sliver_points();
  const std::vector<Vec3> four(points.begin(), points.begin() + 4);
  const Vec3 formula = test::formula_circumcentre(four);
  const Box3 box = Box3::cube(test::sliver_half_width);
  Delaunay del;
  for (const Vec3& p : points) del.insert(p, false);
  // The triangle of the sliver whose line is farthest from v′, and the foot a of v′ on it.
  TriangleKey best{};
  double best_offset = 0;
  Vec3 foot{};
  for (const TriangleKey t : std::vector<TriangleKey>{{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}}) {
    BOOST_TEST_REQUIRE(del.triangle_apexes(t).has_value());
    const VoronoiEdge e = voronoi_edge(del, t, box);
    BOOST_TEST_REQUIRE(e.valid);
    const Vec3 a = e.at(dot(formula - e.point, e.direction));
    if (distance(formula, a) > best_offset) best = t, best_offset = distance(formula, a), foot = a;
  }
  const double margin = tolerances::face_membership_relative_tolerance * box.diagonal();
  BOOST_TEST_REQUIRE(best_offset > 2 * margin);
  const VoronoiEdge e = voronoi_edge(del, best, box);
  // The plane ⟨m, x⟩ = ⟨m, (v′ + a)/2⟩ with m the part of v′ − a orthogonal to the line.
  Vec3 m = formula - foot;
  m = m - dot(m, e.direction) * e.direction;
  m = (1.0 / norm(m)) * m;
  const Vec3 mid = 0.5 * (formula + foot);
  char equation[256];
  std::snprintf(equation, sizeof equation, "(%.17g)*x+(%.17g)*y+(%.17g)*z-(%.17g)", m[0], m[1], m[2], dot(m, mid));
  CheckFixture f(equation, test::sliver_half_width, points);
  BOOST_TEST_REQUIRE(f.oracle.value_sign(foot) == -f.oracle.value_sign(formula));
  const auto& record = f.restricted.voronoi_edge_record(best);
  const VoronoiEdge edge = record.edge(f.del, best);
  BOOST_TEST_REQUIRE(edge.valid);
  // The record keeps the edge's extent; its line is the triangle's, as voronoi_edge() builds it.
  const VoronoiEdge built = voronoi_edge(f.del, best, f.oracle.clip_box());
  BOOST_TEST(edge.point == built.point);
  BOOST_TEST(edge.direction == built.direction);
  BOOST_TEST(edge.t0 == built.t0);
  BOOST_TEST(edge.t1 == built.t1);
  const auto ends = voronoi_edge_ends(f.del, edge);
  const int s0 = f.oracle.value_sign(ends[0]), s1 = f.oracle.value_sign(ends[1]);
  BOOST_TEST_REQUIRE(s0 * s1 != 0);
  BOOST_TEST(record.crossings().size() % 2 == (s0 != s1 ? 1u : 0u));
  BOOST_TEST(record.restricted == (s0 != s1));
}

BOOST_AUTO_TEST_SUITE_END()
