#include "solvers/univariate_isolator.h"

#include <cmath>
#include <random>

#include <boost/multiprecision/cpp_bin_float.hpp>
#include <boost/multiprecision/gmp.hpp>
#include <boost/test/unit_test.hpp>

#include "common/errors.h"
#include "symbolic/catalog.h"
#include "solvers/primitives.h"

using namespace delmesh;

namespace {

struct LineProblem {
  Surface surface;
  CompiledSystem line;
  LinePolynomial polynomial;
  explicit LineProblem(const Surface& s)
      : surface(s), line(surface_line_system(s)), polynomial(s) {}
};

const LineProblem& torus() {
  static const LineProblem problem(catalog_entry("torus").surface());
  return problem;
}
const LineProblem& sphere() {
  static const LineProblem problem(catalog_entry("sphere").surface());
  return problem;
}

using Rational = boost::multiprecision::mpq_rational;

//! q ∈ [lo, hi], exactly (doubles convert exactly to rationals).
bool holds(double lo, double hi, const Rational& q) { return Rational(lo) <= q && q <= Rational(hi); }

//! Each certified interval holds exactly one of the exact zeros `exact`, and each zero is in one.
void check_exact_roots(const SolveResult& r, const std::vector<Rational>& exact) {
  BOOST_TEST(r.status == SolveStatus::complete);
  BOOST_TEST(r.undecided.empty());
  BOOST_REQUIRE_EQUAL(r.roots.size(), exact.size());
  for (std::size_t i = 0; i < exact.size(); ++i) {
    int inside = 0;
    for (const Rational& q : exact) inside += holds(r.roots[i].box.bounds[0][0], r.roots[i].box.bounds[0][1], q);
    BOOST_TEST(inside == 1);
    BOOST_TEST(holds(r.roots[i].box.bounds[0][0], r.roots[i].box.bounds[0][1], exact[i]));  // sorted
  }
}

bool any_reason(const SolveResult& r, UndecidedReason reason) {
  for (const auto& u : r.undecided)
    if (u.reason == reason) return true;
  return false;
}

//! Every certified interval must contain exactly one known root, and no two the same.
void check_roots(const SolveResult& r, const std::vector<double>& expected, double tol = 1e-12) {
  BOOST_TEST(r.status == SolveStatus::complete);
  BOOST_TEST(r.undecided.empty());
  BOOST_REQUIRE_EQUAL(r.roots.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    BOOST_TEST(std::abs(r.roots[i].midpoint[0] - expected[i]) < tol);
    BOOST_TEST(r.roots[i].box.bounds[0][0] <= expected[i] + tol);
    BOOST_TEST(r.roots[i].box.bounds[0][1] >= expected[i] - tol);
  }
}

}  // namespace

BOOST_AUTO_TEST_SUITE(univariate_isolator)

BOOST_AUTO_TEST_CASE(line_through_torus_four_two_zero_roots) {
  const auto& T = torus();
  // Along the x axis: (x² + 0.84)² = 4x² ⇔ |x| = 1 ± 0.4.  t = x + 2.
  for (const LinePolynomial* poly : {&T.polynomial, static_cast<const LinePolynomial*>(nullptr)}) {
    const SolveResult four = isolate_line_roots(T.line, poly, {-2, 0, 0}, {1, 0, 0}, 0, 4);
    check_roots(four, {0.6, 1.4, 2.6, 3.4});
    // World points lie on the torus.
    for (const auto& root : four.roots) BOOST_TEST(std::abs(T.surface.evaluate(root.world)) < 1e-9);
    // Vertical line x = 1, y = 0: (z² + 1.84)² = 4 ⇔ z = ±0.4.  t = z + 1.
    check_roots(isolate_line_roots(T.line, poly, {1, 0, -1}, {0, 0, 1}, 0, 2), {0.6, 1.4});
    // The axis misses the torus.
    check_roots(isolate_line_roots(T.line, poly, {0, 0, -1}, {0, 0, 1}, 0, 2), {});
  }
}

