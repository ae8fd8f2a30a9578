#include "symbolic/detail/straight_line_program.h"

#include <array>
#include <cmath>
#include <random>
#include <sstream>
#include <thread>

#include <boost/math/constants/constants.hpp>
#include <boost/test/unit_test.hpp>

#include "common/errors.h"

using namespace delmesh;
using delmesh::detail::OpCode;
using delmesh::detail::StraightLineProgram;

namespace {

double evalf_at(const GiNaC::ex& e, const std::vector<GiNaC::symbol>& symbols, const std::vector<double>& values) {
  GiNaC::exmap m;
  for (std::size_t i = 0; i < symbols.size(); ++i) m[symbols[i]] = values[i];
  return GiNaC::ex_to<GiNaC::numeric>(e.subs(m).evalf()).to_double();
}

std::size_t count_op(const StraightLineProgram& p, OpCode op) {
  std::size_t n = 0;
  for (const auto& ins : p.code()) n += ins.op == op;
  return n;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(straight_line_program)

BOOST_AUTO_TEST_CASE(common_subexpressions_are_shared) {
  GiNaC::symbol x("x"), y("y");
  const GiNaC::ex e = GiNaC::pow(x + y, 2) + GiNaC::pow(x + y, 3);
  const StraightLineProgram shared({e}, {x, y});
  const StraightLineProgram unshared({e}, {x, y}, false);
  // x + y once, its square, its cube, the sum.
  BOOST_CHECK_EQUAL(shared.instruction_count(), 4u);
  BOOST_CHECK_EQUAL(count_op(shared, OpCode::add), 2u);
  BOOST_CHECK_EQUAL(count_op(unshared, OpCode::add), 3u);
  BOOST_CHECK_LT(shared.instruction_count(), unshared.instruction_count());
  const double in[2] = {0.25, 1.5};
  double a, b;
  shared.evaluate(in, &a);
  unshared.evaluate(in, &b);
  BOOST_CHECK_CLOSE(a, std::pow(1.75, 2) + std::pow(1.75, 3), 1e-13);
  BOOST_CHECK_EQUAL(a, b);

  // Sharing across outputs: the second output costs nothing new.
  const StraightLineProgram two({e, GiNaC::pow(x + y, 3)}, {x, y});
  BOOST_CHECK_EQUAL(two.instruction_count(), 4u);
}

BOOST_AUTO_TEST_CASE(squares_are_tight_over_intervals) {
  GiNaC::symbol x("x");
  const StraightLineProgram p({GiNaC::pow(x, 2), x * x, GiNaC::pow(x, 3) - x}, {x});
  BOOST_CHECK_EQUAL(count_op(p, OpCode::square), 1u);  // x*x is the same GiNaC expression as x^2
  RoundingGuard guard;
  const Interval in(-1, 2);
  Interval out[3];
  p.evaluate(&in, out);
  BOOST_CHECK_EQUAL(out[0].inf(), 0.0);
  BOOST_CHECK_EQUAL(out[0].sup(), 4.0);
  BOOST_CHECK_EQUAL(out[1].inf(), 0.0);
  BOOST_CHECK_EQUAL(out[1].sup(), 4.0);
  BOOST_CHECK_EQUAL(out[2].inf(), -3.0);  // [-1, 8] − [-1, 2]
  BOOST_CHECK_EQUAL(out[2].sup(), 9.0);
}

// A product by a constant that is exactly a double is a scale, evaluated over intervals by the
// double: the enclosure is bit for bit the product with the point interval.  A constant that is
// not a double (1/3) keeps the product of intervals.
BOOST_AUTO_TEST_CASE(products_by_exact_constants_scale_with_the_same_enclosure) {
  GiNaC::symbol x("x"), y("y");
  const StraightLineProgram p({3 * x, GiNaC::numeric(-5, 4) * x * y, x / 3}, {x, y});
  BOOST_CHECK_EQUAL(count_op(p, OpCode::scale), 2u);
  BOOST_CHECK_EQUAL(count_op(p, OpCode::mul), 2u);  // x·y and x·(1/3)
  RoundingGuard guard;
  const Interval in[2] = {Interval(-1.1, 0.7), Interval(0.3, 2.9)};
  Interval out[3];
  p.evaluate(in, out);
  const Interval expected[2] = {Interval(3) * in[0], -(Interval(1.25) * (in[0] * in[1]))};
  for (int i = 0; i < 2; ++i) {
    BOOST_CHECK_EQUAL(out[i].inf(), expected[i].inf());
    BOOST_CHECK_EQUAL(out[i].sup(), expected[i].sup());
  }
  BOOST_TEST((out[2].inf() <= -1.1 / 3 && 0.7 / 3 <= out[2].sup()));
  const double point[2] = {-1.1, 0.3};
  double value[3];
  p.evaluate(point, value);
  BOOST_CHECK_EQUAL(value[0], 3 * -1.1);
}

// The degree bound follows the operations: (x² + y)³·q has degree 6 in (x, y) and 7 in (x, y, q);
// a program with a division has none.
BOOST_AUTO_TEST_CASE(degree_bound_of_a_polynomial_program) {
  GiNaC::symbol x("x"), y("y"), q("q");
  const StraightLineProgram p({GiNaC::pow(GiNaC::pow(x, 2) + y, 3) * q, x * y - 2}, {x, y, q});
  BOOST_CHECK_EQUAL(p.degree_bound(2).value_or(-1), 6);
  BOOST_CHECK_EQUAL(p.degree_bound(3).value_or(-1), 7);
  BOOST_CHECK_EQUAL(p.degree_bound(0).value_or(-1), 0);
  BOOST_TEST(!StraightLineProgram({x / y}, {x, y}).degree_bound(2));
}

BOOST_AUTO_TEST_CASE(every_operation_agrees_with_evalf) {
  GiNaC::symbol x("x"), y("y"), z("z");
  const std::vector<GiNaC::ex> outputs = {
      x - 2 * y + GiNaC::numeric(3, 7) * z,
      (x - 2 * y) / (GiNaC::pow(x, 2) + 1),
      -x * y / z,
      GiNaC::pow(x, -3) + GiNaC::pow(y, 5),
      GiNaC::sqrt(x * x + y * y),
      GiNaC::pow(x * x + 1, GiNaC::numeric(3, 2)) + GiNaC::pow(y * y + 2, GiNaC::numeric(-1, 2)),
      GiNaC::exp(-4 * (GiNaC::pow(x - GiNaC::numeric(9, 20), 2) + y * y)) * GiNaC::log(z + 3),
      GiNaC::sin(x * GiNaC::Pi) * GiNaC::cos(y) - GiNaC::cos(z) / 5,
      GiNaC::ex(GiNaC::numeric(-7, 3)),
      y,
  };
  const StraightLineProgram p(outputs, {x, y, z});
  std::vector<double> out(outputs.size());
  for (const std::vector<double>& in : {std::vector<double>{0.3, -1.25, 0.7}, std::vector<double>{-2.5, 0.125, 3.0}}) {
    p.evaluate(in.data(), out.data());
    for (std::size_t i = 0; i < outputs.size(); ++i) {
      const double ref = evalf_at(outputs[i], {x, y, z}, in);
      BOOST_CHECK_MESSAGE(std::fabs(out[i] - ref) <= 1e-14 * std::max(1.0, std::fabs(ref)),
                          "output " << i << " = " << outputs[i] << ": " << out[i] << " vs " << ref);
    }
  }
}

BOOST_AUTO_TEST_CASE(program_does_not_depend_on_ginac_term_order) {
  // GiNaC orders the terms of sums and products by hash values that depend on the creation order
  // of symbols (and, across runs, on addresses).  The program must not.
  const auto build = [](const GiNaC::symbol& x, const GiNaC::symbol& y, const GiNaC::symbol& z) {
    const GiNaC::ex g = GiNaC::pow(x, 2) - GiNaC::pow(x, 4) - GiNaC::pow(y, 2);
    const GiNaC::ex E = GiNaC::pow(g, 2) + z * z - GiNaC::numeric(1, 50) + x * y * z - 3 * y / (1 + z * z);
    return std::vector<GiNaC::ex>{E, E.diff(x), E.diff(y), E.diff(z) * GiNaC::exp(x - y)};
  };
  GiNaC::symbol x1("x"), y1("y"), z1("z");
  GiNaC::symbol z2("z"), y2("y"), x2("x");  // created in the opposite order
  const StraightLineProgram a(build(x1, y1, z1), {x1, y1, z1});
  const StraightLineProgram b(build(x2, y2, z2), {x2, y2, z2});
  BOOST_REQUIRE_EQUAL(a.instruction_count(), b.instruction_count());
  BOOST_REQUIRE_EQUAL(a.n_constants(), b.n_constants());
  for (std::size_t k = 0; k < a.instruction_count(); ++k) {
    BOOST_CHECK_EQUAL(a.code()[k].op, b.code()[k].op);
    BOOST_CHECK_EQUAL(a.code()[k].a, b.code()[k].a);
    BOOST_CHECK_EQUAL(a.code()[k].b, b.code()[k].b);
  }
  const double in[3] = {0.3, -0.7, 0.11};
  double va[4], vb[4];
  a.evaluate(in, va);
  b.evaluate(in, vb);
  for (int k = 0; k < 4; ++k) BOOST_CHECK_EQUAL(va[k], vb[k]);  // bitwise the same roundings
}

BOOST_AUTO_TEST_CASE(interval_and_mpfi_programs_enclose_transcendental_expressions) {
  GiNaC::symbol x("x"), y("y");
  const std::vector<GiNaC::ex> outputs = {
      GiNaC::sin(x * GiNaC::Pi) * GiNaC::cos(3 * y) - GiNaC::exp(-x * x - y * y),
      GiNaC::log(x * x + y * y + GiNaC::numeric(1, 10)) / (2 + GiNaC::sin(y)),
      GiNaC::sqrt(GiNaC::pow(x, 4) + 1) - GiNaC::pow(x - y, 3) + GiNaC::numeric(1, 3) / (x * x + 1),
  };
  const StraightLineProgram p(outputs, {x, y});
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> centre(-3, 3), unit(0, 1);
  const unsigned saved = MpfiInterval::default_precision();
  MpfiInterval::default_precision(20);
  for (int trial = 0; trial < 200; ++trial) {
    const double cx = centre(rng), cy = centre(rng), r = std::pow(10.0, -5 * unit(rng)) * 2;
    const Interval box[2] = {Interval(cx - r, cx + r), Interval(cy - r, cy + r)};
    const MpfiInterval fbox[2] = {MpfiInterval(cx - r, cx + r), MpfiInterval(cy - r, cy + r)};
    Interval out[3];
    MpfiInterval fout[3];
    {
      RoundingGuard guard;
      p.evaluate(box, out);
    }
    p.evaluate(fbox, fout);
    for (int s = 0; s < 10; ++s) {
      const double point[2] = {cx - r + 2 * r * unit(rng), cy - r + 2 * r * unit(rng)};
      double v[3];
      p.evaluate(point, v);
      for (int k = 0; k < 3; ++k) {
        BOOST_CHECK_MESSAGE(out[k].inf() <= v[k] && v[k] <= out[k].sup(),
                            "output " << k << " at (" << point[0] << ", " << point[1] << ")");
        // MPFI encloses the exact value; the double differs from it by far less than 1e-9.
        BOOST_CHECK(lower(fout[k]) <= v[k] + 1e-9 * (1 + std::fabs(v[k])) &&
                    v[k] - 1e-9 * (1 + std::fabs(v[k])) <= upper(fout[k]));
      }
    }
  }
  MpfiInterval::default_precision(saved);
}

BOOST_AUTO_TEST_CASE(split_inputs_and_outputs_and_no_inputs) {
  GiNaC::symbol t("t"), p("p"), q("q");
  const StraightLineProgram program({t * p, t + q, p - q}, {t, p, q});
  const double unknown = 2, parameters[2] = {3, 5};
  double first, rest[2];
  program.evaluate(&unknown, 1, parameters, &first, 1, rest);
  BOOST_CHECK_EQUAL(first, 6.0);
  BOOST_CHECK_EQUAL(rest[0], 7.0);
  BOOST_CHECK_EQUAL(rest[1], -2.0);

  const StraightLineProgram constants({GiNaC::Pi * 2 / 3, GiNaC::numeric(1, 10)}, {});
  BOOST_CHECK_EQUAL(constants.n_inputs(), 0u);
  double c[2];
  constants.evaluate(static_cast<const double*>(nullptr), c);
  BOOST_CHECK_CLOSE(c[0], 2 * M_PI / 3, 1e-13);
  BOOST_CHECK_EQUAL(c[1], 0.1);
  RoundingGuard guard;
  Interval ci[2];
  constants.evaluate(static_cast<const Interval*>(nullptr), ci);
  BOOST_CHECK(ci[1].inf() < ci[1].sup());  // 1/10 is not a double: enclosed by two
  BOOST_CHECK(ci[0].inf() <= 2 * M_PI / 3 && 2 * M_PI / 3 <= ci[0].sup());
}

BOOST_AUTO_TEST_CASE(unsupported_expressions_throw) {
  GiNaC::symbol x("x"), y("y"), w("w");
  const std::vector<GiNaC::symbol> in = {x, y};
  BOOST_CHECK_THROW(StraightLineProgram({GiNaC::pow(x, GiNaC::numeric(1, 3))}, in), PreconditionViolation);
  BOOST_CHECK_THROW(StraightLineProgram({GiNaC::pow(x, y)}, in), PreconditionViolation);
  BOOST_CHECK_THROW(StraightLineProgram({GiNaC::tan(x)}, in), PreconditionViolation);
  BOOST_CHECK_THROW(StraightLineProgram({GiNaC::abs(x)}, in), PreconditionViolation);
  BOOST_CHECK_THROW(StraightLineProgram({x + w}, in), PreconditionViolation);
  BOOST_CHECK_THROW(StraightLineProgram({x + GiNaC::numeric(0.5)}, in), PreconditionViolation);
  BOOST_CHECK_THROW(StraightLineProgram({x + GiNaC::I}, in), PreconditionViolation);
  BOOST_CHECK_THROW(StraightLineProgram({x * GiNaC::Euler}, in), PreconditionViolation);
  BOOST_CHECK_THROW(StraightLineProgram({x}, {x, x}), PreconditionViolation);
  std::ostringstream os;
  os << OpCode::square;
  BOOST_CHECK_EQUAL(os.str(), "square");
}

BOOST_AUTO_TEST_CASE(programs_alternate_and_threads_evaluate_concurrently) {
  GiNaC::symbol x("x"), y("y");
  const StraightLineProgram a({GiNaC::pow(x, 4) + GiNaC::numeric(1, 3) * y}, {x, y});
  const StraightLineProgram b({GiNaC::numeric(2, 3) - x * y}, {x, y});
  const double in[2] = {1.5, -2};
  double va, vb;
  for (int k = 0; k < 3; ++k) {  // constants reloaded when another program ran in between
    a.evaluate(in, &va);
    b.evaluate(in, &vb);
    BOOST_CHECK_CLOSE(va, std::pow(1.5, 4) - 2.0 / 3, 1e-13);
    BOOST_CHECK_CLOSE(vb, 2.0 / 3 + 3, 1e-13);
  }
  std::vector<double> results(4, 0);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      double sum = 0;
      for (int k = 0; k < 2000; ++k) {
        const double p[2] = {0.001 * k, 1.0 + t};
        double v;
        (t % 2 ? a : b).evaluate(p, &v);
        sum += v;
      }
      results[t] = sum;
    });
  }
  for (auto& th : threads) th.join();
  for (int t = 0; t < 4; ++t) {
    double sum = 0;
    for (int k = 0; k < 2000; ++k) {
      const double xk = 0.001 * k, yk = 1.0 + t;
      sum += t % 2 ? std::pow(xk, 4) + yk / 3 : 2.0 / 3 - xk * yk;
    }
    BOOST_CHECK_CLOSE(results[t], sum, 1e-10);
  }
}

