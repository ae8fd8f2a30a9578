#include "solvers/subdivision_solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>

#include <boost/multiprecision/cpp_bin_float.hpp>
#include <boost/test/data/monomorphic.hpp>
#include <boost/test/data/test_case.hpp>
#include <boost/test/unit_test.hpp>

#include "common/errors.h"
#include "solvers/query_geometry.h"
#include "solvers/univariate_isolator.h"
#include "symbolic/line_polynomial.h"
#include "symbolic/catalog.h"
#include "solvers/primitives.h"

using namespace delmesh;

namespace {

//! Every case runs on the compiled expressions alone and on Taylor forms (wherever the system has
//! a PolynomialForm), so both paths of the solver meet the same known answers and the same
//! degenerate suite.
const auto taylor_modes = boost::unit_test::data::make({TaylorForms::never, TaylorForms::always});

SolveResult solve(TaylorForms mode, const CompiledSystem& system, const std::vector<double>& parameters,
                  const Domain& domain, SubdivisionOptions options = {}) {
  options.taylor_forms = mode;
  return solve_subdivision(system, parameters, domain, options);
}

std::vector<double> frame_parameters(const Vec3& d) {
  const OrthonormalFrame f = orthonormal_frame(d);
  return {f.a[0], f.a[1], f.a[2], f.b[0], f.b[1], f.b[2]};
}

bool contains(const SolverBox& box, const std::vector<double>& point, double slack = 0) {
  for (std::size_t i = 0; i < point.size(); ++i)
    if (point[i] < box.bounds[i][0] - slack || point[i] > box.bounds[i][1] + slack) return false;
  return true;
}

//! Asserts: status complete, the certified roots are exactly `expected` (each in one box).
void check_roots(const SolveResult& r, const std::vector<std::vector<double>>& expected, double tol = 1e-9) {
  BOOST_TEST(r.status == SolveStatus::complete);
  BOOST_TEST(r.undecided.empty());
  BOOST_REQUIRE_EQUAL(r.roots.size(), expected.size());
  for (const auto& e : expected) {
    int hits = 0;
    for (const auto& root : r.roots) {
      double dist = 0;
      for (std::size_t i = 0; i < e.size(); ++i) dist = std::max(dist, std::abs(root.midpoint[i] - e[i]));
      if (dist < tol) {
        ++hits;
        BOOST_TEST(contains(root.box, e, tol));
        BOOST_TEST(root.inside_domain);
      }
    }
    BOOST_TEST(hits == 1);
  }
}

bool any_reason(const SolveResult& r, UndecidedReason reason) {
  for (const auto& u : r.undecided)
    if (u.reason == reason) return true;
  return false;
}

//! Two circles in (u, v): (u − c1)² + v² = r1², (u − c2)² + v² = r2² (parameters c1, r1, c2, r2).
CompiledSystem two_circles() {
  GiNaC::symbol u("u"), v("v"), c1("c1"), r1("r1"), c2("c2"), r2("r2");
  return CompiledSystem({(u - c1) * (u - c1) + v * v - r1 * r1, (u - c2) * (u - c2) + v * v - r2 * r2}, {u, v},
                        {c1, r1, c2, r2});
}

}  // namespace

BOOST_AUTO_TEST_SUITE(subdivision_solver)

BOOST_DATA_TEST_CASE(sphere_critical_points_are_plus_minus_d, taylor_modes, mode) {
  const CatalogEntry& entry = catalog_entry("sphere");
  const CompiledSystem system(surface_critical_system(entry.surface()));
  const Domain domain = box_domain(entry.box);
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 8; ++trial) {
    const Vec3 d = unit_vector({normal(rng), normal(rng), normal(rng)});
    const SolveResult r = solve(mode, system, frame_parameters(d), domain);
    check_roots(r, {{d[0], d[1], d[2]}, {-d[0], -d[1], -d[2]}});
    for (const auto& root : r.roots)
      for (int i = 0; i < 3; ++i) BOOST_TEST(std::abs(root.world[i] - root.midpoint[i]) < 1e-15);
  }
}