BOOST_AUTO_TEST_CASE(monotone_segment_is_decided_on_its_first_node) {
  const auto& S = sphere();
  // E(p + t v) = (0.9 + t)² + 0.0125 − 1 is increasing on [0, 0.2], negative at 0 and positive at
  // 0.2: exactly one zero, t* = √0.9875 − 0.9, decided without subdividing [0, 0.2].
  const SolveResult crossing = isolate_line_roots(S.line, &S.polynomial, {0.9, 0.1, 0.05}, {1, 0, 0}, 0, 0.2);
  check_roots(crossing, {std::sqrt(0.9875) - 0.9});
  BOOST_TEST(crossing.counters.boxes == 1u);
  // Outside the sphere all along [0, 0.3]: no zero, again on the first node.
  const SolveResult missing = isolate_line_roots(S.line, &S.polynomial, {1.2, 0, 0}, {1, 0, 0}, 0, 0.3);
  check_roots(missing, {});
  BOOST_TEST(missing.counters.boxes == 1u);
  BOOST_TEST(missing.counters.exclusions == 1u);
}

BOOST_AUTO_TEST_CASE(random_lines_bernstein_and_newton_agree) {
  const auto& T = torus();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uni(-1, 1);
  int total = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const std::array<double, 3> p{1.6 * uni(rng), 1.6 * uni(rng), 0.6 * uni(rng)}, v{uni(rng), uni(rng), uni(rng)};
    const SolveResult a = isolate_line_roots(T.line, &T.polynomial, p, v, -1, 1);
    const SolveResult b = isolate_line_roots(T.line, nullptr, p, v, -1, 1);
    if (a.status != SolveStatus::complete)
      for (const auto& u : a.undecided)
        BOOST_TEST_MESSAGE("trial " << trial << " status " << a.status << " undecided [" << u.box.bounds[0][0] << ", "
                                    << u.box.bounds[0][1] << "] " << u.reason << " roots " << a.roots.size()
                                    << " newton " << b.status << " " << b.roots.size());
    BOOST_REQUIRE(a.status == SolveStatus::complete);
    BOOST_REQUIRE(b.status == SolveStatus::complete);
    BOOST_REQUIRE_EQUAL(a.roots.size(), b.roots.size());
    for (std::size_t i = 0; i < a.roots.size(); ++i) {
      BOOST_TEST(std::abs(a.roots[i].midpoint[0] - b.roots[i].midpoint[0]) < 1e-12);
      BOOST_TEST(std::abs(T.surface.evaluate(a.roots[i].world)) < 1e-9);
    }
    total += static_cast<int>(a.roots.size());
  }
  BOOST_TEST(total > 100);  // the random lines do meet the torus
}

BOOST_AUTO_TEST_CASE(tangent_line_double_root_is_singular_never_certified) {
  const auto& S = sphere();
  // p + t v = (1, 0, t − 1): E = (t − 1)², a double root at t = 1 (Lemma 4.7(ii)).
  for (const LinePolynomial* poly : {&S.polynomial, static_cast<const LinePolynomial*>(nullptr)}) {
    const SolveResult r = isolate_line_roots(S.line, poly, {1, 0, -1}, {0, 0, 1}, 0, 2);
    BOOST_TEST(r.roots.empty());
    BOOST_TEST(r.status == SolveStatus::undecided);
    BOOST_REQUIRE(!r.undecided.empty());
    bool covers = false;
    for (const auto& u : r.undecided) {
      BOOST_TEST(u.reason == UndecidedReason::singular_root);
      covers = covers || (u.box.bounds[0][0] <= 1 && u.box.bounds[0][1] >= 1);
    }
    BOOST_TEST(covers);
  }
  // A torus tangent line that is only nearly tangent in double: x = 1.4 (not representable).
  const auto& T = torus();
  const SolveResult r = isolate_line_roots(T.line, &T.polynomial, {1.4, 0, -1}, {0, 0, 1}, 0, 2);
  BOOST_TEST(r.roots.empty());
  BOOST_TEST(any_reason(r, UndecidedReason::singular_root));
}

