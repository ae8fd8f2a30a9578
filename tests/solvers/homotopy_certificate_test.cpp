#include <boost/test/unit_test.hpp>

#include <cmath>
#include <memory>
#include <optional>

#include "solvers/detail/complex_krawczyk.h"
#include "solvers/detail/homotopy_tracker.h"
#include "solvers/homotopy_certificate.h"
#include "solvers/homotopy_solver.h"
#include "system_fixture.h"
#include "symbolic/catalog.h"
#include "symbolic/complex_interval.h"

using namespace delmesh;
using GiNaC::ex;
using GiNaC::symbol;

namespace {

using test::make_system;
using test::X;
using test::Y;

HomotopySolveResult solve(const PrimitiveSystem& system, const Domain& domain, std::uint64_t seed = 1) {
  const CompiledSystem compiled(system);
  HomotopyOptions options;
  options.seed = seed;
  return solve_homotopy(compiled, equation_degrees(system), {}, domain, options);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(homotopy_certificate)

BOOST_AUTO_TEST_CASE(complex_interval_products_enclose_sampled_products) {
  // (1 + 2i)(3 − i) = 5 + 5i; rectangles around both factors enclose every product of their points
  const RoundingGuard guard;
  const ComplexInterval a(Interval(0.9, 1.1), Interval(1.9, 2.1)), b(Interval(2.9, 3.1), Interval(-1.1, -0.9));
  ComplexInterval p, q;
  ScalarTraits<ComplexInterval>::mul(p, a, b);
  ScalarTraits<ComplexInterval>::pow(q, a, 3);
  for (double s : {0.9, 1.0, 1.1})
    for (double t : {1.9, 2.0, 2.1}) {
      const Complex z = Complex(s, t) * Complex(3.0, -1.0), w = std::pow(Complex(s, t), 3);
      BOOST_TEST((z.real() >= p.re.inf() && z.real() <= p.re.sup() && z.imag() >= p.im.inf() && z.imag() <= p.im.sup()));
      BOOST_TEST((w.real() >= q.re.inf() && w.real() <= q.re.sup() && w.imag() >= q.im.inf() && w.imag() <= q.im.sup()));
    }
  ComplexInterval r;
  ScalarTraits<ComplexInterval>::inv(r, ComplexInterval(Interval(0.0), Interval(-1.0, 1.0)));  // contains 0
  BOOST_TEST(!certainly_nonzero(r));
}

BOOST_AUTO_TEST_CASE(two_circles_certified_complete) {
  // x² + y² − 1 = 0, x − y = 0 in [0, 1]²: one root (√½, √½); Bézout 2, the other root outside
  const PrimitiveSystem s = make_system({X() * X() + Y() * Y() - 1, X() - Y()}, {X(), Y()});
  const auto r = solve(s, Domain::from_box({{0.0, 1.0}, {0.0, 1.0}}));
  BOOST_TEST_MESSAGE("status " << r.certificate.status << " t_e " << r.certificate.t_barrier << " boxes "
                               << r.certificate.barrier_boxes << " k " << r.certificate.zeros_inside);
  BOOST_TEST(r.completeness_certified());
  BOOST_TEST(r.status == SolveStatus::complete);
  BOOST_REQUIRE(r.roots.size() == 1u);
  BOOST_TEST(std::abs(r.roots[0].midpoint[0] - std::sqrt(0.5)) < 1e-12);
}

BOOST_AUTO_TEST_CASE(barrier_inequality_holds_at_sampled_boundary_points) {
  // (B) of the theorem, checked in double at points of ∂C: some i has (1 − t_e)|f_i| > t_e |g_i|.
  const PrimitiveSystem s = make_system({X() * X() + Y() * Y() - 1, X() - Y()}, {X(), Y()});
  const CompiledSystem f(s);
  const Domain domain = Domain::from_box({{0.0, 1.0}, {0.0, 1.0}});
  const auto r = solve(s, domain);
  BOOST_REQUIRE(r.completeness_certified());
  BOOST_REQUIRE(!r.certificate.pieces.empty());
  const BarrierPiece& piece = r.certificate.pieces.front();
  const double t = r.certificate.t_barrier, mu = piece.margin;
  BOOST_TEST(t > 0);
  BOOST_TEST(mu > 0);
  const std::vector<double> lo = {piece.box[0][0] - mu, piece.box[1][0] - mu},
                            hi = {piece.box[0][1] + mu, piece.box[1][1] + mu};
  int checked = 0;
  for (int face = 0; face < 8; ++face)
    for (int a = 0; a <= 6; ++a)
      for (int b = 0; b <= 6; ++b)
        for (int c = 0; c <= 6; ++c) {
          // the three free real coordinates at grid points, the fixed one at its bound
          double coords[4], free[3] = {a / 6.0, b / 6.0, c / 6.0};
          const int fixed = face / 2;  // 0: Re x, 1: Im x, 2: Re y, 3: Im y
          for (int k = 0, m = 0; k < 4; ++k) {
            const double low = k % 2 == 0 ? lo[k / 2] : -mu, high = k % 2 == 0 ? hi[k / 2] : mu;
            coords[k] = k == fixed ? (face % 2 == 0 ? low : high) : low + free[m++] * (high - low);
          }
          const Complex u[2] = {Complex(coords[0], coords[1]), Complex(coords[2], coords[3])};
          const Complex fv[2] = {u[0] * u[0] + u[1] * u[1] - 1.0, u[0] - u[1]};
          const Complex gv[2] = {u[0] * u[0] - 1.0, u[1] - 1.0};
          const bool holds = (1 - t) * std::abs(fv[0]) > t * std::abs(gv[0]) || (1 - t) * std::abs(fv[1]) > t * std::abs(gv[1]);
          BOOST_TEST(holds);
          ++checked;
        }
  BOOST_TEST(checked == 8 * 343);
}

BOOST_AUTO_TEST_CASE(non_real_zeros_are_counted_and_not_returned) {
  // x² + 1 = 0, y = 0 near the origin: the zeros (±i, 0) are not real; whether they lie in C or
  // not, the solve proves that there is no real root.
  const PrimitiveSystem s = make_system({X() * X() + 1, Y()}, {X(), Y()});
  const auto r = solve(s, Domain::from_box({{-0.5, 0.5}, {-0.5, 0.5}}));
  BOOST_TEST(r.completeness_certified());
  BOOST_TEST(r.status == SolveStatus::complete);
  BOOST_TEST(r.roots.empty());
  BOOST_TEST(r.certificate.real_zeros.empty());
  BOOST_TEST(r.certificate.nonreal_zeros == r.certificate.zeros_inside);
}

BOOST_AUTO_TEST_CASE(a_root_on_the_domain_boundary_is_undecided_not_dropped) {
  // x² + y² − 2 = 0, x − y = 0: the root (1, 1) lies on the face x = 1 of the domain
  const PrimitiveSystem s = make_system({X() * X() + Y() * Y() - 2, X() - Y()}, {X(), Y()});
  const auto r = solve(s, Domain::from_box({{0.0, 1.0}, {0.5, 1.5}}));
  BOOST_TEST(r.completeness_certified());
  BOOST_TEST(r.status == SolveStatus::undecided);
  BOOST_TEST(r.roots.empty());
  BOOST_REQUIRE(r.undecided.size() == 1u);
  BOOST_TEST(r.undecided[0].reason == UndecidedReason::boundary_root);
}

BOOST_AUTO_TEST_CASE(a_curve_of_zeros_is_not_certified_and_the_domain_comes_back_undecided) {
  // f = (x² + y² − 1, (x² + y² − 1)(x − 3)): the circle is a curve of common zeros, so no
  // barrier exists around the domain; the solve must not end complete.
  const ex circle = X() * X() + Y() * Y() - 1;
  const PrimitiveSystem s = make_system({circle, circle * (X() - 3)}, {X(), Y()});
  const auto r = solve(s, Domain::from_box({{0.0, 1.0}, {0.0, 1.0}}));
  BOOST_TEST(!r.completeness_certified());
  BOOST_TEST(r.certificate.status == HomotopyCertificateStatus::barrier_not_proved);
  BOOST_TEST(r.status == SolveStatus::undecided);
  BOOST_TEST(!r.undecided.empty());
}

// The certificate trusts no path: a tracker that jumps (two paths give the same point at t_e) or
// an endgame that misses a zero is caught.
struct TwoCircles {
  PrimitiveSystem system = make_system({X() * X() + Y() * Y() - 1, X() - Y()}, {X(), Y()});
  CompiledSystem f{system};
  std::vector<int> degrees = equation_degrees(system);
  std::vector<double> parameters;
  Domain domain = Domain::from_box({{0.0, 1.0}, {0.0, 1.0}});
  Complex gamma = std::polar(1.0, 2.2);
  std::vector<detail::PathEndpoint> ends;
  std::unique_ptr<detail::HomotopyTracker> tracker;
  std::vector<std::vector<Complex>> starts = total_degree_start_solutions(degrees);
  TwoCircles() {
    const std::vector<Complex> patch = {Complex(0.5, 0.1), Complex(-0.3, 0.6), Complex(0.2, -0.4)};
    tracker = std::make_unique<detail::HomotopyTracker>(f, degrees, std::vector<Complex>{}, gamma, patch);
  }
  std::optional<std::vector<Complex>> point(std::size_t j, double t) const {
    return tracker->point_at(starts[j], t, detail::TrackerSettings::defaults());
  }
  std::vector<std::vector<Complex>> zeros() const {
    return {{Complex(std::sqrt(0.5), 0), Complex(std::sqrt(0.5), 0)}, {Complex(-std::sqrt(0.5), 0), Complex(-std::sqrt(0.5), 0)}};
  }
  HomotopyProblem problem() const { return HomotopyProblem{f, parameters, degrees, gamma, domain}; }
};

BOOST_AUTO_TEST_CASE(honest_paths_and_zeros_are_proved) {
  const TwoCircles c;
  const auto cert = certify_homotopy(c.problem(), c.starts.size(), [&](std::size_t j, double t) { return c.point(j, t); },
                                     c.zeros());
  BOOST_TEST(cert.status == HomotopyCertificateStatus::proved);
  BOOST_TEST(cert.real_zeros.size() == 1u);  // (√½, √½); (−√½, −√½) lies outside C
}

BOOST_AUTO_TEST_CASE(a_jumped_path_is_caught) {
  const TwoCircles c;
  // path 1 "jumps" onto path 0: both report path 0's point at t_e
  const auto cert = certify_homotopy(c.problem(), c.starts.size(), [&](std::size_t, double t) { return c.point(0, t); },
                                     c.zeros());
  BOOST_TEST(cert.status == HomotopyCertificateStatus::intermediate_not_distinct);
}

BOOST_AUTO_TEST_CASE(a_missed_zero_is_caught) {
  const TwoCircles c;
  // the endgame "lost" the root inside the domain: only the one outside is proposed
  const auto cert = certify_homotopy(c.problem(), c.starts.size(), [&](std::size_t j, double t) { return c.point(j, t); },
                                     {c.zeros()[1]});
  // (the pieces around the lost root are bisected until the limit; the last one's failure is reported)
  BOOST_TEST(cert.status != HomotopyCertificateStatus::proved);
  BOOST_TEST(cert.real_zeros.empty());
}

BOOST_AUTO_TEST_CASE(a_failed_path_is_caught) {
  const TwoCircles c;
  const auto cert = certify_homotopy(
      c.problem(), c.starts.size(),
      [&](std::size_t j, double t) { return j == 1 ? std::nullopt : c.point(j, t); }, c.zeros());
  BOOST_TEST(cert.status == HomotopyCertificateStatus::intermediate_path_failed);
}

BOOST_AUTO_TEST_SUITE_END()