BOOST_DATA_TEST_CASE(sphere_critical_points_along_the_axes, taylor_modes, mode) {
  // Axis directions: the roots ±e_i have exact zero coordinates, which Krawczyk contracts to
  // point intervals; they must still be certified.
  const CatalogEntry& entry = catalog_entry("sphere");
  const CompiledSystem system(surface_critical_system(entry.surface()));
  for (int axis = 0; axis < 3; ++axis) {
    Vec3 d{0, 0, 0};
    d[axis] = 1;
    std::vector<double> plus(3, 0.0), minus(3, 0.0);
    plus[axis] = 1, minus[axis] = -1;
    check_roots(solve(mode, system, frame_parameters(d), box_domain(entry.box)), {plus, minus});
  }
}

BOOST_DATA_TEST_CASE(ellipsoid_critical_points, taylor_modes, mode) {
  // x²/a² + y²/b² + z²/c² = 1: the points with normal ∥ d are ± M⁻¹d / √(dᵀM⁻¹d), M = diag(1/a²…).
  const CatalogEntry& entry = catalog_entry("ellipsoid");
  const CompiledSystem system(surface_critical_system(entry.surface()));
  const Domain domain = box_domain(entry.box);
  const double axes2[3] = {2.25, 1.0, 0.5625};
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 4; ++trial) {
    const Vec3 d = unit_vector({normal(rng), normal(rng), normal(rng)});
    double q = 0;
    for (int i = 0; i < 3; ++i) q += axes2[i] * d[i] * d[i];
    std::vector<double> x(3), y(3);
    for (int i = 0; i < 3; ++i) x[i] = axes2[i] * d[i] / std::sqrt(q), y[i] = -x[i];
    check_roots(solve(mode, system, frame_parameters(d), domain), {x, y});
  }
}

BOOST_DATA_TEST_CASE(tanglecube_has_24_critical_points_in_z, taylor_modes, mode) {
  // ∇E ∥ z: 4x³ − 10x = 0 = 4y³ − 10y, so x, y ∈ {0, ±√2.5} with x⁴ − 5x² ∈ {0, −6.25}.  Then
  // z⁴ − 5z² + c = 0 with c = 11.8 + f(x) + f(y):
  //   c = 11.8  (x = y = 0):           25 − 47.2 < 0, no real z;
  //   c = 5.55  (4 pairs, one of x, y zero): z² = (5 ± √2.8)/2 > 0, 4 values of z → 16 points;
  //   c = −0.7  (4 pairs, both ±√2.5):   z² = (5 + √27.8)/2 only, 2 values of z → 8 points.
  const CatalogEntry& entry = catalog_entry("tanglecube");
  const CompiledSystem system(surface_critical_system(entry.surface()));
  const SolveResult r = solve(mode, system, {1, 0, 0, 0, 1, 0}, box_domain(entry.box));
  std::vector<std::vector<double>> expected;
  const double s = std::sqrt(2.5);
  for (double x : {-s, 0.0, s})
    for (double y : {-s, 0.0, s}) {
      const double c = 11.8 + (x * x * x * x - 5 * x * x) + (y * y * y * y - 5 * y * y);
      const double disc = 25 - 4 * c;
      if (disc < 0) continue;
      for (double w : {(5 + std::sqrt(disc)) / 2, (5 - std::sqrt(disc)) / 2})
        if (w > 0) expected.push_back({x, y, std::sqrt(w)}), expected.push_back({x, y, -std::sqrt(w)});
    }
  BOOST_REQUIRE_EQUAL(expected.size(), 24u);
  check_roots(r, expected);
}