BOOST_AUTO_TEST_CASE(tangencies_are_singular_and_not_escalated) {
  // A double root stays singular_root and is not handed to MPFI (no precision can certify it):
  // E = (t − 1)² on the sphere, E = exp((t − 1)²) − 1 (interval Newton path), and the
  // near-tangent torus line x = fl(1.4), which runs ~9e-17 inside the tube and meets the torus
  // twice, at z = ±8.4e-9: two zeros closer than the singular width are one singular region.
  const auto& S = sphere();
  for (const LinePolynomial* poly : {&S.polynomial, static_cast<const LinePolynomial*>(nullptr)}) {
    const SolveResult r = isolate_line_roots(S.line, poly, {1, 0, -1}, {0, 0, 1}, 0, 2);
    BOOST_TEST(r.roots.empty());
    BOOST_TEST(any_reason(r, UndecidedReason::singular_root));
    BOOST_TEST(r.counters.precision_escalations == 0u);
  }
  const Surface s = Surface::parse("exp(x^2+y^2+z^2-1)-1");
  const CompiledSystem line(surface_line_system(s));
  const SolveResult tangent = isolate_line_roots(line, nullptr, {0, 1, -1}, {0, 0, 1}, 0, 2);
  BOOST_TEST(tangent.roots.empty());
  BOOST_TEST(any_reason(tangent, UndecidedReason::singular_root));
  BOOST_TEST(tangent.counters.precision_escalations == 0u);
  const auto& T = torus();
  for (const LinePolynomial* poly : {&T.polynomial, static_cast<const LinePolynomial*>(nullptr)}) {
    const SolveResult r = isolate_line_roots(T.line, poly, {1.4, 0, -1}, {0, 0, 1}, 0, 2);
    BOOST_TEST(r.roots.empty());
    BOOST_TEST(r.status == SolveStatus::undecided);
    for (const auto& u : r.undecided) BOOST_TEST(u.reason == UndecidedReason::singular_root);
    BOOST_TEST(r.counters.precision_escalations == 0u);
  }
}

BOOST_AUTO_TEST_CASE(zeros_1e13_apart_are_one_singular_region) {
  // E = (x − 3/10)(x − (3/10 + 10⁻¹³)) + y² + z² along the x axis, t ∈ [0, 1]: two simple zeros
  // closer than the singular width.  Neither path may certify one interval for the pair; the
  // undecided singular_root region must hold both.
  const Surface s = Surface::parse("(x-0.3)*(x-0.3000000000001)+y^2+z^2");
  const LineProblem problem(s);
  const std::vector<Rational> exact{Rational(3, 10), Rational(3000000000001LL, 10000000000000LL)};
  for (const LinePolynomial* poly : {&problem.polynomial, static_cast<const LinePolynomial*>(nullptr)}) {
    const SolveResult r = isolate_line_roots(problem.line, poly, {0, 0, 0}, {1, 0, 0}, 0, 1);
    BOOST_TEST(r.roots.empty());
    BOOST_TEST(r.status == SolveStatus::undecided);
    for (const Rational& q : exact) {
      bool covered = false;
      for (const auto& u : r.undecided)
        covered = covered || (u.reason == UndecidedReason::singular_root && holds(u.box.bounds[0][0], u.box.bounds[0][1], q));
      BOOST_TEST(covered);
    }
  }
}

BOOST_AUTO_TEST_CASE(huge_cancelling_terms_are_decided_in_mpfi) {
  // (x + 10⁸)² − 10¹⁶ − 2·10⁸ x − 1/4 + y² + z² = x² − 1/4 + y² + z², written with terms of 1e16
  // that cancel: along the x axis on [−1, 1] every double enclosure of E is ~4 wide while
  // |E| ≤ 3/4, so interval Newton on the compiled (unexpanded) expression decides nothing in
  // double; 106-bit MPFI certifies the zeros ±1/2.  (The Bernstein path works on the expanded,
  // exact coefficients of x² − 1/4 and needs no MPFI.)
  const Surface s = Surface::parse("(x+100000000)^2-10000000000000000-200000000*x-0.25+y^2+z^2");
  const LineProblem problem(s);
  const SolveResult newton = isolate_line_roots(problem.line, nullptr, {0, 0, 0}, {1, 0, 0}, -1, 1);
  check_exact_roots(newton, {Rational(-1, 2), Rational(1, 2)});
  BOOST_TEST(newton.counters.precision_escalations > 0u);
  BOOST_TEST(newton.counters.boxes < 100u);  // escalated at once, not subdivided to the noise
  check_exact_roots(isolate_line_roots(problem.line, &problem.polynomial, {0, 0, 0}, {1, 0, 0}, -1, 1),
                    {Rational(-1, 2), Rational(1, 2)});
}

