// Tests of the limits of symbolic/surface.h on differentiation: the size estimate of the
// Hessian (max_derivative_tree_size) refuses expressions whose derivatives explode, before they
// are built, and never a large polynomial; and the command's limits (common/run_limits.h) stop
// the construction between its GiNaC steps.
#include <atomic>
#include <chrono>
#include <string>

#include <boost/test/unit_test.hpp>

#include "common/errors.h"
#include "common/run_limits.h"
#include "symbolic/surface.h"

using namespace delmesh;
using Clock = std::chrono::steady_clock;

namespace {

// (2+sin(x+1))*…*(2+sin(x+n))*(x^2+y^2+z^2-1): a sphere whose derivatives grow as n^2, n^3, …
std::string sin_product(int n) {
  std::string e;
  for (int i = 1; i <= n; ++i) e += "(2+sin(x+" + std::to_string(i) + "))*";
  return e + "(x^2+y^2+z^2-1)";
}

}  // namespace

BOOST_AUTO_TEST_SUITE(surface_limits)

BOOST_AUTO_TEST_CASE(a_product_of_many_factors_is_refused_before_its_hessian) {
  for (const int n : {100, 650}) {
    const auto start = Clock::now();
    try {
      (void)Surface::parse(sin_product(n));
      BOOST_ERROR(n << " factors were accepted");
    } catch (const InvalidInput& e) {
      BOOST_TEST(std::string(e.what()).find("too large to differentiate") != std::string::npos, e.what());
    }
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    BOOST_TEST_MESSAGE(n << " factors refused in " << seconds << " s");
    // Only E and ∇E were built (the Hessian of 100 factors alone takes seconds).
    BOOST_TEST(seconds < 2.0);
  }
}

BOOST_AUTO_TEST_CASE(moderate_products_and_large_polynomials_are_accepted) {
  const Surface product = Surface::parse(sin_product(25));
  BOOST_TEST(!product.is_polynomial());
  // A dense polynomial of degree 18 in three variables (1330 terms, near check_size's bound
  // along a line; built as an expression, as it is longer than parse() takes): its derivatives
  // are no larger than itself.
  GiNaC::ex dense = -1;
  const GiNaC::symbol &x = coordinate_x(), &y = coordinate_y(), &z = coordinate_z();
  for (int i = 0; i <= 18; ++i)
    for (int j = 0; i + j <= 18; ++j)
      for (int k = 0; i + j + k <= 18; ++k)
        dense += GiNaC::numeric(1 + (i * 7 + j * 3 + k) % 5, 100000) * pow(x, i) * pow(y, j) * pow(z, k);
  const Surface polynomial(dense);
  BOOST_TEST(polynomial.is_polynomial());
  BOOST_TEST(polynomial.degree() == 18);
}

BOOST_AUTO_TEST_CASE(the_command_limits_stop_differentiation) {
  std::atomic<bool> flag{true};
  const RunLimits interrupted(std::nullopt, &flag);
  {
    const RunLimits::Scope scope(interrupted);
    try {
      (void)Surface::parse("x^2+y^2+z^2-1");
      BOOST_ERROR("an interrupted parse returned");
    } catch (const RunStopped& stopped) {
      BOOST_TEST((stopped.reason() == StopReason::interrupted));
      BOOST_TEST(stopped.phase() == "differentiating the expression");
    }
    const RunLimits passed(Clock::now() - std::chrono::seconds(1), nullptr);
    const RunLimits::Scope inner(passed);
    BOOST_CHECK_THROW((void)Surface::parse("x^2+y^2+z^2-1"), RunStopped);
  }
  // Outside a scope nothing is limited.
  BOOST_TEST(Surface::parse("x^2+y^2+z^2-1").is_polynomial());
}

BOOST_AUTO_TEST_SUITE_END()