BOOST_DATA_TEST_CASE(curve_critical_on_a_sphere_section, taylor_modes, mode) {
  // The plane z = 1/2 cuts the unit sphere in the circle u² + v² = 3/4; its critical points in the
  // in-plane direction a = x are (u, v) = (±√3/2, 0), world points (±√3/2, 0, 1/2).
  const CompiledSystem system(curve_critical_system(catalog_entry("sphere").surface()));
  const SolveResult r =
      solve(mode, system, {0, 0, 0.5, 1, 0, 0, 0, 1, 0}, Domain::from_box({{-1.1, 1.05}, {-0.9, 0.95}}));
  const double h = std::sqrt(0.75);
  check_roots(r, {{h, 0}, {-h, 0}});
  for (const auto& root : r.roots) {
    BOOST_TEST(std::abs(std::abs(root.world[0]) - h) < 1e-12);
    BOOST_TEST(std::abs(root.world[1]) < 1e-12);
    BOOST_TEST(std::abs(root.world[2] - 0.5) < 1e-15);
  }
}

BOOST_DATA_TEST_CASE(circle_circle_two_and_zero_roots, taylor_modes, mode) {
  const CompiledSystem system = two_circles();
  const Domain domain = Domain::from_box({{-2, 3}, {-2, 2}});
  // Unit circles at 0 and 1 meet at (1/2, ±√3/2).
  check_roots(solve(mode, system, {0, 1, 1, 1}, domain), {{0.5, std::sqrt(0.75)}, {0.5, -std::sqrt(0.75)}});
  // Centres 2.5 apart: no intersection.
  check_roots(solve(mode, system, {0, 1, 2.5, 1}, domain), {});
}

BOOST_DATA_TEST_CASE(roots_inside_and_outside_a_polygon, taylor_modes, mode) {
  const CompiledSystem system = two_circles();
  // Triangle (−1, −1.5), (2, −1.5), (0.5, 0.2): contains (1/2, −√3/2) but not (1/2, +√3/2).
  const Domain triangle = polygon_domain({{-1, -1.5}, {2, -1.5}, {0.5, 0.2}});
  const SolveResult r = solve(mode, system, {0, 1, 1, 1}, triangle);
  check_roots(r, {{0.5, -std::sqrt(0.75)}});
  // A face 1e-9 from the lower root: the root's box straddles the face until Krawczyk refinement
  // decides the side.  Outside → not returned, counted; inside → certified.
  const double v_root = -std::sqrt(0.75);
  for (double gap : {-1e-9, 1e-9}) {
    Domain half = Domain::from_box({{-2, 3}, {-2, 2}});
    half.half_spaces.push_back({{0, 1}, v_root + gap});  // v ≤ v_root + gap
    const SolveResult h = solve(mode, system, {0, 1, 1, 1}, half);
    if (gap < 0) {
      check_roots(h, {});
      BOOST_TEST(h.counters.roots_outside == 1u);
    } else {
      check_roots(h, {{0.5, v_root}});
    }
  }
}

BOOST_DATA_TEST_CASE(cancellation_is_escalated_to_mpfi, taylor_modes, mode) {
  // (u + c)² − c² − 2 c u − 1/4 = u² − 1/4 and v − u/3 with c = 1e8: double enclosures of the
  // first equation are ~1 wide at every point, so only MPFI certifies the roots (±1/2, ±1/6).
  GiNaC::symbol u("u"), v("v"), c("c");
  const CompiledSystem system({GiNaC::pow(u + c, 2) - c * c - 2 * c * u - GiNaC::numeric(1, 4), v - u / 3}, {u, v}, {c});
  const SolveResult r = solve(mode, system, {1e8}, Domain::from_box({{-1, 1.1}, {-1, 0.9}}));
  check_roots(r, {{0.5, 1.0 / 6}, {-0.5, -1.0 / 6}}, 1e-6);
  BOOST_TEST(r.counters.precision_escalations > 0u);
}

// ---- degenerate suite: flagged, never falsely certified ----