BOOST_AUTO_TEST_CASE(multiprecision_registers_follow_the_default_precision) {
  GiNaC::symbol x("x");
  const StraightLineProgram p({x / 3 + GiNaC::Pi}, {x});
  const unsigned saved = MpfrReal::default_precision();
  for (unsigned digits : {20u, 80u}) {
    MpfrReal::default_precision(digits);
    const MpfrReal in = 1;
    MpfrReal out;
    p.evaluate(&in, &out);
    const MpfrReal ref = MpfrReal(1) / 3 + boost::math::constants::pi<MpfrReal>();
    BOOST_CHECK(abs(out - ref) < pow(MpfrReal(10), -static_cast<int>(digits) + 1));
    BOOST_CHECK_EQUAL(mpfr_get_prec(out.backend().data()),
                      static_cast<mpfr_prec_t>(ScalarTraits<MpfrReal>::precision()));
  }
  MpfrReal::default_precision(saved);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_CASE(evaluation_along_a_line_gives_the_exact_coefficients) {
  // f = (x + 2y)^3 − x·y² + 5 along (1, −1) + t (2, 3): the truncation order may be below the
  // degree of intermediate registers (here order 2 < 3): the low coefficients stay exact.
  const GiNaC::symbol x("x"), y("y"), t("t");
  const GiNaC::ex f = GiNaC::pow(x + 2 * y, 3) - x * GiNaC::pow(y, 2) + 5;
  const StraightLineProgram program({f}, {x, y});
  BOOST_TEST(program.is_polynomial_program());
  const GiNaC::ex along = f.subs(GiNaC::lst{x == 1 + 2 * t, y == -1 + 3 * t}).expand();
  for (int order : {1, 2, 3, 5}) {
    std::vector<double> coefficients(static_cast<std::size_t>(order) + 1);
    const double point[2] = {1, -1}, direction[2] = {2, 3};
    BOOST_TEST_REQUIRE(program.evaluate_along_line(point, direction, order, coefficients.data()));
    for (int k = 0; k <= order; ++k)
      BOOST_TEST(coefficients[k] == GiNaC::ex_to<GiNaC::numeric>(along.coeff(t, k)).to_double());
  }
  // Over intervals, with a constant that is not a double: 1/3 is enclosed, so is each coefficient.
  const GiNaC::ex g = GiNaC::pow(x, 2) / 3 - y;
  const StraightLineProgram third({g}, {x, y});
  RoundingGuard guard;
  const Interval point[2] = {Interval(1), Interval(0)}, direction[2] = {Interval(1), Interval(1)};
  Interval c[3];
  BOOST_TEST_REQUIRE(third.evaluate_along_line(point, direction, 2, c));
  // (1 + t)²/3 − t = 1/3 − t/3 + t²/3.
  for (int k = 0; k < 3; ++k) {
    const double third_value = (k == 1 ? -1.0 : 1.0) / 3;
    BOOST_TEST(c[k].inf() <= third_value);
    BOOST_TEST(c[k].sup() >= third_value);
    BOOST_TEST(c[k].sup() - c[k].inf() <= 1e-15);
  }
}

BOOST_AUTO_TEST_CASE(evaluation_along_a_line_is_exact_above_and_below_the_degree) {
  // f = (x − 2y)^5·z + 3(y + z)² − x has degree 6 along a line: for every order the coefficients
  // up to min(order, 6) are exact (small integers, exact in doubles) and those above 6 are zero,
  // whatever another program left in the evaluator's scratch series in between.
  const GiNaC::symbol x("x"), y("y"), z("z"), t("t");
  const GiNaC::ex f = GiNaC::pow(x - 2 * y, 5) * z + 3 * GiNaC::pow(y + z, 2) - x;
  const StraightLineProgram program({f}, {x, y, z});
  const StraightLineProgram other({GiNaC::pow(x + 3, 7) * GiNaC::pow(y, 4) - z}, {x, y, z});
  const GiNaC::ex along = f.subs(GiNaC::lst{x == 1 + t, y == 2 - t, z == -1 + 2 * t}).expand();
  const double point[3] = {1, 2, -1}, direction[3] = {1, -1, 2};
  for (int order : {0, 3, 6, 9}) {
    std::vector<double> scratch(10), coefficients(static_cast<std::size_t>(order) + 1, 7.0);
    const double far[3] = {5, -4, 3}, steep[3] = {-2, 6, 1};
    BOOST_TEST_REQUIRE(other.evaluate_along_line(far, steep, 9, scratch.data()));
    BOOST_TEST_REQUIRE(program.evaluate_along_line(point, direction, order, coefficients.data()));
    for (int k = 0; k <= order; ++k)
      BOOST_TEST(coefficients[k] == GiNaC::ex_to<GiNaC::numeric>(along.coeff(t, k)).to_double(),
                 "order " << order << ", coefficient " << k);
  }
  // The same program again and again, at other lines and orders (the scratch series are then
  // reused without being cleared): still exact, and zero above the degree.
  const std::array<std::array<double, 6>, 4> lines{{{0, 1, 2, 1, 1, -1}, {-1, 0, 3, 2, 0, 1}, {2, 2, 0, 0, -1, 1},
                                                   {1, -3, 1, 1, 2, 0}}};
  for (int order : {9, 9, 3, 9, 9}) {
    for (const auto& l : lines) {
      const GiNaC::ex on_line =
          f.subs(GiNaC::lst{x == l[0] + l[3] * t, y == l[1] + l[4] * t, z == l[2] + l[5] * t}).expand();
      std::vector<double> coefficients(static_cast<std::size_t>(order) + 1, 7.0);
      BOOST_TEST_REQUIRE(program.evaluate_along_line(l.data(), l.data() + 3, order, coefficients.data()));
      for (int k = 0; k <= order; ++k)
        BOOST_TEST(coefficients[k] == GiNaC::ex_to<GiNaC::numeric>(on_line.coeff(t, k)).to_double(),
                   "order " << order << ", coefficient " << k);
    }
  }
}

BOOST_AUTO_TEST_CASE(evaluation_along_a_line_refuses_non_polynomial_programs) {
  const GiNaC::symbol x("x");
  const StraightLineProgram program({GiNaC::exp(x) + x}, {x});
  BOOST_TEST(!program.is_polynomial_program());
  const double point[1] = {0}, direction[1] = {1};
  double c[3] = {7, 7, 7};
  BOOST_TEST(!program.evaluate_along_line(point, direction, 2, c));
  BOOST_TEST(c[0] == 7.0);
}
