#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>
#include <sstream>

#include "common/errors.h"
#include "solvers/detail/homotopy_tracker.h"
#include "solvers/homotopy_solver.h"
#include "system_fixture.h"
#include "solvers/kostlan_system.h"
#include "solvers/query_geometry.h"
#include "symbolic/catalog.h"
#include "solvers/primitives.h"

using namespace delmesh;
using GiNaC::ex;
using GiNaC::symbol;

namespace {

using test::make_system;
using test::X;
using test::Y;

HomotopySolveResult solve(const PrimitiveSystem& system, const std::vector<double>& parameters, const Domain& domain,
                          std::uint64_t seed = 1) {
  const CompiledSystem compiled(system);
  HomotopyOptions options;
  options.seed = seed;
  return solve_homotopy(compiled, equation_degrees(system), parameters, domain, options);
}

//! Every path of the total-degree homotopy of `system` (no parameters), tracked with a fixed γ and
//! patch.
std::vector<detail::PathEndpoint> track_all(const PrimitiveSystem& system,
                                            const detail::TrackerSettings& settings = detail::TrackerSettings::defaults()) {
  const CompiledSystem compiled(system);
  const auto degrees = equation_degrees(system);
  std::vector<Complex> patch;
  for (std::size_t j = 0; j <= degrees.size(); ++j)
    patch.push_back(std::polar(1.0 / std::sqrt(degrees.size() + 1.0), 0.37 + 1.91 * static_cast<double>(j)));
  const detail::HomotopyTracker tracker(compiled, degrees, {}, std::polar(1.0, 2.2), patch);
  std::vector<detail::PathEndpoint> ends;
  for (const auto& start : total_degree_start_solutions(degrees))
    ends.push_back(tracker.track(start, settings));
  return ends;
}

std::size_t count(const std::vector<detail::PathEndpoint>& ends, detail::PathOutcome outcome) {
  return static_cast<std::size_t>(
      std::count_if(ends.begin(), ends.end(), [&](const auto& end) { return end.outcome == outcome; }));
}

//! An endgame that accepts a poor estimate: no direct finish, valuations taken as settled at once
//! (the loops start at t = 0.35), `samples` samples per loop, any two successive estimates taken
//! to agree.
detail::TrackerSettings poor_endgame(int samples) {
  auto settings = detail::TrackerSettings::defaults();
  settings.endgame_direct_steps = 0;
  settings.endgame_samples = samples;
  settings.endgame_start = 0.3;
  settings.endgame_valuation_stable = 1e300;
  settings.endgame_tolerance = 1e300;
  return settings;
}

double distance_to(const std::vector<Complex>& u, const std::vector<double>& expected) {
  double d = 0;
  for (std::size_t i = 0; i < expected.size(); ++i) d = std::max(d, std::abs(u[i] - expected[i]));
  return d;
}

//! The certified root matching `expected` (max-norm distance ≤ 1e-10), checking it lies in its box.
bool has_root(const SolveResult& r, const std::vector<double>& expected) {
  for (const auto& root : r.roots) {
    bool close = true;
    for (std::size_t i = 0; i < expected.size(); ++i) {
      close = close && std::abs(root.midpoint[i] - expected[i]) <= 1e-10;
      close = close && root.box.bounds[i][0] <= root.midpoint[i] && root.midpoint[i] <= root.box.bounds[i][1];
    }
    if (close) return true;
  }
  return false;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(homotopy_solver_test)

BOOST_AUTO_TEST_CASE(equation_degrees_are_total_degrees_in_the_unknowns) {
  const symbol a("a");
  const auto s = make_system({X() * X() * Y() + a * a * a * X() - 1, (X() + 1) * (X() + 1) - X() * X(), a * Y() + 2},
                             {X(), Y()});
  BOOST_TEST(equation_degrees(s) == std::vector<int>({3, 1, 1}), boost::test_tools::per_element());
  const auto sphere = surface_critical_system(catalog_entry("sphere").surface());
  BOOST_TEST(equation_degrees(sphere) == std::vector<int>({2, 1, 1}), boost::test_tools::per_element());
  const auto torus = surface_critical_system(catalog_entry("torus").surface());
  BOOST_TEST(equation_degrees(torus) == std::vector<int>({4, 3, 3}), boost::test_tools::per_element());
  const auto line = surface_line_system(catalog_entry("tanglecube").surface());
  BOOST_TEST(equation_degrees(line) == std::vector<int>({4}), boost::test_tools::per_element());
}

BOOST_AUTO_TEST_CASE(equation_degrees_rejects_non_polynomial) {
  BOOST_CHECK_THROW(equation_degrees(make_system({GiNaC::sin(X()) + Y(), X() - Y()}, {X(), Y()})), InvalidInput);
  BOOST_CHECK_THROW(equation_degrees(make_system({1 / X() + Y(), X() - Y()}, {X(), Y()})), InvalidInput);
  BOOST_CHECK_THROW(equation_degrees(make_system({GiNaC::sqrt(X() * X() + 1), Y()}, {X(), Y()})), InvalidInput);
}

BOOST_AUTO_TEST_CASE(start_solutions_are_the_bezout_many_roots_of_unity) {
  const std::vector<int> degrees{3, 4, 2};
  BOOST_TEST(bezout_number(degrees) == 24u);
  const auto starts = total_degree_start_solutions(degrees);
  BOOST_TEST(starts.size() == 24u);
  std::set<std::vector<long>> distinct;
  for (const auto& s : starts) {
    BOOST_REQUIRE(s.size() == 3u);
    std::vector<long> key;
    for (std::size_t i = 0; i < 3; ++i) {
      BOOST_TEST(std::abs(std::pow(s[i], degrees[i]) - 1.0) < 1e-14);
      key.push_back(std::lround(1e6 * s[i].real()));
      key.push_back(std::lround(1e6 * s[i].imag()));
    }
    distinct.insert(key);
  }
  BOOST_TEST(distinct.size() == 24u);
  BOOST_CHECK_THROW(bezout_number({}), PreconditionViolation);
  BOOST_CHECK_THROW(total_degree_start_solutions({2, 0}), InvalidInput);
}

BOOST_AUTO_TEST_CASE(circle_meets_line) {
  const auto s = make_system({X() * X() + Y() * Y() - 1, Y() - X()}, {X(), Y()});
  const auto r = solve(s, {}, Domain::from_box({{{-2.0, 2.0}}, {{-2.0, 2.0}}}));
  BOOST_TEST(r.status == SolveStatus::complete);
  BOOST_TEST(r.roots.size() == 2u);
  const double h = std::sqrt(0.5);
  BOOST_TEST(has_root(r, {h, h}));
  BOOST_TEST(has_root(r, {-h, -h}));
  BOOST_TEST(r.counters.paths >= 2u);
}

BOOST_AUTO_TEST_CASE(circle_meets_circle) {
  const auto s = make_system({X() * X() + Y() * Y() - 1, (X() - 1) * (X() - 1) + Y() * Y() - 1}, {X(), Y()});
  const auto r = solve(s, {}, Domain::from_box({{{-2.0, 2.0}}, {{-2.0, 2.0}}}));
  BOOST_TEST(r.status == SolveStatus::complete);
  BOOST_TEST(r.roots.size() == 2u);
  BOOST_TEST(has_root(r, {0.5, std::sqrt(3.0) / 2}));
  BOOST_TEST(has_root(r, {0.5, -std::sqrt(3.0) / 2}));
  BOOST_TEST(r.counters.paths == 4u);  // two of the four paths go to the circular points at infinity
}

BOOST_AUTO_TEST_CASE(half_space_domain_keeps_only_the_roots_inside) {
  // circle ∩ line with the half-plane x + y ≤ 0: only (−1/√2, −1/√2) is inside
  const auto s = make_system({X() * X() + Y() * Y() - 1, Y() - X()}, {X(), Y()});
  Domain domain = Domain::from_box({{{-2.0, 2.0}}, {{-2.0, 2.0}}});
  domain.half_spaces.push_back({{1.0, 1.0}, 0.0});
  const auto r = solve(s, {}, domain);
  BOOST_TEST(r.status == SolveStatus::complete);
  BOOST_TEST(r.roots.size() == 1u);
  BOOST_TEST(has_root(r, {-std::sqrt(0.5), -std::sqrt(0.5)}));
  BOOST_TEST(r.counters.roots_outside == 1u);
  // and a box that contains no root
  const auto none = solve(s, {}, Domain::from_box({{{0.8, 2.0}}, {{-2.0, 2.0}}}));
  BOOST_TEST(none.status == SolveStatus::complete);
  BOOST_TEST(none.roots.empty());
}

BOOST_AUTO_TEST_CASE(root_on_a_face_is_a_boundary_root) {
  // the root (1/2, 1/2) lies exactly on the box face x = 1/2, then exactly on the half-plane y ≤ x
  const auto s = make_system({X() * X() + Y() * Y() - GiNaC::numeric(1, 2), Y() - X()}, {X(), Y()});
  const auto on_box_face = solve(s, {}, Domain::from_box({{{-0.25, 0.5}}, {{-1.0, 1.0}}}));
  BOOST_TEST(on_box_face.status == SolveStatus::undecided);
  BOOST_TEST(on_box_face.roots.empty());
  BOOST_REQUIRE(on_box_face.undecided.size() == 1u);
  BOOST_TEST(on_box_face.undecided[0].reason == UndecidedReason::boundary_root);
  BOOST_TEST(on_box_face.undecided[0].box.bounds[0][0] <= 0.5);
  BOOST_TEST(on_box_face.undecided[0].box.bounds[0][1] >= 0.5);
  Domain half = Domain::from_box({{{0.0, 1.0}}, {{0.0, 1.0}}});
  half.half_spaces.push_back({{-1.0, 1.0}, 0.0});  // y − x ≤ 0
  const auto on_half_space = solve(s, {}, half);
  BOOST_TEST(on_half_space.status == SolveStatus::undecided);
  BOOST_TEST(on_half_space.roots.empty());
  BOOST_REQUIRE(on_half_space.undecided.size() == 1u);
  BOOST_TEST(on_half_space.undecided[0].reason == UndecidedReason::boundary_root);
}

BOOST_AUTO_TEST_CASE(tangent_circles_are_flagged_singular_never_certified) {
  // (1, 0) is a double root; the other two paths go to infinity.  No piece of the domain around
  // the double root can be proved (its zero is not regular): it stays undecided.
  const auto s = make_system({X() * X() + Y() * Y() - 1, (X() - 2) * (X() - 2) + Y() * Y() - 1}, {X(), Y()});
  const auto r = solve(s, {}, Domain::from_box({{{-3.0, 3.0}}, {{-3.0, 3.0}}}));
  BOOST_TEST(r.status == SolveStatus::undecided);
  BOOST_TEST(r.roots.empty());
  BOOST_REQUIRE(!r.undecided.empty());
  bool covered = false;
  for (const auto& u : r.undecided) {
    BOOST_TEST_MESSAGE("undecided " << u.reason << " [" << u.box.bounds[0][0] << ", " << u.box.bounds[0][1] << "] × ["
                                    << u.box.bounds[1][0] << ", " << u.box.bounds[1][1] << "]");
    covered = covered || (u.box.bounds[0][0] <= 1 && 1 <= u.box.bounds[0][1] && u.box.bounds[1][0] <= 0 &&
                          0 <= u.box.bounds[1][1]);
  }
  BOOST_TEST(covered);
}

BOOST_AUTO_TEST_CASE(sphere_critical_points_are_plus_minus_d) {
  const auto system = surface_critical_system(catalog_entry("sphere").surface());
  const Vec3 d = unit_vector({0.3, -0.5, 0.8});
  const auto frame = orthonormal_frame(d);
  const std::vector<double> parameters{frame.a[0], frame.a[1], frame.a[2], frame.b[0], frame.b[1], frame.b[2]};
  const auto r = solve(system, parameters, Domain::from_box({{{-1.5, 1.5}}, {{-1.5, 1.5}}, {{-1.5, 1.5}}}));
  BOOST_TEST(r.status == SolveStatus::complete);
  BOOST_TEST(r.roots.size() == 2u);
  BOOST_TEST(has_root(r, {d[0], d[1], d[2]}));
  BOOST_TEST(has_root(r, {-d[0], -d[1], -d[2]}));
  for (const auto& root : r.roots)
    for (int k = 0; k < 3; ++k) BOOST_TEST(std::abs(root.world[k] - root.midpoint[k]) < 1e-15);
}

BOOST_AUTO_TEST_CASE(tanglecube_has_24_critical_points_in_direction_z) {
  // E = g(x) + g(y) + g(z) + 11.8, g(t) = t⁴ − 5t²; ∇E ∥ e_z ⇔ g'(x) = g'(y) = 0 ⇔ x, y ∈ {0, ±√(5/2)},
  // g(0) = 0, g(±√(5/2)) = −25/4.  Then z⁴ − 5z² + c = 0 with c = 11.8 + g(x) + g(y):
  //  x = y = 0: c = 11.8, no real z;  one of x, y non-zero (4 pairs): c = 5.55, z² = (5 ± √2.8)/2,
  //  4 values of z;  both non-zero (4 pairs): c = −0.7, z² = (5 + √27.8)/2, 2 values.  16 + 8 = 24.
  const auto system = surface_critical_system(catalog_entry("tanglecube").surface());
  const std::vector<double> parameters{1, 0, 0, 0, 1, 0};  // a = e_x, b = e_y
  // The certificate of completeness is not proved on all of this large box within its budget:
  // the pieces left come back undecided, and the roots found there are kept.
  const auto r = solve(system, parameters, Domain::from_box({{{-3.0, 3.0}}, {{-3.0, 3.0}}, {{-3.0, 3.0}}}));
  BOOST_TEST_MESSAGE("tanglecube: " << r.status << ", " << r.certificate.pieces.size() << " pieces proved, "
                                    << r.certificate.unproved.size() << " not");
  BOOST_TEST(r.status != SolveStatus::time_limit);
  BOOST_TEST((r.status == SolveStatus::complete) == r.undecided.empty());
  BOOST_TEST(r.roots.size() == 24u);
  BOOST_TEST(r.counters.paths == 36u);
  const double s = std::sqrt(2.5);
  BOOST_TEST(has_root(r, {s, 0, std::sqrt((5 + std::sqrt(2.8)) / 2)}));
  BOOST_TEST(has_root(r, {0, -s, -std::sqrt((5 - std::sqrt(2.8)) / 2)}));
  BOOST_TEST(has_root(r, {-s, s, std::sqrt((5 + std::sqrt(27.8)) / 2)}));
}

BOOST_AUTO_TEST_CASE(line_meets_torus_in_four_points) {
  // torus (R = 1, r = 0.4) and the line (−2, 0.3, 0.1) + t (1, 0, 0): with w = x², the roots solve
  // w² − 2.12 w + 0.5236 = 0, so x = ±√w and t = x + 2.
  const auto system = surface_line_system(catalog_entry("torus").surface());
  const std::vector<double> parameters{-2, 0.3, 0.1, 1, 0, 0};
  const auto r = solve(system, parameters, Domain::from_box({{{0.0, 4.0}}}));
  BOOST_TEST(r.status == SolveStatus::complete);
  BOOST_TEST(r.roots.size() == 4u);
  for (double sign_w : {-1.0, 1.0})
    for (double sign_x : {-1.0, 1.0}) {
      const double w = (2.12 + sign_w * std::sqrt(2.4)) / 2;
      const double t = sign_x * std::sqrt(w) + 2;
      BOOST_TEST(has_root(r, {t}), "t = " << t);
    }
  for (const auto& root : r.roots) {
    BOOST_TEST(std::abs(root.world[0] - (root.midpoint[0] - 2)) < 1e-14);
    BOOST_TEST(std::abs(root.world[1] - 0.3) < 1e-15);
  }
}

BOOST_AUTO_TEST_CASE(reproducible_for_a_seed_and_seed_independent_roots) {
  const auto s = make_system({X() * X() * X() - 2 * X() * Y() + Y() * Y() - GiNaC::numeric(1, 3),
                              X() * X() + 3 * Y() * Y() * Y() - X() - 1},
                             {X(), Y()});
  const auto domain = Domain::from_box({{{-3.0, 3.0}}, {{-3.0, 3.0}}});
  const auto a = solve(s, {}, domain, 7), b = solve(s, {}, domain, 7), c = solve(s, {}, domain, 8);
  BOOST_TEST(a.status == SolveStatus::complete);
  BOOST_REQUIRE(a.roots.size() == b.roots.size());
  for (std::size_t i = 0; i < a.roots.size(); ++i) {
    BOOST_TEST(a.roots[i].midpoint == b.roots[i].midpoint, boost::test_tools::per_element());
    BOOST_TEST(a.roots[i].box.bounds == b.roots[i].box.bounds);
  }
  BOOST_TEST(a.counters.paths == b.counters.paths);
  BOOST_REQUIRE(c.roots.size() == a.roots.size());
  for (const auto& root : c.roots) BOOST_TEST(has_root(a, root.midpoint));
}

BOOST_AUTO_TEST_CASE(univariate_cubic) {
  const auto s = make_system({(X() - 1) * (X() - 2) * (X() + 3)}, {X()});
  const auto r = solve(s, {}, Domain::from_box({{{-5.0, 1.5}}}));
  BOOST_TEST(r.status == SolveStatus::complete);
  BOOST_TEST(r.roots.size() == 2u);
  BOOST_TEST(has_root(r, {1.0}));
  BOOST_TEST(has_root(r, {-3.0}));
}

BOOST_AUTO_TEST_CASE(time_limit_returns_the_domain_undecided) {
  const auto s = make_system({X() * X() + Y() * Y() - 1, Y() - X()}, {X(), Y()});
  const CompiledSystem compiled(s);
  HomotopyOptions options;
  options.time_limit_seconds = 1e-12;
  const auto r = solve_homotopy(compiled, {2, 1}, {}, Domain::from_box({{{-2.0, 2.0}}, {{-2.0, 2.0}}}), options);
  BOOST_TEST(r.status == SolveStatus::time_limit);
  BOOST_REQUIRE(!r.undecided.empty());
  BOOST_TEST(r.undecided.back().reason == UndecidedReason::budget);
  BOOST_TEST(r.undecided.back().box.bounds[0][0] == -2.0);
}

BOOST_AUTO_TEST_CASE(failed_paths_make_the_whole_domain_undecided) {
  // with a budget of 3 steps per path no path can reach s = 1: nothing may be certified or dropped
  const auto s = make_system({X() * X() + Y() * Y() - 1, Y() - X()}, {X(), Y()});
  const CompiledSystem compiled(s);
  HomotopyOptions options;
  options.max_steps_per_path = 3;
  const auto r = solve_homotopy(compiled, {2, 1}, {}, Domain::from_box({{{-2.0, 2.0}}, {{-2.0, 2.0}}}), options);
  BOOST_TEST(r.status == SolveStatus::undecided);
  BOOST_TEST(r.roots.empty());
  BOOST_REQUIRE(r.undecided.size() == 1u);
  BOOST_TEST(r.undecided[0].reason == UndecidedReason::precision);
  BOOST_TEST(r.undecided[0].box.bounds[0][0] == -2.0);
  BOOST_TEST(r.undecided[0].box.bounds[1][1] == 2.0);
  BOOST_TEST(r.counters.paths == 2u);
}

BOOST_AUTO_TEST_CASE(invalid_arguments_throw) {
  const auto s = make_system({X() * X() + Y() * Y() - 1, Y() - X()}, {X(), Y()});
  const CompiledSystem compiled(s);
  const auto box2 = Domain::from_box({{{-2.0, 2.0}}, {{-2.0, 2.0}}});
  BOOST_CHECK_THROW((void)solve_homotopy(compiled, {2}, {}, box2), PreconditionViolation);
  BOOST_CHECK_THROW((void)solve_homotopy(compiled, {2, 0}, {}, box2), InvalidInput);  // a constant equation
  BOOST_CHECK_THROW((void)solve_homotopy(compiled, {2, 1}, {1.0}, box2), PreconditionViolation);
  BOOST_CHECK_THROW((void)solve_homotopy(compiled, {2, 1}, {}, Domain::from_box({{{-2.0, 2.0}}})),
                    PreconditionViolation);
  const auto over = make_system({X() * X() + Y() * Y() - 1, Y() - X(), X()}, {X(), Y()});
  BOOST_CHECK_THROW((void)solve_homotopy(CompiledSystem(over), {2, 1, 1}, {}, box2), PreconditionViolation);
}

BOOST_AUTO_TEST_CASE(cauchy_endgame_finds_a_triple_root_with_winding_number_three) {
  // (2x − 1)³ (x + 2): the three paths to the triple root x = 1/2 form one cycle (c = 3); Newton
  // would only reach |x − 1/2| ~ ε^{1/3} there, the Cauchy estimate is far better.  (Not (x − 1)³:
  // x = 1 also solves the start equation x⁴ = 1, so one path would stay at x = 1 and c = 2.)
  const auto s = make_system({GiNaC::pow(2 * X() - 1, 3) * (X() + 2)}, {X()});
  const auto ends = track_all(s);
  BOOST_REQUIRE(ends.size() == 4u);
  BOOST_TEST(count(ends, detail::PathOutcome::singular) == 3u);
  BOOST_TEST(count(ends, detail::PathOutcome::finite) == 1u);
  for (const auto& end : ends) {
    BOOST_TEST_MESSAGE(end.outcome << " c = " << end.winding << " u = " << end.point[0] << " steps " << end.steps
                                   << " + " << end.rejections << " rejected");
    if (end.outcome == detail::PathOutcome::singular) {
      BOOST_TEST(end.winding == 3);
      BOOST_TEST(distance_to(end.point, {0.5}) <= 1e-6);
      BOOST_TEST(end.last_correction <= 1e-6);  // its own accuracy estimate
    } else {
      BOOST_TEST(end.winding <= 1);  // 0: finished directly, without a loop
      BOOST_TEST(distance_to(end.point, {-2.0}) <= 1e-12);
    }
  }
  // the solver: −2 certified, 1/2 undecided, never certified
  const auto r = solve(s, {}, Domain::from_box({{{-3.0, 3.0}}}), 1);
  const HomotopyStatistics& statistics = r.statistics;
  BOOST_TEST(r.status == SolveStatus::undecided);
  BOOST_REQUIRE(r.roots.size() == 1u);
  BOOST_TEST(has_root(r, {-2.0}));
  // the pieces around the triple root cannot be proved: a small undecided box holds it
  BOOST_REQUIRE(r.undecided.size() == 1u);
  BOOST_TEST(r.undecided[0].reason == UndecidedReason::precision);
  BOOST_TEST(r.undecided[0].box.bounds[0][0] <= 0.5);
  BOOST_TEST(r.undecided[0].box.bounds[0][1] >= 0.5);
  BOOST_TEST(r.undecided[0].box.bounds[0][1] - r.undecided[0].box.bounds[0][0] <= 0.1);
  BOOST_TEST(statistics.singular == 3u);
  BOOST_TEST(statistics.finite == 1u);
  BOOST_TEST(statistics.max_winding == 3);
}

BOOST_AUTO_TEST_CASE(an_endgame_whose_loops_do_not_close_fails_the_path) {
  // the triple root needs c = 3 loops; allowing at most 2 the three paths must come back failed
  const auto s = make_system({GiNaC::pow(2 * X() - 1, 3) * (X() + 2)}, {X()});
  auto settings = detail::TrackerSettings::defaults();
  settings.endgame_max_winding = 2;
  const auto ends = track_all(s, settings);
  BOOST_TEST(count(ends, detail::PathOutcome::failed) == 3u);
  BOOST_TEST(count(ends, detail::PathOutcome::finite) == 1u);
  // and one that must conclude before t = 0.1: the Cauchy estimates at the triple root need two
  // levels, so those three paths fail; the regular one finishes directly
  settings = detail::TrackerSettings::defaults();
  settings.endgame_min_t = 0.09;
  const auto early = track_all(s, settings);
  BOOST_TEST(count(early, detail::PathOutcome::failed) == 3u);
  BOOST_TEST(count(early, detail::PathOutcome::finite) == 1u);
}

BOOST_AUTO_TEST_CASE(an_endpoint_estimate_that_is_not_a_zero_fails_the_path) {
  // x² − 2 with an endgame that accepts a poor estimate: no direct finish, valuations taken as
  // settled at once, so the loops start at t = 0.35, 2 samples per loop (the trapezoid rule's error
  // is then O(t_k²): the estimate at t = 0.175 is about 4e-3 from ±√2, the branch point of the
  // paths being at |t| ≈ 0.74), and any two successive estimates taken to agree.  Newton may move
  // an estimate only homotopy_endpoint_newton_travel = 1e-3 (relative), so it cannot reach ±√2 from there: a path may end finite
  // only at a zero of f, else it has failed.
  const auto s = make_system({X() * X() - 2}, {X()});
  for (const auto& end : track_all(s)) {  // default settings: both zeros, regular
    BOOST_TEST(end.outcome == detail::PathOutcome::finite);
    BOOST_TEST(std::abs(end.point[0] * end.point[0] - 2.0) <= 1e-12);
  }
  const auto ends = track_all(s, poor_endgame(2));
  BOOST_REQUIRE(ends.size() == 2u);
  for (const auto& end : ends) {
    BOOST_TEST_MESSAGE(end.outcome << " c = " << end.winding << " u = " << end.point[0]);
    if (end.outcome == detail::PathOutcome::finite)
      BOOST_TEST(std::abs(end.point[0] * end.point[0] - 2.0) <= 1e-12, "finite endpoint " << end.point[0]);
  }
  BOOST_TEST(count(ends, detail::PathOutcome::failed) == 2u);
}

BOOST_AUTO_TEST_CASE(a_singular_estimate_must_pass_the_residual_test) {
  // x² + y² = 1 and (x − 2)² + y² = 1 touch at (1, 0) (c = 2).  With the poor endgame of the test
  // above (loops from t = 0.35, one sample per loop, any two estimates taken to agree) the estimate
  // is off by a few 1e-7, so ‖f‖/‖J_f‖ is about 1e-7: it passes the default bound
  // (homotopy_singular_endpoint_residual = 1e-6) but not a bound of 1e-9, and those paths must then
  // fail rather than end singular.  The default endgame's estimate passes even that bound.
  const auto s = make_system({X() * X() + Y() * Y() - 1, (X() - 2) * (X() - 2) + Y() * Y() - 1}, {X(), Y()});
  auto strict = detail::TrackerSettings::defaults();
  strict.singular_residual = 1e-9;
  BOOST_TEST(count(track_all(s, strict), detail::PathOutcome::singular) == 2u);
  auto poor = poor_endgame(1);
  const auto accepted = track_all(s, poor);
  BOOST_TEST(count(accepted, detail::PathOutcome::singular) == 2u);
  for (const auto& end : accepted)
    if (end.outcome == detail::PathOutcome::singular) {
      BOOST_TEST(std::abs(end.point[0] - 1.0) <= 1e-5);
      BOOST_TEST(std::abs(end.point[0] - 1.0) >= 1e-9);  // a poor estimate indeed
    }
  poor.singular_residual = 1e-9;
  const auto rejected = track_all(s, poor);
  BOOST_TEST(count(rejected, detail::PathOutcome::singular) == 0u);
  BOOST_TEST(count(rejected, detail::PathOutcome::failed) == 2u);
}

BOOST_AUTO_TEST_CASE(cauchy_endgame_at_tangent_circles_and_the_circular_points) {
  // x² + y² = 1 and (x − 2)² + y² = 1 touch at (1, 0) (multiplicity 2, one cycle of c = 2);
  // the other two paths go to the circular points at infinity (1 : ±i : 0).
  const auto s = make_system({X() * X() + Y() * Y() - 1, (X() - 2) * (X() - 2) + Y() * Y() - 1}, {X(), Y()});
  const auto ends = track_all(s);
  BOOST_REQUIRE(ends.size() == 4u);
  BOOST_TEST(count(ends, detail::PathOutcome::diverging) == 2u);
  BOOST_TEST(count(ends, detail::PathOutcome::singular) == 2u);
  for (const auto& end : ends) {
    BOOST_TEST_MESSAGE(end.outcome << " c = " << end.winding << " u = (" << end.point[0] << ", " << end.point[1]
                                   << ") steps " << end.steps << " + " << end.rejections << " rejected");
    if (end.outcome != detail::PathOutcome::singular) continue;
    BOOST_TEST(end.winding == 2);
    BOOST_TEST(distance_to(end.point, {1.0, 0.0}) <= 1e-6);
  }
}

BOOST_AUTO_TEST_CASE(three_paths_to_a_singular_point_at_infinity) {
  // y = x² and y = x² + x − 1 meet at (1, 1) only: of the 4 Bézout paths, 3 go to the point
  // (0 : 1 : 0) at infinity, where the homogenised curves YW = X² and YW = X² + XW − W² meet with
  // intersection multiplicity 3.
  const auto s = make_system({Y() - X() * X(), Y() - X() * X() - X() + 1}, {X(), Y()});
  const auto ends = track_all(s);
  BOOST_TEST(count(ends, detail::PathOutcome::diverging) == 3u);
  BOOST_TEST(count(ends, detail::PathOutcome::finite) == 1u);
  const auto r = solve(s, {}, Domain::from_box({{{-3.0, 3.0}}, {{-3.0, 3.0}}}), 1);
  const HomotopyStatistics& statistics = r.statistics;
  BOOST_TEST(r.status == SolveStatus::complete);
  BOOST_REQUIRE(r.roots.size() == 1u);
  BOOST_TEST(has_root(r, {1.0, 1.0}));
  BOOST_TEST(statistics.diverging == 3u);
  BOOST_TEST(statistics.finite == 1u);
  BOOST_TEST(statistics.failed == 0u);
}

BOOST_AUTO_TEST_CASE(torus_critical_points_and_its_paths_to_infinity) {
  // E = (x² + y² + z² + 0.84)² − 4(x² + y²), direction d ∥ (3, −5, 8): 4 · 3 · 3 = 36 paths.  The
  // affine solutions number 8 with multiplicity (dimension of the quotient ring, Gröbner basis in
  // sympy for this direction): the 4 real critical points of the height ⟨d, ·⟩ on the torus, and
  // the singular points (0, 0, ±i√0.84) of the complexified torus (∇E = 0 there), 2 each, so 28
  // paths go to infinity, where the solution set is singular.
  const auto system = surface_critical_system(catalog_entry("torus").surface());
  const auto frame = orthonormal_frame(unit_vector({3, -5, 8}));
  const std::vector<double> parameters{frame.a[0], frame.a[1], frame.a[2], frame.b[0], frame.b[1], frame.b[2]};
  for (std::uint64_t seed : {1, 2}) {
    const auto r = solve(system, parameters, box_domain(catalog_entry("torus").box), seed);
    const HomotopyStatistics& statistics = r.statistics;
    BOOST_TEST_MESSAGE("seed " << seed << ": finite " << statistics.finite << " singular " << statistics.singular
                               << " diverging " << statistics.diverging << " failed " << statistics.failed
                               << ", steps per path " << (statistics.steps + statistics.rejections) / 36.0
                               << ", max winding " << statistics.max_winding);
    // the whole box is large for the certificate: what it cannot prove comes back undecided
    BOOST_TEST((r.status == SolveStatus::complete) == r.undecided.empty());
    BOOST_TEST(r.roots.size() == 4u);
    BOOST_TEST(statistics.diverging == 28u);
    BOOST_TEST(statistics.finite == 4u);
    BOOST_TEST(statistics.singular == 4u);
    BOOST_TEST(statistics.failed == 0u);
  }
}

BOOST_AUTO_TEST_CASE(two_close_roots_are_not_merged_by_the_endgame) {
  // Kostlan degrees (6, 5, 6), seed 104: two real roots 0.07 apart (found and certified by the
  // subdivision solver in the cross-check).  Their paths swap around a branch point close to t = 0,
  // so loops at larger |t| close after 2 loops and their mean converges to the centroid; that
  // must not be taken for a singular endpoint (both roots must be certified).
  const CompiledSystem compiled(kostlan_system({6, 5, 6}, 104));
  HomotopyOptions options;
  options.seed = 104;
  const auto r = solve_homotopy(compiled, {6, 5, 6}, {}, Domain::from_box({{{-1.0, 1.0}}, {{-1.0, 1.0}}, {{-1.0, 1.0}}}),
                                options);
  const HomotopyStatistics& statistics = r.statistics;
  BOOST_TEST(r.status != SolveStatus::time_limit);
  BOOST_TEST(statistics.singular == 0u);
  for (const std::vector<double>& root : {std::vector<double>{-0.402875, 0.186436, 0.832277},
                                         std::vector<double>{-0.360289, 0.170589, 0.760149}}) {
    bool found = false;
    for (const auto& certified : r.roots) {
      double d = 0;
      for (std::size_t i = 0; i < 3; ++i) d = std::max(d, std::abs(certified.midpoint[i] - root[i]));
      found = found || d <= 1e-6;
    }
    BOOST_TEST(found, "root " << root[0] << " " << root[1] << " " << root[2]);
  }
}

BOOST_AUTO_TEST_CASE(near_real_endpoints_are_undecided_not_dropped) {
  // (x − y)² + 0.01 = 0, x + y = 2000, written expanded (interval evaluation cannot exclude a box
  // around (1000, 1000)): the roots x = 1000 ± 0.05i, y = 1000 ∓ 0.05i are regular endpoints with
  // ‖Im u‖∞ / (1 + ‖u‖∞) ≈ 5e-5, above homotopy_real_candidate but within homotopy_near_real.  No
  // real root exists, but the real Jacobian is singular at (1000, 1000): neither certified nor
  // excluded, a box around (1000, 1000) comes back undecided.
  const ex eps = GiNaC::numeric(1, 10);
  const auto s = make_system({X() * X() - 2 * X() * Y() + Y() * Y() + eps * eps, X() + Y() - 2000}, {X(), Y()});
  for (std::uint64_t seed : {1, 2, 3}) {
    const auto r = solve(s, {}, Domain::from_box({{{999.0, 1001.0}}, {{999.0, 1001.0}}}), seed);
    const HomotopyStatistics& statistics = r.statistics;
    BOOST_TEST(statistics.finite == 2u);
    BOOST_TEST(statistics.near_real == 2u);
    BOOST_TEST(r.status == SolveStatus::undecided);
    BOOST_TEST(r.roots.empty());
    // (1000, 1000) lies in an undecided piece (the complex zeros beside it leave no barrier there)
    BOOST_REQUIRE(!r.undecided.empty());
    bool covered = false;
    for (const auto& u : r.undecided)
      covered = covered || (u.reason == UndecidedReason::precision && u.box.bounds[0][0] <= 1000.0 &&
                            u.box.bounds[0][1] >= 1000.0 && u.box.bounds[1][0] <= 1000.0 && u.box.bounds[1][1] >= 1000.0);
    BOOST_TEST(covered);
  }
}

BOOST_AUTO_TEST_CASE(near_real_endpoints_proved_root_free_are_dropped) {
  // x² + 1e-10: endpoints ±1e-5 i, near-real; Krawczyk proves the box around 0 root-free.
  const auto s = make_system({X() * X() + GiNaC::numeric(1, 10000000000)}, {X()});
  const auto r = solve(s, {}, Domain::from_box({{{-1.0, 1.0}}}), 1);
  const HomotopyStatistics& statistics = r.statistics;
  BOOST_TEST(statistics.near_real == 2u);
  BOOST_TEST(r.status == SolveStatus::complete);
  BOOST_TEST(r.roots.empty());
  BOOST_TEST(r.undecided.empty());
}

BOOST_AUTO_TEST_CASE(diverging_paths_near_the_domain_are_counted) {
  // y = x⁴ and y = x⁴ + x − 1 meet at (1, 1) only: 15 of the 16 paths go to infinity, slowly
  // (their last points, where the valuation test declares them diverging, have ‖u‖∞ ≈ 10).  On
  // [−10, 10]² those points are near the domain and counted; the root is certified.  On
  // [−0.5, 0.5]² (no root) the same paths end far from it: complete.
  const auto s = make_system({Y() - GiNaC::pow(X(), 4), Y() - GiNaC::pow(X(), 4) - X() + 1}, {X(), Y()});
  for (std::uint64_t seed : {1, 2}) {
    const auto r = solve(s, {}, Domain::from_box({{{-10.0, 10.0}}, {{-10.0, 10.0}}}), seed);
    const HomotopyStatistics& statistics = r.statistics;
    BOOST_TEST(statistics.diverging == 15u);
    BOOST_TEST(statistics.diverging_near_domain >= 1u);
    // the certificate decides; the root is certified either way
    BOOST_TEST((r.status == SolveStatus::complete) == r.undecided.empty());
    BOOST_REQUIRE(r.roots.size() == 1u);
    BOOST_TEST(has_root(r, {1.0, 1.0}));

    const auto small = solve(s, {}, Domain::from_box({{{-0.5, 0.5}}, {{-0.5, 0.5}}}), seed);
    const HomotopyStatistics& far = small.statistics;
    BOOST_TEST(far.diverging == 15u);
    BOOST_TEST(far.diverging_near_domain == 0u);
    BOOST_TEST(small.status == SolveStatus::complete);
    BOOST_TEST(small.roots.empty());
  }
}

BOOST_AUTO_TEST_CASE(a_deadline_in_the_past_stops_the_first_path) {
  const auto s = make_system({X() * X() + Y() * Y() - 1, Y() - X()}, {X(), Y()});
  const CompiledSystem compiled(s);
  HomotopyOptions options;
  options.deadline = std::chrono::steady_clock::now() - std::chrono::seconds(1);
  const auto r = solve_homotopy(compiled, {2, 1}, {}, Domain::from_box({{{-2.0, 2.0}}, {{-2.0, 2.0}}}), options);
  const HomotopyStatistics& statistics = r.statistics;
  BOOST_TEST(r.status == SolveStatus::time_limit);
  BOOST_TEST(r.roots.empty());
  BOOST_REQUIRE(r.undecided.size() == 1u);
  BOOST_TEST(r.undecided[0].reason == UndecidedReason::budget);
  BOOST_TEST(r.undecided[0].box.bounds[0][0] == -2.0);
  BOOST_TEST(r.counters.paths == 1u);  // started, and abandoned at its first step
  BOOST_TEST(statistics.steps == 0u);
  BOOST_TEST(statistics.finite + statistics.singular + statistics.diverging + statistics.failed == 0u);
}

BOOST_AUTO_TEST_CASE(a_deadline_cuts_a_long_solve) {
  // Kostlan degrees (6, 5, 6): 180 paths.  A deadline a tenth of the way through (tracking or
  // certificate) stops the solve there, with status time_limit and the domain undecided, never a
  // clean result.
  const CompiledSystem compiled(kostlan_system({6, 5, 6}, 104));
  const auto domain = Domain::from_box({{{-1.0, 1.0}}, {{-1.0, 1.0}}, {{-1.0, 1.0}}});
  HomotopyOptions options;
  options.seed = 104;
  const auto full_start = std::chrono::steady_clock::now();
  const auto full = solve_homotopy(compiled, {6, 5, 6}, {}, domain, options);
  const double full_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - full_start).count();
  BOOST_TEST(full.status != SolveStatus::time_limit);
  BOOST_TEST(full.counters.paths >= 180u);

  const double budget = full_seconds / 10;
  const auto start = std::chrono::steady_clock::now();
  options.deadline = start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                 std::chrono::duration<double>(budget));
  const auto cut = solve_homotopy(compiled, {6, 5, 6}, {}, domain, options);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  BOOST_TEST_MESSAGE("full solve " << full_seconds << " s; cut at " << budget << " s after " << seconds << " s, "
                                   << cut.counters.paths << " paths");
  BOOST_TEST(cut.status == SolveStatus::time_limit);
  BOOST_REQUIRE(!cut.undecided.empty());
  BOOST_TEST(cut.undecided.back().reason == UndecidedReason::budget);
  BOOST_TEST(seconds < full_seconds / 2);  // returns at the deadline, not after the solve
}

BOOST_AUTO_TEST_CASE(path_outcome_prints) {
  std::ostringstream out;
  out << detail::PathOutcome::finite << ' ' << detail::PathOutcome::singular << ' ' << detail::PathOutcome::diverging
      << ' ' << detail::PathOutcome::failed;
  BOOST_TEST(out.str() == "finite singular diverging failed");
}

BOOST_AUTO_TEST_SUITE_END()
