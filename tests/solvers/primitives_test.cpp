#include "solvers/primitives.h"

#include <array>
#include <random>
#include <string>
#include <vector>

#include <boost/test/unit_test.hpp>

#include "common/errors.h"
#include "solvers/primitive_registry.h"
#include "symbolic/catalog.h"

using namespace delmesh;

namespace {

using Vec = std::array<GiNaC::numeric, 3>;

bool vanishes(const GiNaC::ex& e) { return e.expand().normal().is_zero(); }

//! Substitutes the system's parameters by the given exact values (in the order of the table).
GiNaC::exmap parameter_map(const PrimitiveSystem& s, const std::vector<Vec>& vectors) {
  GiNaC::exmap m;
  std::size_t k = 0;
  for (const Vec& v : vectors)
    for (const GiNaC::numeric& c : v) m[s.parameters.at(k++)] = c;
  BOOST_REQUIRE(k == s.n_parameters());
  return m;
}

GiNaC::exmap with_unknowns(GiNaC::exmap m, const PrimitiveSystem& s, const std::vector<GiNaC::numeric>& u) {
  BOOST_REQUIRE(u.size() == s.n_unknowns());
  for (std::size_t j = 0; j < u.size(); ++j) m[s.unknowns[j]] = u[j];
  return m;
}

//! Every equation of s vanishes at the substitution m.
bool all_vanish(const PrimitiveSystem& s, const GiNaC::exmap& m) {
  for (const GiNaC::ex& e : s.equations)
    if (!vanishes(e.subs(m))) return false;
  return true;
}

//! An exactly unit rational vector (2a, 2b, 1 - a^2 - b^2) / (1 + a^2 + b^2) for random rational a, b.
Vec random_unit(std::mt19937& rng) {
  std::uniform_int_distribution<int> k(-20, 20);
  const GiNaC::numeric a(k(rng), 7), b(k(rng), 9);
  const GiNaC::numeric n = 1 + a * a + b * b;
  return {2 * a / n, 2 * b / n, (1 - a * a - b * b) / n};
}

Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Vec scaled(const Vec& a, const GiNaC::numeric& s) { return {a[0] * s, a[1] * s, a[2] * s}; }
//! A non-zero vector ⟂ d (not normalised).
Vec perpendicular(const Vec& d) {
  const Vec e = (d[0] == 0 && d[1] == 0) ? Vec{1, 0, 0} : Vec{0, 0, 1};
  return cross(d, e);
}

const Vec ex_{1, 0, 0}, ey_{0, 1, 0}, ez_{0, 0, 1}, zero_{0, 0, 0};

std::vector<std::string> parameter_names(const PrimitiveSystem& s) {
  std::vector<std::string> names;
  for (const GiNaC::symbol& p : s.parameters) names.push_back(p.get_name());
  return names;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(primitives)

BOOST_AUTO_TEST_CASE(the_six_primitives_follow_the_table_of_primitives_h) {
  struct Shape {
    std::string name;
    std::size_t unknowns, equations;
    std::vector<std::string> parameters;
  };
  const std::vector<Shape> table = {
      {"surface_critical", 3, 3, {"a0", "a1", "a2", "b0", "b1", "b2"}},
      {"surface_line", 1, 1, {"p0", "p1", "p2", "v0", "v1", "v2"}},
      {"surface_plane_contact", 2, 3, {"o0", "o1", "o2", "a0", "a1", "a2", "b0", "b1", "b2"}},
      {"curve_critical", 2, 2, {"o0", "o1", "o2", "a0", "a1", "a2", "b0", "b1", "b2"}},
      {"silhouette_plane", 2, 2, {"o0", "o1", "o2", "a0", "a1", "a2", "b0", "b1", "b2", "d0", "d1", "d2"}},
      {"silhouette_critical", 3, 3, {"d0", "d1", "d2", "e0", "e1", "e2"}},
  };
  // The built-in rows are the paper's six, in the paper's order; the registry starts with them.
  BOOST_REQUIRE(builtin_primitives().size() == table.size());
  const Surface torus = catalog_entry("torus").surface();
  for (std::size_t i = 0; i < table.size(); ++i) {
    BOOST_TEST_CONTEXT(table[i].name) {
      BOOST_TEST(builtin_primitives()[i].name == table[i].name);
      BOOST_TEST(primitive_registry().at(i).name == table[i].name);
      const PrimitiveSystem s = build_primitive(table[i].name, torus);
      BOOST_TEST(s.name == table[i].name);
      BOOST_TEST(s.n_unknowns() == table[i].unknowns);
      BOOST_TEST(s.n_equations() == table[i].equations);
      BOOST_TEST(s.is_square() == (table[i].name != "surface_plane_contact"));
      BOOST_TEST(parameter_names(s) == table[i].parameters, boost::test_tools::per_element());
    }
  }
}

BOOST_AUTO_TEST_CASE(unknown_primitive_throws_and_lists_the_names) {
  const Surface sphere = catalog_entry("sphere").surface();
  try {
    (void)build_primitive("surface_lines", sphere);
    BOOST_FAIL("no exception");
  } catch (const InvalidInput& error) {
    const std::string message = error.what();
    BOOST_TEST(message.find("'surface_lines'") != std::string::npos);
    for (const PrimitiveInfo& info : primitive_registry()) BOOST_TEST(message.find(info.name) != std::string::npos);
  }
}

BOOST_AUTO_TEST_CASE(jacobians_and_plane_derivatives_are_consistent) {
  // For every polynomial catalog surface and every registered primitive: Jacobian entries (derived
  // by the registry, not by the builder) are the derivatives of the equations, the first equation
  // is E at the world point, and in the plane systems ⟨∇E, a⟩ and ⟨∇E, b⟩ are ∂u and ∂v of
  // E(o + u a + v b) (chain rule).
  for (const char* name : {"torus", "chair", "near_sheets"}) {
    const Surface surface = catalog_entry(name).surface();
    for (const PrimitiveInfo& info : primitive_registry()) {
      const PrimitiveSystem s = info.build(surface);
      BOOST_TEST_CONTEXT(name << "/" << info.name) {
        BOOST_TEST(s.name == info.name);
        for (std::size_t i = 0; i < s.n_equations(); ++i)
          for (std::size_t j = 0; j < s.n_unknowns(); ++j)
            BOOST_TEST(vanishes(s.jacobian(i, j) - s.equations[i].diff(s.unknowns[j])));
        const GiNaC::lst to_world{coordinate_x() == s.world_point[0], coordinate_y() == s.world_point[1],
                                  coordinate_z() == s.world_point[2]};
        BOOST_TEST(vanishes(s.equations[0] - surface.E().subs(to_world)));
        if (info.name == "surface_plane_contact") {
          BOOST_TEST(vanishes(s.equations[1] - s.equations[0].diff(s.unknowns[0])));
          BOOST_TEST(vanishes(s.equations[2] - s.equations[0].diff(s.unknowns[1])));
        }
        if (info.name == "curve_critical") BOOST_TEST(vanishes(s.equations[1] - s.equations[0].diff(s.unknowns[1])));
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(silhouette_critical_matches_direct_derivation) {
  // G = ⟨∇E, d⟩ differentiated directly (not through the Hessian) for a non-polynomial surface.
  const Surface metaball = catalog_entry("metaball").surface();
  const PrimitiveSystem s = silhouette_critical_system(metaball);
  const std::array<GiNaC::ex, 3> d{s.parameters[0], s.parameters[1], s.parameters[2]};
  const std::array<GiNaC::ex, 3> e{s.parameters[3], s.parameters[4], s.parameters[5]};
  const auto& g = metaball.gradient();
  const GiNaC::ex G = g[0] * d[0] + g[1] * d[1] + g[2] * d[2];
  std::array<GiNaC::ex, 3> gG{G.diff(coordinate_x()), G.diff(coordinate_y()), G.diff(coordinate_z())};
  const GiNaC::ex third = (gG[1] * g[2] - gG[2] * g[1]) * e[0] + (gG[2] * g[0] - gG[0] * g[2]) * e[1] +
                          (gG[0] * g[1] - gG[1] * g[0]) * e[2];
  BOOST_TEST(vanishes(s.equations[0] - metaball.E()));
  BOOST_TEST(vanishes(s.equations[1] - G));
  BOOST_TEST(vanishes(s.equations[2] - third));
}

BOOST_AUTO_TEST_CASE(sphere_critical_points_are_plus_minus_d) {
  const Surface sphere = catalog_entry("sphere").surface();
  const PrimitiveSystem s = surface_critical_system(sphere);
  std::mt19937 rng(7);
  for (int trial = 0; trial < 8; ++trial) {
    const Vec d = random_unit(rng);
    const Vec a = perpendicular(d), b = cross(d, a);
    const GiNaC::exmap params = parameter_map(s, {a, b});
    BOOST_TEST(all_vanish(s, with_unknowns(params, s, {d[0], d[1], d[2]})));
    BOOST_TEST(all_vanish(s, with_unknowns(params, s, {-d[0], -d[1], -d[2]})));
    // A point of the sphere that is not ±d is not critical in direction d.
    BOOST_TEST(!all_vanish(s, with_unknowns(params, s, {a[0], a[1], a[2]})));
    // Non-degenerate root: the Jacobian is invertible at d.
    const GiNaC::matrix J = GiNaC::ex_to<GiNaC::matrix>(s.jacobian.subs(with_unknowns(params, s, {d[0], d[1], d[2]})));
    BOOST_TEST(!J.determinant().is_zero());
  }
}

BOOST_AUTO_TEST_CASE(line_through_the_sphere_centre_meets_it_at_unit_distance) {
  const Surface sphere = catalog_entry("sphere").surface();
  const PrimitiveSystem s = surface_line_system(sphere);
  const GiNaC::ex t = s.unknowns[0];
  std::mt19937 rng(11);
  for (int trial = 0; trial < 8; ++trial) {
    const Vec v = random_unit(rng);
    const GiNaC::exmap m = parameter_map(s, {zero_, v});
    BOOST_TEST(vanishes(s.equations[0].subs(m) - (t * t - 1)));
    BOOST_TEST(vanishes(s.jacobian(0, 0).subs(m) - 2 * t));
    for (int sign : {-1, 1}) {
      const GiNaC::exmap at = with_unknowns(m, s, {GiNaC::numeric(sign)});
      BOOST_TEST(all_vanish(s, at));
      for (unsigned i = 0; i < 3; ++i) BOOST_TEST(vanishes(s.world_point[i].subs(at) - sign * v[i]));
    }
  }
  // A line tangent to the sphere at e_z: p = e_z + 5 e_x, v = e_x has the double root t = -5.
  const GiNaC::exmap tangent = parameter_map(s, {Vec{5, 0, 1}, ex_});
  BOOST_TEST(vanishes(s.equations[0].subs(tangent) - GiNaC::pow(t + 5, 2)));
}

BOOST_AUTO_TEST_CASE(torus_plane_systems) {
  const Surface torus = catalog_entry("torus").surface();  // R = 1, r = 2/5, axis z
  const GiNaC::numeric r(2, 5), three5(3, 5), four5(4, 5);

  // The plane z = r touches the torus along its top circle ρ = 1: every point of that circle is a
  // tangential contact; a point of the plane off the circle is not on Σ.
  const PrimitiveSystem contact = surface_plane_contact_system(torus);
  const GiNaC::exmap top = parameter_map(contact, {Vec{0, 0, r}, ex_, ey_});
  for (const auto& uv : std::vector<std::array<GiNaC::numeric, 2>>{{1, 0}, {three5, four5}, {-four5, three5}})
    BOOST_TEST(all_vanish(contact, with_unknowns(top, contact, {uv[0], uv[1]})));
  BOOST_TEST(!all_vanish(contact, with_unknowns(top, contact, {GiNaC::numeric(11, 10), 0})));
  // The plane z = 0 cuts the torus transversally: no tangential contact at its section circles.
  const GiNaC::exmap equator = parameter_map(contact, {zero_, ex_, ey_});
  BOOST_TEST(!all_vanish(contact, with_unknowns(equator, contact, {GiNaC::numeric(7, 5), 0})));
  BOOST_TEST(vanishes(contact.equations[0].subs(with_unknowns(equator, contact, {GiNaC::numeric(7, 5), 0}))));

  // In the plane z = 0 the section is the circles ρ = 7/5 and ρ = 3/5; their critical points in
  // direction a = e_x are (±7/5, 0) and (±3/5, 0), and (0, 7/5) is not critical.
  const PrimitiveSystem curve = curve_critical_system(torus);
  const GiNaC::exmap plane = parameter_map(curve, {zero_, ex_, ey_});
  for (const GiNaC::numeric& u : {GiNaC::numeric(7, 5), GiNaC::numeric(-7, 5), three5, -three5})
    BOOST_TEST(all_vanish(curve, with_unknowns(plane, curve, {u, 0})));
  BOOST_TEST(!all_vanish(curve, with_unknowns(plane, curve, {0, GiNaC::numeric(7, 5)})));
  // The same plane with origin shifted in-plane: o = (1, 1, 0), point (7/5, 0) is u = 2/5, v = -1.
  const GiNaC::exmap shifted = parameter_map(curve, {Vec{1, 1, 0}, ex_, ey_});
  BOOST_TEST(all_vanish(curve, with_unknowns(shifted, curve, {GiNaC::numeric(2, 5), -1})));

  // The silhouette J_d of the torus in direction d = e_x meets the plane y = 0 (a = e_x, b = e_z)
  // where ∂xE = 4x(S - 2) = 0 on Σ: at the four points (±1, ±r); not at (7/5, 0).
  const PrimitiveSystem sil = silhouette_plane_system(torus);
  const GiNaC::exmap xz = parameter_map(sil, {zero_, ex_, ez_, ex_});
  BOOST_TEST(all_vanish(sil, with_unknowns(xz, sil, {1, r})));
  BOOST_TEST(all_vanish(sil, with_unknowns(xz, sil, {-1, -r})));
  BOOST_TEST(!all_vanish(sil, with_unknowns(xz, sil, {GiNaC::numeric(7, 5), 0})));
}

BOOST_AUTO_TEST_CASE(sphere_silhouette_is_the_great_circle_perpendicular_to_d) {
  const Surface sphere = catalog_entry("sphere").surface();
  const PrimitiveSystem sil = silhouette_plane_system(sphere);
  const PrimitiveSystem crit = silhouette_critical_system(sphere);
  std::mt19937 rng(3);
  for (int trial = 0; trial < 6; ++trial) {
    const Vec d = random_unit(rng);
    // The plane through the centre perpendicular to d (spanned by a ⟂ d and b = d × a) lies in
    // the cylinder of the silhouette direction: ⟨∇E, d⟩ = 2⟨u a + v b, d⟩ vanishes identically
    // in (u, v), so J_d ∩ Π is the great circle Σ ∩ Π.
    const Vec a = perpendicular(d), b = cross(d, a);
    const GiNaC::exmap m = parameter_map(sil, {zero_, a, b, d});
    BOOST_TEST(vanishes(sil.equations[1].subs(m)));
    // A plane not through the centre (o = d/2) meets the silhouette nowhere: ⟨∇E, d⟩ = 1 there.
    const GiNaC::exmap off = parameter_map(sil, {scaled(d, GiNaC::numeric(1, 2)), a, b, d});
    BOOST_TEST(vanishes(sil.equations[1].subs(off) - 1));
  }
  // SilhouetteCritical: J_d for d = (3/5, 4/5, 0) is the great circle in the plane spanned by
  // q = (4/5, -3/5, 0) and e_z; its critical points in direction d' = e_z are ±e_z (tangent ⟂ d').
  const Vec d{GiNaC::numeric(3, 5), GiNaC::numeric(4, 5), 0}, q{GiNaC::numeric(4, 5), GiNaC::numeric(-3, 5), 0};
  const GiNaC::exmap m = parameter_map(crit, {d, ez_});
  BOOST_TEST(all_vanish(crit, with_unknowns(m, crit, {0, 0, 1})));
  BOOST_TEST(all_vanish(crit, with_unknowns(m, crit, {0, 0, -1})));
  // Other points of the great circle satisfy E = G = 0 but are not critical in direction e_z.
  for (const auto& cs : std::vector<std::array<GiNaC::numeric, 2>>{{1, 0}, {GiNaC::numeric(3, 5), GiNaC::numeric(4, 5)}}) {
    const Vec p{q[0] * cs[0], q[1] * cs[0], cs[1]};
    const GiNaC::exmap at = with_unknowns(m, crit, {p[0], p[1], p[2]});
    BOOST_TEST(vanishes(crit.equations[0].subs(at)));
    BOOST_TEST(vanishes(crit.equations[1].subs(at)));
    BOOST_TEST(!vanishes(crit.equations[2].subs(at)));
  }
  // With d' = q the critical points are ±q.
  const GiNaC::exmap mq = parameter_map(crit, {d, q});
  BOOST_TEST(all_vanish(crit, with_unknowns(mq, crit, {q[0], q[1], q[2]})));
  BOOST_TEST(all_vanish(crit, with_unknowns(mq, crit, {-q[0], -q[1], -q[2]})));
}

BOOST_AUTO_TEST_SUITE_END()