BOOST_AUTO_TEST_CASE(zero_within_an_ulp_of_an_end_is_decided_in_mpfi) {
  // The sphere of radius 3/10 along the x axis: zeros t = ±3/10, not doubles.  fl(0.3) lies
  // 1.1e-17 below 3/10, so E(fl(0.3)) ≈ −6.7e-18 is inside double rounding (boundary_root without
  // escalation); in MPFI its sign is certain.
  const Surface s = Surface::parse("x^2+y^2+z^2-0.09");
  const LineProblem problem(s);
  const double lo = 0.3, above = std::nextafter(0.3, 1.0);
  BOOST_REQUIRE(Rational(lo) < Rational(3, 10) && Rational(3, 10) < Rational(above));
  for (const LinePolynomial* poly : {&problem.polynomial, static_cast<const LinePolynomial*>(nullptr)}) {
    // t0 = fl(0.3) < 3/10: the zero 3/10 is inside [t0, 1], within an ulp of t0, and so is −3/10
    // in [−1, −fl(0.3)].
    const SolveResult in = isolate_line_roots(problem.line, poly, {0, 0, 0}, {1, 0, 0}, lo, 1);
    check_exact_roots(in, {Rational(3, 10)});
    BOOST_TEST(in.counters.precision_escalations > 0u);
    const SolveResult negative = isolate_line_roots(problem.line, poly, {0, 0, 0}, {1, 0, 0}, -1, -lo);
    check_exact_roots(negative, {Rational(-3, 10)});
    // t0 = the next double above 3/10: no zero in [t0, 1]; proved, not left at the boundary.
    const SolveResult out = isolate_line_roots(problem.line, poly, {0, 0, 0}, {1, 0, 0}, above, 1);
    check_exact_roots(out, {});
  }
}

BOOST_AUTO_TEST_CASE(root_at_an_end_is_boundary_root) {
  const auto& S = sphere();
  for (const LinePolynomial* poly : {&S.polynomial, static_cast<const LinePolynomial*>(nullptr)}) {
    // Through the centre along x: roots t = ±1; t0 = −1 is a root, +1 is outside [−1, 0.5].
    const SolveResult r = isolate_line_roots(S.line, poly, {0, 0, 0}, {1, 0, 0}, -1, 0.5);
    BOOST_TEST(r.roots.empty());
    BOOST_TEST(r.status == SolveStatus::undecided);
    BOOST_REQUIRE_EQUAL(r.undecided.size(), 1u);
    BOOST_TEST(r.undecided[0].reason == UndecidedReason::boundary_root);
    BOOST_TEST(r.undecided[0].box.bounds[0][0] == -1.0);
    // Both ends roots; an interior root stays certified.
    const SolveResult both = isolate_line_roots(S.line, poly, {0, 0, 0}, {1, 0, 0}, -1, 1);
    BOOST_TEST(both.roots.empty());
    BOOST_TEST(both.undecided.size() == 2u);
    const SolveResult interior = isolate_line_roots(S.line, poly, {0, 0, 0}, {1, 0, 0}, -1, 2);
    BOOST_REQUIRE_EQUAL(interior.roots.size(), 1u);
    BOOST_TEST(std::abs(interior.roots[0].midpoint[0] - 1) < 1e-14);
    BOOST_TEST(interior.undecided.size() == 1u);
  }
}

BOOST_AUTO_TEST_CASE(root_at_a_bisection_point_is_certified) {
  const auto& S = sphere();
  // The line (t, 0, 0) meets the sphere at t = ±1; on [−1.5, 3.5] the root t = 1 is exactly the
  // first bisection point, so the split must move off it.
  const SolveResult r = isolate_line_roots(S.line, &S.polynomial, {0, 0, 0}, {1, 0, 0}, -3, 1.5);
  check_roots(r, {-1, 1});
  const SolveResult mid = isolate_line_roots(S.line, &S.polynomial, {0, 0, 0}, {1, 0, 0}, -1.5, 3.5);
  check_roots(mid, {-1, 1});
}

