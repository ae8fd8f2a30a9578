#include "symbolic/surface.h"

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <boost/test/unit_test.hpp>

#include "common/errors.h"

using namespace delmesh;

namespace {

const GiNaC::symbol& x = coordinate_x();
const GiNaC::symbol& y = coordinate_y();
const GiNaC::symbol& z = coordinate_z();

bool same(const GiNaC::ex& a, const GiNaC::ex& b) { return (a - b).expand().is_zero(); }

//! The message of the InvalidInput thrown by Surface::parse(text), or "" if none was thrown.
std::string parse_error(const std::string& text) {
  try {
    (void)Surface::parse(text);
  } catch (const InvalidInput& error) {
    return error.what();
  }
  return "";
}

std::string box_error(const std::string& text) {
  try {
    (void)Box3::parse(text);
  } catch (const InvalidInput& error) {
    return error.what();
  }
  return "";
}

}  // namespace

BOOST_AUTO_TEST_SUITE(surface)

BOOST_AUTO_TEST_CASE(torus_gradient_and_hessian_match_hand_derivation) {
  // E = (s + R^2 - r^2)^2 - 4 R^2 (x^2 + y^2), R = 1, r = 2/5, s = x^2 + y^2 + z^2.
  const Surface torus = Surface::parse("(x^2+y^2+z^2+0.84)^2-4*(x^2+y^2)");
  const GiNaC::ex S = x * x + y * y + z * z + GiNaC::numeric(21, 25);
  BOOST_TEST(same(torus.E(), S * S - 4 * (x * x + y * y)));
  BOOST_TEST(same(torus.gradient()[0], 4 * x * S - 8 * x));
  BOOST_TEST(same(torus.gradient()[1], 4 * y * S - 8 * y));
  BOOST_TEST(same(torus.gradient()[2], 4 * z * S));
  const GiNaC::matrix& H = torus.hessian();
  BOOST_TEST(same(H(0, 0), 4 * S + 8 * x * x - 8));
  BOOST_TEST(same(H(2, 2), 4 * S + 8 * z * z));
  BOOST_TEST(same(H(0, 1), 8 * x * y));
  BOOST_TEST(same(H(0, 2), 8 * x * z));
  for (unsigned i = 0; i < 3; ++i)
    for (unsigned j = 0; j < 3; ++j) BOOST_TEST(same(H(i, j), H(j, i)));
  BOOST_TEST(torus.is_polynomial());
  BOOST_TEST(torus.degree() == 4);
  BOOST_TEST(torus.evaluate({1.4, 0, 0}) == 0.0, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(torus.evaluate({0, 0.6, 0}) == 0.0, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(torus.evaluate({1, 0, 0}) < 0);
}

BOOST_AUTO_TEST_CASE(decimal_literals_become_exact_rationals) {
  BOOST_TEST(same(Surface::parse("0.16*x").E(), GiNaC::numeric(4, 25) * x));
  BOOST_TEST(same(Surface::parse("0.1*x+y").E(), GiNaC::numeric(1, 10) * x + y));
  BOOST_TEST(same(Surface::parse("x-0.3").E(), x - GiNaC::numeric(3, 10)));
  BOOST_TEST(same(Surface::parse("1.5e-3*x").E(), GiNaC::numeric(3, 2000) * x));
  BOOST_TEST(same(Surface::parse("2E2*x+.5").E(), 200 * x + GiNaC::numeric(1, 2)));
  BOOST_TEST(same(Surface::parse("x^2.0").E(), x * x));
  // 0.1 + 0.2 - 0.3 is exactly 0, which it is not in binary floating point.
  BOOST_TEST(same(Surface::parse("(0.1+0.2-0.3)*y+x").E(), x));
  // Many digits survive: 0.1234567890123456789 is not a double.
  BOOST_TEST(same(Surface::parse("0.1234567890123456789*x").E(),
                  GiNaC::numeric("1234567890123456789") / GiNaC::numeric("10000000000000000000") * x));
  // A double inside a built expression becomes the rational of its shortest decimal.
  BOOST_TEST(same(Surface(GiNaC::numeric(0.1) * x).E(), GiNaC::numeric(1, 10) * x));
  BOOST_TEST(same(Surface(GiNaC::numeric(-2.5e-7) + y).E(), y - GiNaC::numeric(1, 4000000)));
}

BOOST_AUTO_TEST_CASE(accepted_syntax) {
  BOOST_TEST(same(Surface::parse("-x^2+y").E(), y - x * x));
  BOOST_TEST(same(Surface::parse("2*(-x)+y").E(), y - 2 * x));
  BOOST_TEST(same(Surface::parse("x^(-2)*y - 1").E(), y / (x * x) - 1));
  BOOST_TEST(same(Surface::parse("x^(2)").E(), x * x));
  BOOST_TEST(same(Surface::parse("x/3+y").E(), x / 3 + y));
  BOOST_TEST(same(Surface::parse("Pi*x").E(), Surface::parse("pi*x").E()));
  const Surface analytic = Surface::parse("exp(-x^2)+sqrt(y^2+1)+sin(z)*cos(x)-log(2+z^2)");
  BOOST_TEST(!analytic.is_polynomial());
  BOOST_TEST(analytic.degree() == -1);
  BOOST_TEST(same(analytic.gradient()[2], GiNaC::cos(z) * GiNaC::cos(x) - 2 * z / (2 + z * z)));
  BOOST_TEST(std::isnan(Surface::parse("sqrt(x)").evaluate({-1, 0, 0})));
  BOOST_TEST(std::isnan(Surface::parse("1/x+y").evaluate({0, 1, 0})));
  BOOST_TEST(Surface::parse("x^2+y^2+z^2-1").text() == "x^2+y^2+z^2-1");
}

// ** is ^ with the same precedence and associativity, so sympy's str() output parses.
BOOST_AUTO_TEST_CASE(double_star_is_the_power_operator) {
  const std::vector<std::pair<std::string, std::string>> pairs = {
      {"x**2 + y**2 + z**2 - 1", "x^2 + y^2 + z^2 - 1"},
      {"2*x**3*y - z", "2*x^3*y - z"},
      {"-x**2+y", "-x^2+y"},
      {"x**(-2)*y - 1", "x^(-2)*y - 1"},
      {"(x+y)**2*z**3 - 1", "(x+y)^2*z^3 - 1"},
      {"x/2**3 + y", "x/2^3 + y"},
      {"sqrt(x**2 + 1)*exp(-y**2) - pi*z", "sqrt(x^2 + 1)*exp(-y^2) - pi*z"},
      {"x**2.0 + y**2 ** 1 - 1", "x^2.0 + y^2 ^ 1 - 1"},
  };
  for (const auto& [stars, carets] : pairs) {
    BOOST_TEST_CONTEXT(stars) {
      if (stars.find("** 1") != std::string::npos) {  // a**b**c is refused as a^b^c is
        BOOST_TEST(parse_error(stars).find("ambiguous") != std::string::npos);
        BOOST_TEST(parse_error(carets).find("ambiguous") != std::string::npos);
        continue;
      }
      const Surface a = Surface::parse(stars), b = Surface::parse(carets);
      BOOST_TEST(a.E().is_equal(b.E()));
      BOOST_TEST(a.text() == stars);
    }
  }
  BOOST_TEST(same(Surface::parse("-x**2+y").E(), y - x * x));
  BOOST_TEST(same(Surface::parse("x/2**3 + y").E(), x / 8 + y));
}

// A function that is not C² gets one line naming the smooth blend to write instead.
BOOST_AUTO_TEST_CASE(non_smooth_functions_are_refused_with_a_hint) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"abs(x) + y - 1", "abs at position 1 of \"abs(x) + y - 1\" is not smooth: E must be C² (use a smooth blend, "
                         "e.g. sqrt(x^2+c^2) for |x|, with a small c > 0)"},
      {"Abs(x) + y - 1", "Abs at position 1"},
      {"y - min(x, z)", "min at position 5 of \"y - min(x, z)\" is not smooth: E must be C² (use a smooth blend, "
                        "e.g. (a+b-sqrt((a-b)^2+c^2))/2 for min(a,b), with a small c > 0)"},
      {"max(x,y)-z", "e.g. (a+b+sqrt((a-b)^2+c^2))/2 for max(a,b)"},
      {"Max(x,y)-z", "Max at position 1"},
      {"sign(x)+y", "sign at position 1 of \"sign(x)+y\" is not continuous: E must be C² (use a smooth blend, "
                    "e.g. x/sqrt(x^2+c^2) for sign(x)"},
      {"floor(x)+y", "floor at position 1 of \"floor(x)+y\" is not continuous: E must be C² (write E without it)"},
      {"ceil(x)+y", "is not continuous"},
      {"ceiling(x)+y", "is not continuous"},
  };
  for (const auto& [text, fragment] : cases) {
    const std::string message = parse_error(text);
    BOOST_TEST_CONTEXT("text \"" << text << "\", message \"" << message << "\"") {
      BOOST_TEST(message.find(fragment) != std::string::npos);
      BOOST_TEST(message.find('\n') == std::string::npos);
    }
  }
  // The same hint for a built expression.
  try {
    (void)Surface(GiNaC::abs(x) + y);
    BOOST_FAIL("abs(x) + y was accepted");
  } catch (const InvalidInput& error) {
    BOOST_TEST(std::string(error.what()).find("abs in \"") == 0, error.what());
    BOOST_TEST(std::string(error.what()).find("is not smooth: E must be C²") != std::string::npos, error.what());
  }
}