BOOST_DATA_TEST_CASE(root_exactly_on_a_box_face_is_boundary_root, taylor_modes, mode) {
  const CompiledSystem system = two_circles();
  // The roots have u = 1/2 exactly; the box face u = 0.5 passes through both.
  const SolveResult r = solve(mode, system, {0, 1, 1, 1}, Domain::from_box({{0.5, 2}, {-2, 2}}));
  BOOST_TEST(r.roots.empty());
  BOOST_TEST(r.status == SolveStatus::undecided);
  BOOST_REQUIRE_EQUAL(r.undecided.size(), 2u);
  for (const auto& u : r.undecided) {
    BOOST_TEST(u.reason == UndecidedReason::boundary_root);
    BOOST_TEST(contains(u.box, {0.5, u.box.bounds[1][0] > 0 ? std::sqrt(0.75) : -std::sqrt(0.75)}));
  }
  // A root exactly on a half-space face: v ≤ u − 0.5 + √0.75 ... use the face u ≤ 0.5.
  Domain half = Domain::from_box({{-2, 3}, {-2, 2}});
  half.half_spaces.push_back({{1, 0}, 0.5});
  const SolveResult h = solve(mode, system, {0, 1, 1, 1}, half);
  BOOST_TEST(h.roots.empty());
  BOOST_TEST(h.undecided.size() == 2u);
  BOOST_TEST(any_reason(h, UndecidedReason::boundary_root));
}

BOOST_DATA_TEST_CASE(tangent_circles_double_root_is_singular, taylor_modes, mode) {
  const CompiledSystem system = two_circles();
  // Unit circles at 0 and 2 touch at (1, 0).
  const SolveResult r = solve(mode, system, {0, 1, 2, 1}, Domain::from_box({{-2, 3.5}, {-2, 2}}));
  BOOST_TEST(r.roots.empty());
  BOOST_TEST(r.status == SolveStatus::undecided);
  BOOST_REQUIRE(!r.undecided.empty());
  bool covers = false;
  for (const auto& u : r.undecided) {
    BOOST_TEST(u.reason == UndecidedReason::singular_root);
    covers = covers || contains(u.box, {1, 0});
  }
  BOOST_TEST(covers);
}

BOOST_DATA_TEST_CASE(torus_axis_direction_is_non_isolated_within_budget, taylor_modes, mode) {
  // Direction z = the torus axis: the critical points form the circles ρ = 1, z = ±0.4.
  const CatalogEntry& entry = catalog_entry("torus");
  const CompiledSystem system(surface_critical_system(entry.surface()));
  const auto start = std::chrono::steady_clock::now();
  const SolveResult r = solve(mode, system, {1, 0, 0, 0, 1, 0}, box_domain(entry.box));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  BOOST_TEST(r.status == SolveStatus::non_isolated);
  BOOST_TEST(r.roots.empty());
  BOOST_TEST(!r.undecided.empty());
  BOOST_TEST(r.counters.boxes < SubdivisionOptions{}.box_budget);
  BOOST_TEST_MESSAGE("torus axis: " << r.counters.boxes << " boxes, " << seconds << " s");
  // A generic direction has isolated critical points again (4 on this torus: ±d-extremes of the
  // outer and inner equators' images… at least the two global extremes in direction d).
  const Vec3 d = unit_vector({0.3, 0.2, 1.0});
  const SolveResult g = solve(mode, system, frame_parameters(d), box_domain(entry.box));
  BOOST_TEST(g.status == SolveStatus::complete);
  BOOST_TEST(g.roots.size() == 4u);
}

BOOST_DATA_TEST_CASE(cone_apex_is_never_certified, taylor_modes, mode) {
  // x² + y² − z²: the critical system in direction z is singular at the apex (0, 0, 0).
  const Surface cone = Surface::parse("x^2+y^2-z^2");
  const CompiledSystem system(surface_critical_system(cone));
  const SolveResult r = solve(mode, system, {1, 0, 0, 0, 1, 0}, Domain::from_box({{-0.5, 0.7}, {-0.6, 0.5}, {-0.5, 0.55}}));
  BOOST_TEST(r.roots.empty());
  BOOST_TEST(r.status != SolveStatus::complete);
  bool covers = false;
  for (const auto& u : r.undecided) covers = covers || contains(u.box, {0, 0, 0});
  BOOST_TEST(covers);
  BOOST_TEST(any_reason(r, UndecidedReason::singular_root));
}

// ---- exclusion mode (SurfacePlaneContact) ----