BOOST_AUTO_TEST_CASE(non_polynomial_surface_uses_interval_newton) {
  // exp(x² + y² + z² − 1) − 1 = 0 is the unit sphere.
  const Surface s = Surface::parse("exp(x^2+y^2+z^2-1)-1");
  const CompiledSystem line(surface_line_system(s));
  check_roots(isolate_line_roots(line, nullptr, {0, 0, 0}, {0, 1, 0}, -2, 2), {-1, 1});
  const SolveResult tangent = isolate_line_roots(line, nullptr, {0, 1, -1}, {0, 0, 1}, 0, 2);
  BOOST_TEST(tangent.roots.empty());
  BOOST_TEST(any_reason(tangent, UndecidedReason::singular_root));
}

BOOST_AUTO_TEST_CASE(line_inside_the_surface_is_non_isolated) {
  // E = (x − y)(z² + (x − y)²): E ≡ 0 along the line x = y, z = 0.
  const Surface s = Surface::parse("(x-y)*z^2+(x-y)^3");
  const LineProblem problem(s);
  const SolveResult r = isolate_line_roots(problem.line, &problem.polynomial, {0, 0, 0}, {1, 1, 0}, -1, 1);
  BOOST_TEST(r.roots.empty());
  BOOST_TEST(r.status == SolveStatus::non_isolated);
  BOOST_TEST(r.counters.boxes < 5000u);
  // The undecided regions cover [−1, 1].
  double covered = 0;
  for (const auto& u : r.undecided) covered += u.box.bounds[0][1] - u.box.bounds[0][0];
  BOOST_TEST(covered >= 2.0 - 1e-9);
}

BOOST_AUTO_TEST_CASE(box_budget_returns_the_rest_as_undecided) {
  const auto& T = torus();
  UnivariateOptions options;
  options.box_budget = 3;
  const SolveResult r = isolate_line_roots(T.line, &T.polynomial, {-2, 0, 0}, {1, 0, 0}, 0, 4, options);
  BOOST_TEST(r.status == SolveStatus::box_limit);
  BOOST_TEST(any_reason(r, UndecidedReason::budget));
  double covered = 0;
  for (const auto& u : r.undecided) covered += u.box.bounds[0][1] - u.box.bounds[0][0];
  for (const auto& root : r.roots) covered += root.box.bounds[0][1] - root.box.bounds[0][0];
  BOOST_TEST(r.roots.size() + r.undecided.size() >= 1u);
  // Roots not certified lie in undecided intervals.
  for (double t : {0.6, 1.4, 2.6, 3.4}) {
    bool found = false;
    for (const auto& u : r.undecided) found = found || (u.box.bounds[0][0] <= t && t <= u.box.bounds[0][1]);
    for (const auto& root : r.roots) found = found || (root.box.bounds[0][0] <= t && t <= root.box.bounds[0][1]);
    BOOST_TEST(found);
  }
}