BOOST_AUTO_TEST_CASE(polynomial_and_degree) {
  BOOST_TEST(Surface::parse("x^2+y^2+z^2-1").degree() == 2);
  BOOST_TEST(Surface::parse("(x^2-x^4-y^2)^2+z^2-0.02").degree() == 8);
  BOOST_TEST(Surface::parse("x*y*z-0.5").degree() == 3);
  BOOST_TEST(Surface::parse("x^3-x^3+y").degree() == 1);
  BOOST_TEST(!Surface::parse("1/x+y").is_polynomial());
  BOOST_TEST(!Surface::parse("sqrt(2)*x+y").is_polynomial());
  BOOST_TEST(!Surface::parse("Pi*x+y").is_polynomial());
  BOOST_TEST(!Surface::parse("exp(x)+y").is_polynomial());
  BOOST_TEST(Surface::parse("exp(0)*x+y").is_polynomial());
}

BOOST_AUTO_TEST_CASE(malformed_expressions_throw_and_name_the_problem) {
  // {text, a fragment the message must contain}
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"x+w", "'w'"},
      {"x+w", "position 3"},
      {"tan(x)", "'tan'"},
      {"abs(x)", "abs at position 1"},
      {"x^0.5", "0.5"},
      {"x^y", "'y'"},
      {"x^(1/2)", "'/'"},
      {"x^2^3", "ambiguous"},
      {"x^-2", "'-'"},
      {"2*-x+y", "'-'"},
      {"", "empty"},
      {"   ", "empty"},
      {"3", "constant"},
      {"x-x", "constant"},
      {"0*y+2", "constant"},
      {"I*x", "'I'"},
      {"Euler*x", "'Euler'"},
      {"sqrt(-1)*x", "complex"},
      {"log(-2)+x", "complex"},
      {"x***2", "expected an integer exponent after '**', got '*'"},
      {"**x", "unexpected '**' at position 1"},
      {"x**2**3", "ambiguous"},
      {"x**0.5", "non-integer power '**0.5'"},
      {"x**-2", "x**(-2)"},
      {"x* *2", "unexpected '*'"},
      {"x+", "end"},
      {"(x+y", "')'"},
      {"x)", "')'"},
      {"x y", "'y'"},
      {"2x", "'x'"},
      {"sin x", "'sin'"},
      {"x(1)", "'x'"},
      {"sqrt(x,y)", "','"},
      {"x=1", "'='"},
      {"x;y", "';'"},
      {"{x,y}", "'{'"},
      {"1e*x", "1e"},
      {"x^100000+y", "too large"},
      {"1e999*x", "out of range"},
  };
  for (const auto& [text, fragment] : cases) {
    const std::string message = parse_error(text);
    BOOST_TEST_CONTEXT("text \"" << text << "\", message \"" << message << "\"") {
      BOOST_TEST(!message.empty());
      BOOST_TEST(message.find(fragment) != std::string::npos);
    }
  }
}