BOOST_DATA_TEST_CASE(exclusion_mode_plane_missing_and_tangent_to_sphere, taylor_modes, mode) {
  const Surface sphere = catalog_entry("sphere").surface();
  const CompiledSystem contact(surface_plane_contact_system(sphere));
  SubdivisionOptions options;
  options.exclusion_mode = true;
  const Domain square = Domain::from_box({{-0.7, 0.6}, {-0.5, 0.65}});
  // The plane z = 1.2 misses the sphere.
  const SolveResult miss = solve(mode, contact, {0, 0, 1.2, 1, 0, 0, 0, 1, 0}, square, options);
  BOOST_TEST(miss.status == SolveStatus::complete);
  BOOST_TEST(miss.undecided.empty());
  BOOST_TEST(miss.roots.empty());
  // The plane z = 0.5 cuts the sphere transversally: no tangential contact either.
  const SolveResult cut = solve(mode, contact, {0, 0, 0.5, 1, 0, 0, 0, 1, 0}, square, options);
  BOOST_TEST(cut.status == SolveStatus::complete);
  // The plane z = 1 touches it at (0, 0, 1) = (u, v) = (0, 0).
  const SolveResult touch = solve(mode, contact, {0, 0, 1, 1, 0, 0, 0, 1, 0}, square, options);
  BOOST_TEST(touch.status == SolveStatus::undecided);
  BOOST_TEST(touch.roots.empty());
  bool covers = false;
  for (const auto& u : touch.undecided) {
    covers = covers || contains(u.box, {0, 0});
    BOOST_TEST(u.reason == UndecidedReason::singular_root);
    BOOST_TEST(std::abs(u.world[2] - 1) < 1e-6);
  }
  BOOST_TEST(covers);
}

BOOST_DATA_TEST_CASE(budgets_return_unexplored_boxes, taylor_modes, mode) {
  const CatalogEntry& entry = catalog_entry("tanglecube");
  const CompiledSystem system(surface_critical_system(entry.surface()));
  SubdivisionOptions options;
  options.box_budget = 50;
  const SolveResult r = solve(mode, system, {1, 0, 0, 0, 1, 0}, box_domain(entry.box), options);
  BOOST_TEST(r.status == SolveStatus::box_limit);
  BOOST_TEST(r.counters.boxes == 50u);
  BOOST_TEST(any_reason(r, UndecidedReason::budget));
  // Every expected root is certified or in an undecided box.
  const double s = std::sqrt(2.5), z = std::sqrt((5 + std::sqrt(27.8)) / 2);
  bool found = false;
  for (const auto& u : r.undecided) found = found || contains(u.box, {s, s, z});
  for (const auto& root : r.roots) found = found || contains(root.box, {s, s, z});
  BOOST_TEST(found);
  // A time limit far below the solve time stops it the same way.
  SubdivisionOptions timed;
  timed.time_limit_seconds = 1e-9;
  const SolveResult t = solve(mode, system, {1, 0, 0, 0, 1, 0}, box_domain(entry.box), timed);
  BOOST_TEST(t.status == SolveStatus::time_limit);
  BOOST_TEST(any_reason(t, UndecidedReason::budget));
}