namespace {

//! E = Π_{i=1..n} (x − r_i) + y² + z², r_i = (2i − n − 1)/n ∈ (−1, 1): along the x axis the zeros
//! are exactly the r_i, 2/n apart (a degree-n line polynomial with n simple zeros in [−1, 1]).
struct ProductRoots {
  LineProblem problem;
  std::vector<Rational> roots;
  explicit ProductRoots(int n) : problem(surface(n)) {
    for (int i = 1; i <= n; ++i) roots.push_back(Rational(2 * i - n - 1, n));
  }
  static Surface surface(int n) {
    std::string text;
    for (int i = 1; i <= n; ++i)
      text += (i > 1 ? "*" : "") + std::string("(x-(") + std::to_string(2 * i - n - 1) + "/" + std::to_string(n) + "))";
    return Surface::parse(text + "+y^2+z^2");
  }
};

const ProductRoots& twenty_roots() {
  static const ProductRoots problem(20);
  return problem;
}

//! Every zero is in a certified or an undecided interval (nothing dropped), and every certified
//! interval holds exactly one zero (nothing invented).
void check_nothing_dropped(const SolveResult& r, const std::vector<Rational>& zeros) {
  for (const Rational& t : zeros) {
    bool found = false;
    for (const auto& u : r.undecided) found = found || holds(u.box.bounds[0][0], u.box.bounds[0][1], t);
    for (const auto& root : r.roots) found = found || holds(root.box.bounds[0][0], root.box.bounds[0][1], t);
    BOOST_TEST(found);
  }
  for (const auto& root : r.roots) {
    int inside = 0;
    for (const Rational& t : zeros) inside += holds(root.box.bounds[0][0], root.box.bounds[0][1], t);
    BOOST_TEST(inside == 1);
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(degree_56_root_at_an_end_is_not_excluded) {
  // E = x^24 − 1 + y^56 along the x axis, t ∈ [0, 1]: a degree-56 line polynomial t^24 − 1 whose
  // last Bernstein coefficient on [0, 1] is E(1) = 0.  Its enclosure must keep 0 (a rounded-up
  // C(56, 24) made it certainly negative, every coefficient negative, and the zero excluded).
  const LineProblem P(Surface::parse("x^24-1+y^56"));
  BOOST_REQUIRE_EQUAL(P.polynomial.degree(), 56);
  const SolveResult r = isolate_line_roots(P.line, &P.polynomial, {0, 0, 0}, {1, 0, 0}, 0, 1);
  check_nothing_dropped(r, {Rational(1)});
  BOOST_TEST(r.roots.empty());
  BOOST_REQUIRE_EQUAL(r.undecided.size(), 1u);
  BOOST_TEST(r.undecided[0].reason == UndecidedReason::boundary_root);
}

BOOST_AUTO_TEST_CASE(many_roots_of_a_product_are_all_certified) {
  // Regression: the Bernstein path used to stop with non_isolated here (after 9 of 20, 5 of 30
  // zeros).  The double enclosures of the Bernstein coefficients on [−1, 1] (Taylor shift of the
  // expanded polynomial) are far wider than E between the middle zeros; such nodes are now handed
  // to interval Newton on the product form, which decides them in double.
  for (int n : {20, 30}) {
    const ProductRoots P(n);
    for (const LinePolynomial* poly : {&P.problem.polynomial, static_cast<const LinePolynomial*>(nullptr)}) {
      const SolveResult r = isolate_line_roots(P.problem.line, poly, {0, 0, 0}, {1, 0, 0}, -1, 1);
      check_exact_roots(r, P.roots);
      BOOST_TEST(r.counters.precision_escalations == 0u);
    }
  }
}

BOOST_AUTO_TEST_CASE(time_budget_returns_the_rest_as_undecided) {
  const auto& P = twenty_roots();
  UnivariateOptions options;
  options.time_limit_seconds = 1e-9;  // far less than the ≥ 40 subintervals the 20 zeros need
  for (const LinePolynomial* poly : {&P.problem.polynomial, static_cast<const LinePolynomial*>(nullptr)}) {
    const SolveResult r = isolate_line_roots(P.problem.line, poly, {0, 0, 0}, {1, 0, 0}, -1, 1, options);
    BOOST_TEST((r.status == SolveStatus::time_limit || r.status == SolveStatus::complete));
    if (r.status == SolveStatus::time_limit) BOOST_TEST(any_reason(r, UndecidedReason::budget));
    check_nothing_dropped(r, P.roots);
  }
}

// A start given in the options is where the time limit and counters.seconds count from: one
// second before the call, a one-second budget has already passed (the isolation stops at its
// first look at the clock, after a few subintervals of the ≥ 40 the 20 zeros need), and the
// reported seconds include that second.
BOOST_AUTO_TEST_CASE(a_given_start_is_where_time_counts_from) {
  const auto& P = twenty_roots();
  UnivariateOptions options;
  options.time_limit_seconds = 1;
  options.start = std::chrono::steady_clock::now() - std::chrono::seconds(1);
  const SolveResult r = isolate_line_roots(P.problem.line, &P.problem.polynomial, {0, 0, 0}, {1, 0, 0}, -1, 1, options);
  BOOST_TEST(r.status == SolveStatus::time_limit);
  BOOST_TEST(any_reason(r, UndecidedReason::budget));
  BOOST_TEST(r.counters.seconds >= 1.0);
  check_nothing_dropped(r, P.roots);
}

BOOST_AUTO_TEST_CASE(time_budget_also_stops_an_mpfi_escalation) {
  // Π_{i=1..8} (x − r_i), r_i = (2i − 9)/8, plus (x + 10⁸)² − 10¹⁶ − 2·10⁸ x − x² (≡ 0, but ~4
  // wide in double): interval Newton on the compiled expression is rounding-limited on all of
  // [−1, 1], which goes to MPFI as a whole (eight certifications in MPFI, a few milliseconds); a
  // 0.5 ms budget stops it there.
  std::string text;
  std::vector<Rational> zeros;
  for (int i = 1; i <= 8; ++i) {
    text += (i > 1 ? "*" : "") + std::string("(x-(") + std::to_string(2 * i - 9) + "/8))";
    zeros.push_back(Rational(2 * i - 9, 8));
  }
  const Surface s = Surface::parse(text + "+(x+100000000)^2-10000000000000000-200000000*x-x^2+y^2+z^2");
  const CompiledSystem line(surface_line_system(s));
  UnivariateOptions options;
  options.time_limit_seconds = 5e-4;
  const SolveResult r = isolate_line_roots(line, nullptr, {0, 0, 0}, {1, 0, 0}, -1, 1, options);
  BOOST_TEST((r.status == SolveStatus::time_limit || r.status == SolveStatus::complete));
  BOOST_TEST(r.counters.precision_escalations > 0u);
  if (r.status == SolveStatus::time_limit) BOOST_TEST(any_reason(r, UndecidedReason::budget));
  check_nothing_dropped(r, zeros);
  // Without a budget all eight zeros are certified (in MPFI).
  const SolveResult full = isolate_line_roots(line, nullptr, {0, 0, 0}, {1, 0, 0}, -1, 1);
  check_exact_roots(full, zeros);
  BOOST_TEST(full.counters.precision_escalations > 0u);
}

namespace {

//! Random lines against the unit sphere, |p + t v|² = 1, on t ∈ [−1, 1]: every analytic root
//! strictly inside is certified or undecided; every certified interval holds an analytic root.
//! Half of the lines are nearly tangent (distance to the centre 1 ± 1e-7…1e-15): a certified
//! interval must then hold exactly one of the two close roots.
void sphere_line_sweep(int trials, std::uint64_t seed) {
  const auto& S = sphere();
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uni(-1, 1);
  for (int trial = 0; trial < trials; ++trial) {
    std::array<double, 3> v{normal(rng), normal(rng), normal(rng)}, p{uni(rng), uni(rng), uni(rng)};
    double vv = 0, pv = 0;
    for (int i = 0; i < 3; ++i) vv += v[i] * v[i];
    for (int i = 0; i < 3; ++i) v[i] /= std::sqrt(vv);
    for (int i = 0; i < 3; ++i) pv += p[i] * v[i];
    for (int i = 0; i < 3; ++i) p[i] -= pv * v[i];  // p ⟂ v: the closest point to the centre
    double pp = 0;
    for (int i = 0; i < 3; ++i) pp += p[i] * p[i];
    if (trial % 2 == 1) {  // nearly tangent
      const double target = 1 + std::pow(10.0, -7 - 8 * std::abs(uni(rng))) * (uni(rng) < 0 ? -1 : 1);
      for (int i = 0; i < 3; ++i) p[i] *= target / std::sqrt(pp);
      pp = 0;
      for (int i = 0; i < 3; ++i) pp += p[i] * p[i];
    }
    const double shift = 0.5 * uni(rng);  // roots at t = shift ± √(1 − |p|²)
    for (int i = 0; i < 3; ++i) p[i] -= shift * v[i];
    // The roots of the line as represented in double, from a·t² + b·t + c = 0 in 50 digits
    // (a = v·v, b = 2 p·v, c = p·p − 1 are exact there).
    using Real = boost::multiprecision::cpp_bin_float_50;
    Real a = 0, b = 0, c = -1;
    for (int i = 0; i < 3; ++i) a += Real(v[i]) * v[i], b += 2 * Real(p[i]) * v[i], c += Real(p[i]) * p[i];
    const Real disc = b * b - 4 * a * c;
    std::vector<double> known;
    if (disc >= 0) known = {static_cast<double>((-b - sqrt(disc)) / (2 * a)), static_cast<double>((-b + sqrt(disc)) / (2 * a))};
    const SolveResult r = isolate_line_roots(S.line, &S.polynomial, p, v, -1, 1);
    for (const auto& root : r.roots) {
      int inside = 0;  // a certified interval holds exactly one root (near-double pairs included)
      for (double k : known) inside += (root.box.bounds[0][0] <= k && k <= root.box.bounds[0][1]) ? 1 : 0;
      BOOST_TEST(inside == 1);
    }
    for (double k : known) {
      if (!(k > -1 + 1e-9 && k < 1 - 1e-9)) continue;
      bool covered = false;
      for (const auto& root : r.roots) covered = covered || (root.box.bounds[0][0] - 1e-9 <= k && k <= root.box.bounds[0][1] + 1e-9);
      for (const auto& u : r.undecided) covered = covered || (u.box.bounds[0][0] - 1e-9 <= k && k <= u.box.bounds[0][1] + 1e-9);
      BOOST_TEST(covered);
    }
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(sphere_random_lines_never_miss_never_invent) { sphere_line_sweep(400, 21); }

BOOST_AUTO_TEST_CASE(sphere_random_lines_sweep, *boost::unit_test::label("slow")) { sphere_line_sweep(200000, 22); }

BOOST_AUTO_TEST_CASE(ill_conditioned_degree_10_line_agrees_with_newton) {
  // Regression: monomial coefficients up to 1e5 in t make interval Horner over an interval
  // useless near these roots (two of them 0.027 apart); certification must still succeed, by the
  // sign change inside the Bernstein isolating interval.
  const Surface s = Surface::parse(
      "(x-0.860456)*(x+0.532638)*(x-0.786227)*(x+0.307254)*(x+0.0239051)*(x-0.351474)*(x+0.0572752)*"
      "(x+0.741076)*(x-0.54776)*(x+0.362211)+y^2+z^2-0.01");
  const LineProblem problem(s);
  const std::array<double, 3> p{-1.2, -0.046025242264017885, -0.046557960182797502},
      v{2.3999999999999999, -0.041147480546549209, -0.012035562762547103};
  const SolveResult a = isolate_line_roots(problem.line, &problem.polynomial, p, v, 0, 1);
  const SolveResult b = isolate_line_roots(problem.line, nullptr, p, v, 0, 1);
  BOOST_TEST(a.status == SolveStatus::complete);
  BOOST_TEST(b.status == SolveStatus::complete);
  BOOST_REQUIRE_EQUAL(a.roots.size(), 4u);
  BOOST_REQUIRE_EQUAL(b.roots.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    // The certified intervals of both paths hold the same root: they must overlap.
    BOOST_TEST(a.roots[i].box.bounds[0][0] <= b.roots[i].box.bounds[0][1]);
    BOOST_TEST(b.roots[i].box.bounds[0][0] <= a.roots[i].box.bounds[0][1]);
  }
}

BOOST_AUTO_TEST_CASE(misuse_throws_precondition_violation) {
  const auto& S = sphere();
  BOOST_CHECK_THROW((void)isolate_line_roots(S.line, &S.polynomial, {0, 0, 0}, {1, 0, 0}, 1, 0), PreconditionViolation);
  BOOST_CHECK_THROW((void)isolate_line_roots(S.line, &S.polynomial, {0, 0, 0}, {0, 0, 0}, 0, 1), PreconditionViolation);
  const CompiledSystem critical(surface_critical_system(S.surface));
  BOOST_CHECK_THROW((void)isolate_line_roots(critical, nullptr, {0, 0, 0}, {1, 0, 0}, 0, 1), PreconditionViolation);
  for (double seconds : {-1.0, std::nan(""), HUGE_VAL}) {
    UnivariateOptions options;
    options.time_limit_seconds = seconds;
    BOOST_CHECK_THROW((void)isolate_line_roots(S.line, &S.polynomial, {0, 0, 0}, {1, 0, 0}, 0, 1, options),
                      PreconditionViolation);
  }
}

BOOST_AUTO_TEST_SUITE_END()