BOOST_AUTO_TEST_CASE(built_expressions_are_validated) {
  const GiNaC::symbol w("w");
  BOOST_CHECK_THROW(Surface(x + w), InvalidInput);
  BOOST_CHECK_THROW(Surface(GiNaC::tan(x)), InvalidInput);
  BOOST_CHECK_THROW(Surface(GiNaC::abs(x) + y), InvalidInput);
  BOOST_CHECK_THROW(Surface(GiNaC::pow(x, GiNaC::numeric(1, 3))), InvalidInput);
  BOOST_CHECK_THROW(Surface(GiNaC::pow(x, y)), InvalidInput);
  BOOST_CHECK_THROW(Surface(GiNaC::ex(3)), InvalidInput);
  BOOST_CHECK_THROW(Surface(GiNaC::I * x), InvalidInput);
  BOOST_CHECK_THROW(Surface(GiNaC::Euler * x), InvalidInput);
  BOOST_CHECK_NO_THROW(Surface(GiNaC::exp(x) + GiNaC::sqrt(y * y + 1) - 3));
  BOOST_CHECK_NO_THROW(Surface(GiNaC::pow(GiNaC::sqrt(x * x + 1), 3) - y));
}

BOOST_AUTO_TEST_CASE(box_parsing) {
  const Box3 b = Box3::parse("-1,2, -3,4 ,0.5,1.5");
  BOOST_TEST(b.lo[0] == -1.0);
  BOOST_TEST(b.hi[0] == 2.0);
  BOOST_TEST(b.lo[1] == -3.0);
  BOOST_TEST(b.hi[1] == 4.0);
  BOOST_TEST(b.lo[2] == 0.5);
  BOOST_TEST(b.hi[2] == 1.5);
  BOOST_TEST(b.diagonal() == std::sqrt(9.0 + 49.0 + 1.0), boost::test_tools::tolerance(1e-15));
  BOOST_TEST(b.contains({0, 0, 1}));
  BOOST_TEST(b.contains({2, 4, 1.5}));
  BOOST_TEST(!b.contains({0, 0, 2}));

  const std::vector<std::pair<std::string, std::string>> bad = {
      {"1,2,3", "6"},          {"", "6"},
      {"0,1,0,1,0,1,", "6"},   {"0,1,0,1,0,1,2", "6"},
      {"0,1,0,1,1,0", "z"},    {"0,0,0,1,0,1", "x"},
      {"0,1,0,1,0,nan", "nan"}, {"0,1,0,1,0,inf", "inf"},
      {"a,1,0,1,0,1", "\"a\""}, {"0,1x,0,1,0,1", "1x"},
      {"0,1,,1,0,1", "field 3"},
      {"-1e308,1e308,-2,2,-2,2", "overflows"}, {"-2,2,-1e200,1e200,-2,2", "overflows"},
  };
  for (const auto& [text, fragment] : bad) {
    const std::string message = box_error(text);
    BOOST_TEST_CONTEXT("box \"" << text << "\", message \"" << message << "\"") {
      BOOST_TEST(!message.empty());
      BOOST_TEST(message.find(fragment) != std::string::npos);
    }
  }
}