namespace {

//! Ellipsoid critical points in random directions over random Voronoi-cell-sized boxes near one
//! of them (so the root is inside, outside or near a face): every known root strictly inside the
//! box is in a certified or an undecided box; every certified root is a known root inside it.
void ellipsoid_sweep(TaylorForms mode, int trials, std::uint64_t seed) {
  const CatalogEntry& entry = catalog_entry("ellipsoid");
  const CompiledSystem system(surface_critical_system(entry.surface()));
  const double axes2[3] = {2.25, 1.0, 0.5625};
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> offset(-0.15, 0.15);
  int certified = 0;
  for (int trial = 0; trial < trials; ++trial) {
    const Vec3 d = unit_vector({normal(rng), normal(rng), normal(rng)});
    double q = 0;
    for (int i = 0; i < 3; ++i) q += axes2[i] * d[i] * d[i];
    std::vector<std::vector<double>> known(2, std::vector<double>(3));
    for (int i = 0; i < 3; ++i) known[0][i] = axes2[i] * d[i] / std::sqrt(q), known[1][i] = -known[0][i];
    std::vector<std::array<double, 2>> bounds(3);
    for (int i = 0; i < 3; ++i) {
      const double c = known[0][i] + offset(rng);
      bounds[i] = {c - 0.125, c + 0.125};
    }
    const SolveResult r = solve(mode, system, frame_parameters(d), Domain::from_box(bounds));
    for (const auto& root : r.roots) {
      bool matches = false;
      for (const auto& k : known) matches = matches || contains(root.box, k, 1e-12);
      BOOST_TEST(matches);
      ++certified;
    }
    for (const auto& k : known) {
      bool strictly_inside = true;
      for (int i = 0; i < 3; ++i) strictly_inside = strictly_inside && k[i] > bounds[i][0] + 1e-9 && k[i] < bounds[i][1] - 1e-9;
      if (!strictly_inside) continue;
      bool covered = false;
      for (const auto& root : r.roots) covered = covered || contains(root.box, k, 1e-12);
      for (const auto& u : r.undecided) covered = covered || contains(u.box, k, 1e-12);
      BOOST_TEST(covered);
    }
  }
  BOOST_TEST(certified > trials / 10);
}

}  // namespace

BOOST_DATA_TEST_CASE(ellipsoid_random_cells_never_miss_never_invent, taylor_modes, mode) { ellipsoid_sweep(mode, 150, 3); }

BOOST_TEST_DECORATOR(*boost::unit_test::label("slow"))
BOOST_DATA_TEST_CASE(ellipsoid_random_cells_sweep, taylor_modes, mode) { ellipsoid_sweep(mode, 20000, 4); }

namespace {

//! Two circles (centres (0, 0) and (c, 0), radii 1 and r) that cross, nearly touch (gap ±1e-6 …
//! ±1e-14) or miss, over random boxes: each certified box holds exactly one intersection point
//! (computed in 50 digits), every intersection strictly inside the box is covered.
void circles_sweep(TaylorForms mode, int trials, std::uint64_t seed) {
  const CompiledSystem system = two_circles();
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(-1, 1);
  using Real = boost::multiprecision::cpp_bin_float_50;
  for (int trial = 0; trial < trials; ++trial) {
    const double r = 0.5 + 0.4 * std::abs(uni(rng));
    double c = 1 + r;
    if (trial % 3 == 0) c -= 0.5 * std::abs(uni(rng));                                        // crossing
    else c += std::pow(10.0, -6 - 8 * std::abs(uni(rng))) * (uni(rng) < 0 ? -1 : 1);          // nearly touching
    // u = (1 − r² + c²) / (2c), v = ±√(1 − u²), from the parameters as doubles.
    const Real U = (Real(1) - Real(r) * r + Real(c) * c) / (2 * Real(c)), V2 = 1 - U * U;
    std::vector<std::vector<double>> known;
    if (V2 >= 0) {
      known.push_back({static_cast<double>(U), static_cast<double>(sqrt(V2))});
      known.push_back({static_cast<double>(U), -static_cast<double>(sqrt(V2))});
    }
    const double cu = 1 + 0.2 * uni(rng), cv = 0.3 * uni(rng);
    const std::vector<std::array<double, 2>> bounds = {{cu - 0.3, cu + 0.3}, {cv - 0.4, cv + 0.4}};
    const SolveResult result = solve(mode, system, {0, 1, c, r}, Domain::from_box(bounds));
    for (const auto& root : result.roots) {
      int inside = 0;
      for (const auto& k : known) inside += contains(root.box, k) ? 1 : 0;
      BOOST_TEST(inside == 1);
    }
    for (const auto& k : known) {
      if (!(k[0] > bounds[0][0] + 1e-9 && k[0] < bounds[0][1] - 1e-9 && k[1] > bounds[1][0] + 1e-9 &&
            k[1] < bounds[1][1] - 1e-9))
        continue;
      bool covered = false;
      for (const auto& root : result.roots) covered = covered || contains(root.box, k, 1e-12);
      for (const auto& u : result.undecided) covered = covered || contains(u.box, k, 1e-12);
      BOOST_TEST(covered);
    }
  }
}

}  // namespace