// Numbers at the ends of double precision: a subnormal coordinate or one that underflows is
// refused as below the smallest normal double (not as "not a finite number"); one that overflows
// says so; the smallest normal double and 0 are accepted.
BOOST_AUTO_TEST_CASE(box_coordinates_at_the_ends_of_double) {
  for (const std::string small : {"5e-324", "1e-310", "-1e-400"}) {
    const std::string message = box_error("-2,2,-2,2," + small + ",1");
    BOOST_TEST(message.find("is too small: a nonzero box coordinate must be at least 2.2250738585072014e-308") !=
                   std::string::npos,
               message);
    BOOST_TEST(message.find("not a finite number") == std::string::npos, message);
  }
  BOOST_TEST(box_error("-2,2,-2,2,0,1e400").find("overflows double precision") != std::string::npos);
  const Box3 b = Box3::parse("-2,2,-2,2,0,2.2250738585072014e-308");
  BOOST_TEST(b.hi[2] == Box3::min_coordinate);
}

// A constant factor far from 1 is divided out by a power of two: E = 1e200 (x² + y² + z² − 1)
// becomes 10^200 / 2^664 (x² + y² + z² − 1), exactly; moderate coefficients are kept as given.
BOOST_AUTO_TEST_CASE(extreme_constant_factor_is_normalised) {
  const GiNaC::ex unit = x * x + y * y + z * z - 1;
  const Surface big = Surface::parse("1e200*(x^2+y^2+z^2-1)");
  BOOST_TEST(big.normalization_exponent() == 664);
  const GiNaC::numeric c = GiNaC::numeric(10).power(200) / GiNaC::numeric(2).power(664);
  BOOST_TEST(same(big.E(), c * unit));
  BOOST_TEST(same(big.gradient()[0], 2 * c * x));
  BOOST_TEST(same(big.hessian()(2, 2), 2 * c));
  BOOST_TEST(std::abs(big.evaluate({2, 0, 0}) - 3 * c.to_double()) < 1e-12);
  const Surface small = Surface::parse("1e-300*x^2+1e-300*y^2+1e-300*z^2-1e-300");
  BOOST_TEST(small.normalization_exponent() < -900);
  BOOST_TEST(std::abs(small.evaluate({0, 0, 0}) + 1) < 1, "E(0) = " << small.evaluate({0, 0, 0}));
  const Surface product = Surface::parse("1e-250*(x^2+y^2+z^2-1)*exp(x)");
  BOOST_TEST(product.normalization_exponent() < -800);
  BOOST_TEST(std::abs(product.evaluate({0, 0, 0}) + 1) < 1);
  const Surface moderate = Surface::parse("1000*(x^2+y^2+z^2-1)");
  BOOST_TEST(moderate.normalization_exponent() == 0);
  BOOST_TEST(same(moderate.E(), 1000 * unit));
}