BOOST_DATA_TEST_CASE(circles_random_never_miss_never_invent, taylor_modes, mode) { circles_sweep(mode, 300, 8); }

BOOST_TEST_DECORATOR(*boost::unit_test::label("slow"))
BOOST_DATA_TEST_CASE(circles_random_sweep, taylor_modes, mode) { circles_sweep(mode, 30000, 9); }

// ---- Taylor forms against the compiled expressions ----

BOOST_AUTO_TEST_CASE(taylor_forms_agree_with_compiled_expressions_on_catalog_cells) {
  // The square primitives of four polynomial catalog surfaces on random Voronoi-cell-sized
  // domains (a cube of side 0.3 around a surface point; a square of side 0.3 in a random plane
  // through it): where both paths complete, they certify the same roots.
  std::mt19937_64 rng(21);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uni(-1, 1);
  int compared = 0, roots = 0;
  for (const std::string name : {"torus", "genus2", "tanglecube", "chair"}) {
    const CatalogEntry& entry = catalog_entry(name);
    const Surface surface = entry.surface();
    const CompiledSystem line(surface_line_system(surface));
    const LinePolynomial polynomial(surface);
    for (const std::string primitive : {"surface_critical", "silhouette_critical", "curve_critical", "silhouette_plane"}) {
      PrimitiveSystem system;
      for (const PrimitiveInfo& info : primitive_registry())
        if (info.name == primitive) system = info.build(surface);
      const CompiledSystem compiled(system);
      BOOST_REQUIRE(compiled.polynomial_form());
      for (int trial = 0; trial < 12; ++trial) {
        // A surface point: a root of a random line through the box.
        Vec3 x{};
        for (bool found = false; !found;) {
          Vec3 p;
          for (int i = 0; i < 3; ++i) p[i] = entry.box.lo[i] + (0.5 + 0.4 * uni(rng)) * (entry.box.hi[i] - entry.box.lo[i]);
          const Vec3 v = unit_vector({normal(rng), normal(rng), normal(rng)});
          const auto range = clip_line_to_box(p, v, entry.box);
          if (!range) continue;
          const SolveResult r = isolate_line_roots(line, &polynomial, p, v, (*range)[0], (*range)[1]);
          if (!r.roots.empty()) x = r.roots.front().world, found = true;
        }
        const Vec3 d = unit_vector({normal(rng), normal(rng), normal(rng)});
        const Vec3 d2 = unit_vector({normal(rng), normal(rng), normal(rng)});
        const OrthonormalFrame f = orthonormal_frame(d);
        std::vector<double> params;
        Domain domain;
        if (system.n_unknowns() == 3) {
          params = primitive == "surface_critical" ? std::vector<double>{f.a[0], f.a[1], f.a[2], f.b[0], f.b[1], f.b[2]}
                                                   : std::vector<double>{d[0], d[1], d[2], d2[0], d2[1], d2[2]};
          domain = Domain::from_box({{x[0] - 0.15, x[0] + 0.15}, {x[1] - 0.15, x[1] + 0.15}, {x[2] - 0.15, x[2] + 0.15}});
        } else {
          params = {x[0], x[1], x[2], f.a[0], f.a[1], f.a[2], f.b[0], f.b[1], f.b[2]};
          if (system.n_parameters() == 12) params.insert(params.end(), {d2[0], d2[1], d2[2]});
          domain = Domain::from_box({{-0.15, 0.15}, {-0.15, 0.15}});
        }
        const SolveResult plain = solve(TaylorForms::never, compiled, params, domain);
        const SolveResult taylor = solve(TaylorForms::always, compiled, params, domain);
        if (!plain.is_complete() || !taylor.is_complete()) continue;
        ++compared;
        BOOST_REQUIRE_EQUAL(plain.roots.size(), taylor.roots.size());
        for (const auto& a : plain.roots) {
          ++roots;
          int matches = 0;
          for (const auto& b : taylor.roots) {
            double dist = 0;
            for (std::size_t i = 0; i < a.midpoint.size(); ++i) dist = std::max(dist, std::abs(a.midpoint[i] - b.midpoint[i]));
            matches += dist < 1e-9;
          }
          BOOST_TEST(matches == 1, name << " " << primitive << " trial " << trial);
        }
      }
    }
  }
  BOOST_TEST(compared >= 150);
  BOOST_TEST(roots >= 20);
  BOOST_TEST_MESSAGE("Taylor vs compiled: " << compared << " solves compared, " << roots << " roots");
}

// refine_singular_regions on three systems in (u, v) whose feature at u = 0 is narrower than
// singular_box_relative_width: f = (u − a)(u + a) + c with a = 1e-8 (compiled expressions only: a
// Taylor form would see u² − a² + c at once).  c = 2a²: no zero, but every box wider than about a
// keeps 0 in f's enclosure; c = 0: the simple roots ±a; and f = u²: a true double root.
BOOST_AUTO_TEST_CASE(singular_regions_are_refined_and_never_dropped) {
  GiNaC::symbol u("u"), v("v"), a("a"), c("c");
  const CompiledSystem near({(u - a) * (u + a) + c, v - u / 3}, {u, v}, {a, c});
  const Domain domain = Domain::from_box({{-1, 1.1}, {-1, 0.9}});
  auto first_look = [&](const CompiledSystem& system, const std::vector<double>& parameters) {
    SolveResult r = solve(TaylorForms::never, system, parameters, domain);
    BOOST_TEST(r.status == SolveStatus::undecided);
    BOOST_TEST(!r.undecided.empty());
    BOOST_TEST(r.roots.empty());
    return r;
  };
  SubdivisionOptions never;
  never.taylor_forms = TaylorForms::never;
  const double e = 1e-8;
  // No zero: every region is excluded.
  SolveResult gap = first_look(near, {e, 2 * e * e});
  refine_singular_regions(near, {e, 2 * e * e}, domain, gap, never);
  BOOST_TEST(gap.status == SolveStatus::complete);
  BOOST_TEST(gap.undecided.empty());
  BOOST_TEST(gap.roots.empty());
  // Two simple roots 2e-8 apart: both certified.
  SolveResult pair = first_look(near, {e, 0.0});
  refine_singular_regions(near, {e, 0.0}, domain, pair, never);
  BOOST_TEST(pair.status == SolveStatus::complete);
  check_roots(pair, {{e, e / 3}, {-e, -e / 3}}, 1e-12);
  // A double root stays undecided, with a region that holds it.
  const CompiledSystem double_root({u * u, v - u / 3}, {u, v}, {});
  SolveResult twice = first_look(double_root, {});
  refine_singular_regions(double_root, {}, domain, twice, never);
  BOOST_TEST(twice.status == SolveStatus::undecided);
  BOOST_TEST(twice.roots.empty());
  BOOST_TEST(std::any_of(twice.undecided.begin(), twice.undecided.end(),
                         [](const UndecidedBox& b) { return contains(b.box, {0.0, 0.0}); }));
}

BOOST_AUTO_TEST_CASE(misuse_throws_precondition_violation) {
  const CompiledSystem system = two_circles();
  BOOST_CHECK_THROW((void)solve_subdivision(system, {0, 1, 1}, Domain::from_box({{0, 1}, {0, 1}})),
                    PreconditionViolation);
  BOOST_CHECK_THROW((void)solve_subdivision(system, {0, 1, 1, 1}, Domain::from_box({{0, 1}, {0, 1}, {0, 1}})),
                    PreconditionViolation);
  const CompiledSystem contact(surface_plane_contact_system(catalog_entry("sphere").surface()));
  BOOST_CHECK_THROW((void)solve_subdivision(contact, std::vector<double>(9, 0.0), Domain::from_box({{0, 1}, {0, 1}})),
                    PreconditionViolation);  // over-determined without exclusion_mode
}

BOOST_AUTO_TEST_SUITE_END()