// Inputs that once exhausted the stack (20 000 nested parentheses) or would exhaust the memory of
// the exact arithmetic are refused with the limit they break, before any expansion.
BOOST_AUTO_TEST_CASE(input_limits) {
  const auto nested = [](std::size_t depth, const std::string& open, const std::string& inner) {
    std::string text;
    for (std::size_t i = 0; i < depth; ++i) text += open;
    text += inner;
    text += std::string(depth, ')');
    return text;
  };
  const std::vector<std::pair<std::string, std::string>> cases = {
      {nested(20000, "(", "x") + "-1", "expression too long: 40003 characters"},
      {nested(Surface::max_nesting + 1, "(", "x") + "-1", "nested more than 200"},
      {nested(Surface::max_nesting + 1, "sin(", "x") + "-1", "nested more than 200"},
      {"x^" + nested(Surface::max_nesting + 1, "(", "2"), "nested more than 200"},
      {"x+" + std::string(Surface::max_length, 'y'), "too long"},
      {"x^201+y", "degree up to 201"},
      {"(x^2+y^2)^101-1", "degree up to 202"},
      {"((x^10)^10)^10-1", "degree up to 1000"},
      {"(x+y+z+1)^120-1", "may have more than 200000 terms"},
      {"(x^2+y^2+z^2+1)^100-2", "may have more than 200000 terms"},
      {"1/(x-x)+y", "division by zero"},
      {"y+1/(0*x)", "division by zero"},
  };
  for (const auto& [text, fragment] : cases) {
    const std::string message = parse_error(text);
    BOOST_TEST_CONTEXT("text of " << text.size() << " characters, message \"" << message << "\"") {
      BOOST_TEST(message.find(fragment) != std::string::npos);
      BOOST_TEST(message.size() < 300u);  // long inputs are abbreviated in the message
    }
  }
  // Just inside the limits.
  BOOST_CHECK_NO_THROW(Surface::parse(nested(Surface::max_nesting, "(", "x") + "^2+y^2+z^2-1"));
  BOOST_CHECK_NO_THROW(Surface::parse(nested(Surface::max_nesting - 1, "sin(", "x") + "+y"));
  BOOST_TEST(Surface::parse("x^200+y^2+z^2-1").degree() == 200);
  BOOST_TEST(Surface::parse("(x+y+z+1)^12-1").degree() == 12);  // 18 564 terms along a line
  BOOST_TEST(parse_error("(x+y+z+1)^50-1").find("may have more than 200000 terms") != std::string::npos);
  // The bound on the expanded size holds for built expressions too.
  BOOST_CHECK_THROW(Surface(GiNaC::pow(x + y + z + 1, 150)), InvalidInput);
}

BOOST_AUTO_TEST_SUITE_END()
