#include "symbolic/compiled_system.h"

#include <cmath>
#include <random>
#include <sstream>
#include <string>

#include <boost/test/unit_test.hpp>
#include <mpfi.h>
#include <mpfr.h>

#include "common/errors.h"
#include "symbolic/catalog.h"
#include "solvers/primitives.h"
#include "symbolic/scalar_traits.h"
#include "tests/symbolic/exact_rational.h"

using namespace delmesh;
using delmesh::testing::exact;

namespace {

//! One primitive of one catalog surface, derived and compiled (with Hessians) once per test run.
struct Case {
  std::string label;  // "surface/primitive"
  const CatalogEntry* entry;
  bool polynomial;
  PrimitiveSystem system;
  CompiledSystem compiled;
};

const std::vector<Case>& cases() {
  static const std::vector<Case> all = [] {
    std::vector<Case> v;
    for (const CatalogEntry& entry : catalog()) {
      const Surface surface = entry.surface();
      for (const PrimitiveInfo& info : primitive_registry()) {
        PrimitiveSystem system = info.build(surface);
        CompiledSystem compiled(system, true);
        v.push_back(Case{entry.name + "/" + info.name, &entry, surface.is_polynomial(), std::move(system),
                         std::move(compiled)});
      }
    }
    return v;
  }();
  return all;
}

//! A random input of a case: unknowns in the catalog box (x, y, z) or in [-1, 1] (t, u, v),
//! parameters in [-1, 1]; all dyadic rationals k/1024, so exactly representable everywhere.
struct Input {
  std::vector<double> unknowns, parameters;
};
Input random_input(const Case& c, std::mt19937_64& rng) {
  const auto dyadic = [&](double lo, double hi) {
    std::uniform_int_distribution<long> k(static_cast<long>(std::ceil(lo * 1024)), static_cast<long>(std::floor(hi * 1024)));
    return static_cast<double>(k(rng)) / 1024;
  };
  Input in;
  const bool world = c.system.n_unknowns() == 3;
  for (std::size_t j = 0; j < c.system.n_unknowns(); ++j)
    in.unknowns.push_back(world ? dyadic(c.entry->box.lo[j], c.entry->box.hi[j]) : dyadic(-1, 1));
  for (std::size_t j = 0; j < c.system.n_parameters(); ++j) in.parameters.push_back(dyadic(-1, 1));
  return in;
}

//! The exact substitution of an input.
GiNaC::exmap exact_substitution(const Case& c, const Input& in) {
  GiNaC::exmap m;
  for (std::size_t j = 0; j < in.unknowns.size(); ++j) m[c.system.unknowns[j]] = exact(in.unknowns[j]);
  for (std::size_t j = 0; j < in.parameters.size(); ++j) m[c.system.parameters[j]] = exact(in.parameters[j]);
  return m;
}

//! Equations then the row-major Jacobian, as expressions.
std::vector<GiNaC::ex> values_and_jacobian_expressions(const PrimitiveSystem& s) {
  std::vector<GiNaC::ex> out(s.equations);
  for (std::size_t i = 0; i < s.n_equations(); ++i)
    for (std::size_t j = 0; j < s.n_unknowns(); ++j) out.push_back(s.jacobian(i, j));
  return out;
}

struct DoubleOutput {
  std::vector<double> all;  // values then Jacobian
};
DoubleOutput evaluate_double(const Case& c, const Input& in) {
  const std::size_t m = c.system.n_equations(), n = c.system.n_unknowns();
  DoubleOutput out;
  out.all.resize(m + m * n);
  c.compiled.values_and_jacobian(in.unknowns.data(), in.parameters.data(), out.all.data(), out.all.data() + m);
  return out;
}

Rational to_rational(const GiNaC::numeric& q) {
  std::ostringstream os;
  os << q.numer() << "/" << q.denom();
  return Rational(os.str());
}

bool close(double a, double ref, double relative) {
  return std::fabs(a - ref) <= relative * std::max(1.0, std::fabs(ref));
}

}  // namespace

BOOST_AUTO_TEST_SUITE(compiled_system)

BOOST_AUTO_TEST_CASE(every_catalog_primitive_compiles_with_shared_subexpressions) {
  BOOST_REQUIRE_GE(cases().size(), 48u);  // ≥ 8 surfaces × 6 primitives
  for (const Case& c : cases()) {
    BOOST_TEST_CONTEXT(c.label) {
      BOOST_CHECK_EQUAL(c.compiled.n_unknowns(), c.system.n_unknowns());
      BOOST_CHECK_EQUAL(c.compiled.n_parameters(), c.system.n_parameters());
      BOOST_CHECK_EQUAL(c.compiled.n_equations(), c.system.n_equations());
      BOOST_CHECK(c.compiled.has_hessians());
      BOOST_CHECK_GT(c.compiled.instruction_count(), 0u);
    }
  }
}

BOOST_AUTO_TEST_CASE(double_agrees_with_evalf_for_every_catalog_primitive) {
  std::mt19937_64 rng(11);
  for (const Case& c : cases()) {
    const std::vector<GiNaC::ex> expressions = values_and_jacobian_expressions(c.system);
    for (int trial = 0; trial < 4; ++trial) {
      const Input in = random_input(c, rng);
      const DoubleOutput out = evaluate_double(c, in);
      const GiNaC::exmap m = exact_substitution(c, in);
      std::vector<double> single(c.system.n_equations());
      c.compiled.values(in.unknowns.data(), in.parameters.data(), single.data());
      for (std::size_t k = 0; k < expressions.size(); ++k) {
        const double ref = GiNaC::ex_to<GiNaC::numeric>(expressions[k].subs(m).evalf()).to_double();
        BOOST_CHECK_MESSAGE(close(out.all[k], ref, 1e-12),
                            c.label << " output " << k << ": " << out.all[k] << " vs evalf " << ref);
        if (k < single.size()) BOOST_CHECK_EQUAL(single[k], out.all[k]);
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(interval_encloses_point_values_on_random_boxes) {
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> unit(0, 1);
  for (const Case& c : cases()) {
    const std::size_t m = c.system.n_equations(), n = c.system.n_unknowns(), p = c.system.n_parameters();
    for (int trial = 0; trial < 3; ++trial) {
      const Input centre = random_input(c, rng);
      const double radius = std::pow(10.0, -4.0 * unit(rng)) * 0.5;
      std::vector<Interval> box(n), params(p), out(m + m * n);
      for (std::size_t j = 0; j < n; ++j) box[j] = Interval(centre.unknowns[j] - radius, centre.unknowns[j] + radius);
      // Parameters: small intervals too (the mesher passes exact doubles, but enclosure must hold).
      for (std::size_t j = 0; j < p; ++j)
        params[j] = trial == 0 ? Interval(centre.parameters[j])
                               : Interval(centre.parameters[j], centre.parameters[j] + radius * 0.1);
      {
        RoundingGuard guard;
        c.compiled.values_and_jacobian(box.data(), params.data(), out.data(), out.data() + m);
      }
      for (int s = 0; s < 12; ++s) {
        Input point;
        for (std::size_t j = 0; j < n; ++j) point.unknowns.push_back(box[j].inf() + (box[j].sup() - box[j].inf()) * unit(rng));
        for (std::size_t j = 0; j < p; ++j)
          point.parameters.push_back(params[j].inf() + (params[j].sup() - params[j].inf()) * unit(rng));
        const DoubleOutput v = evaluate_double(c, point);
        for (std::size_t k = 0; k < v.all.size(); ++k)
          BOOST_CHECK_MESSAGE(out[k].inf() <= v.all[k] && v.all[k] <= out[k].sup(),
                              c.label << " output " << k << ": " << v.all[k] << " not in [" << out[k].inf()
                                      << ", " << out[k].sup() << "]");
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(mpfr_200_bits_agrees_with_exact_rational_evaluation) {
  const unsigned saved = MpfrReal::default_precision();
  MpfrReal::default_precision(61);  // 61 decimal digits: ≥ 200 bits
  BOOST_REQUIRE_GE(ScalarTraits<MpfrReal>::precision(), 200);
  std::mt19937_64 rng(13);
  int polynomial_cases = 0;
  for (const Case& c : cases()) {
    if (!c.polynomial) continue;
    ++polynomial_cases;
    const std::size_t m = c.system.n_equations(), n = c.system.n_unknowns();
    const std::vector<GiNaC::ex> expressions = values_and_jacobian_expressions(c.system);
    for (int trial = 0; trial < 2; ++trial) {
      const Input in = random_input(c, rng);
      std::vector<MpfrReal> u(in.unknowns.begin(), in.unknowns.end()), q(in.parameters.begin(), in.parameters.end());
      std::vector<MpfrReal> out(m + m * n);
      c.compiled.values_and_jacobian(u.data(), q.data(), out.data(), out.data() + m);
      const GiNaC::exmap sub = exact_substitution(c, in);
      for (std::size_t k = 0; k < expressions.size(); ++k) {
        const GiNaC::ex exact = expressions[k].subs(sub);
        BOOST_REQUIRE(GiNaC::is_a<GiNaC::numeric>(exact) && GiNaC::ex_to<GiNaC::numeric>(exact).is_rational());
        mpfr_t ref, diff;
        mpfr_init2(ref, 400);
        mpfr_init2(diff, 400);
        mpfr_set_q(ref, to_rational(GiNaC::ex_to<GiNaC::numeric>(exact)).backend().data(), MPFR_RNDN);
        mpfr_sub(diff, out[k].backend().data(), ref, MPFR_RNDN);
        mpfr_abs(diff, diff, MPFR_RNDN);
        mpfr_abs(ref, ref, MPFR_RNDN);
        const double scale = std::max(1.0, mpfr_get_d(ref, MPFR_RNDN));
        BOOST_CHECK_MESSAGE(mpfr_get_d(diff, MPFR_RNDU) <= 1e-55 * scale,
                            c.label << " output " << k << ": error " << mpfr_get_d(diff, MPFR_RNDU));
        mpfr_clear(ref);
        mpfr_clear(diff);
      }
    }
  }
  BOOST_CHECK_GE(polynomial_cases, 6 * 6);
  MpfrReal::default_precision(saved);
}

BOOST_AUTO_TEST_CASE(mpfi_encloses_the_exact_rational_value) {
  const unsigned saved = MpfiInterval::default_precision();
  MpfiInterval::default_precision(32);  // ≈ 106 bits, the first escalation precision
  std::mt19937_64 rng(14);
  for (const Case& c : cases()) {
    if (!c.polynomial) continue;
    const std::size_t m = c.system.n_equations(), n = c.system.n_unknowns();
    const std::vector<GiNaC::ex> expressions = values_and_jacobian_expressions(c.system);
    const Input in = random_input(c, rng);
    std::vector<MpfiInterval> u(in.unknowns.begin(), in.unknowns.end()), q(in.parameters.begin(), in.parameters.end());
    std::vector<MpfiInterval> out(m + m * n);
    c.compiled.values_and_jacobian(u.data(), q.data(), out.data(), out.data() + m);
    const GiNaC::exmap sub = exact_substitution(c, in);
    for (std::size_t k = 0; k < expressions.size(); ++k) {
      const Rational exact = to_rational(GiNaC::ex_to<GiNaC::numeric>(expressions[k].subs(sub)));
      BOOST_CHECK_MESSAGE(mpfi_is_inside_q(exact.backend().data(), out[k].backend().data()),
                          c.label << " output " << k << " misses the exact value");
      BOOST_CHECK(width(out[k]) < 1e-25 * std::max(1.0, std::fabs(exact.convert_to<double>())));
    }
  }
  MpfiInterval::default_precision(saved);
}

BOOST_AUTO_TEST_CASE(complex_agrees_with_evalf_at_complex_points) {
  std::mt19937_64 rng(15);
  for (const Case& c : cases()) {
    const std::size_t m = c.system.n_equations(), n = c.system.n_unknowns();
    const std::vector<GiNaC::ex> expressions = values_and_jacobian_expressions(c.system);
    const Input re = random_input(c, rng), im = random_input(c, rng);
    std::vector<Complex> u, q, out(m + m * n);
    GiNaC::exmap sub;
    for (std::size_t j = 0; j < n; ++j) {
      const double a = re.unknowns[j], b = 0.25 * im.unknowns[j];
      u.emplace_back(a, b);
      sub[c.system.unknowns[j]] = exact(a) + exact(b) * GiNaC::I;
    }
    for (std::size_t j = 0; j < c.system.n_parameters(); ++j) {
      const double a = re.parameters[j], b = 0.25 * im.parameters[j];
      q.emplace_back(a, b);
      sub[c.system.parameters[j]] = exact(a) + exact(b) * GiNaC::I;
    }
    c.compiled.values_and_jacobian(u.data(), q.data(), out.data(), out.data() + m);
    for (std::size_t k = 0; k < expressions.size(); ++k) {
      const GiNaC::numeric ref = GiNaC::ex_to<GiNaC::numeric>(expressions[k].subs(sub).evalf());
      const Complex r(ref.real().to_double(), ref.imag().to_double());
      BOOST_CHECK_MESSAGE(std::abs(out[k] - r) <= 1e-12 * std::max(1.0, std::abs(r)),
                          c.label << " output " << k << ": " << out[k] << " vs evalf " << r);
    }
  }
}

BOOST_AUTO_TEST_CASE(hessians_and_world_points_agree_with_evalf) {
  std::mt19937_64 rng(16);
  for (const Case& c : cases()) {
    const std::size_t m = c.system.n_equations(), n = c.system.n_unknowns();
    const Input in = random_input(c, rng);
    const GiNaC::exmap sub = exact_substitution(c, in);
    std::vector<double> h(m * n * n);
    c.compiled.hessians(in.unknowns.data(), in.parameters.data(), h.data());
    for (std::size_t i = 0; i < m; ++i)
      for (std::size_t j = 0; j < n; ++j)
        for (std::size_t k = 0; k < n; ++k) {
          const GiNaC::ex e = c.system.jacobian(i, j).diff(c.system.unknowns[k]);
          const double ref = GiNaC::ex_to<GiNaC::numeric>(e.subs(sub).evalf()).to_double();
          BOOST_CHECK_MESSAGE(close(h[(i * n + j) * n + k], ref, 1e-12),
                              c.label << " Hessian " << i << "," << j << "," << k << ": " << h[(i * n + j) * n + k]
                                      << " vs " << ref);
        }
    double xyz[3];
    c.compiled.world_point(in.unknowns.data(), in.parameters.data(), xyz);
    for (int d = 0; d < 3; ++d) {
      const double ref = GiNaC::ex_to<GiNaC::numeric>(c.system.world_point[d].subs(sub).evalf()).to_double();
      BOOST_CHECK(close(xyz[d], ref, 1e-14));
    }
  }
}

// The fused program gives exactly the numbers of values_and_jacobian() and hessians(), over
// intervals (outward rounding) and doubles, on every catalog primitive.
BOOST_AUTO_TEST_CASE(values_and_derivatives_are_exactly_the_separate_evaluations) {
  std::mt19937_64 rng(21);
  for (const Case& c : cases()) {
    BOOST_TEST_REQUIRE(c.compiled.has_hessians());
    const std::size_t m = c.system.n_equations(), n = c.system.n_unknowns();
    for (int trial = 0; trial < 3; ++trial) {
      const Input centre = random_input(c, rng);
      std::vector<Interval> box(n), params(centre.parameters.begin(), centre.parameters.end());
      for (std::size_t j = 0; j < n; ++j) box[j] = Interval(centre.unknowns[j] - 0.01, centre.unknowns[j] + 0.01);
      std::vector<Interval> separate(m + m * n + m * n * n), fused(separate.size());
      std::vector<double> separate_d(separate.size()), fused_d(separate.size());
      {
        RoundingGuard guard;
        c.compiled.values_and_jacobian(box.data(), params.data(), separate.data(), separate.data() + m);
        c.compiled.hessians(box.data(), params.data(), separate.data() + m + m * n);
        c.compiled.values_and_derivatives(box.data(), params.data(), fused.data(), fused.data() + m);
      }
      c.compiled.values_and_jacobian(centre.unknowns.data(), centre.parameters.data(), separate_d.data(),
                                     separate_d.data() + m);
      c.compiled.hessians(centre.unknowns.data(), centre.parameters.data(), separate_d.data() + m + m * n);
      c.compiled.values_and_derivatives(centre.unknowns.data(), centre.parameters.data(), fused_d.data(),
                                        fused_d.data() + m);
      for (std::size_t k = 0; k < separate.size(); ++k) {
        BOOST_CHECK_MESSAGE(separate[k].inf() == fused[k].inf() && separate[k].sup() == fused[k].sup(),
                            c.label << " output " << k);
        BOOST_CHECK_MESSAGE(separate_d[k] == fused_d[k], c.label << " double output " << k);
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(general_constructor_derives_the_jacobian) {
  GiNaC::symbol x("x"), y("y"), z("z"), a("a");
  const CompiledSystem s({x * x * y - a, GiNaC::sin(x) + z}, {x, y, z}, {a}, true);
  BOOST_CHECK_EQUAL(s.n_unknowns(), 3u);
  BOOST_CHECK_EQUAL(s.n_parameters(), 1u);
  const double u[3] = {0.5, 2.0, -1.0}, p[1] = {3.0};
  double v[2], J[6], H[18], w[3];
  s.values_and_jacobian(u, p, v, J);
  BOOST_CHECK_CLOSE(v[0], 0.5 - 3.0, 1e-13);
  BOOST_CHECK_CLOSE(v[1], std::sin(0.5) - 1.0, 1e-13);
  BOOST_CHECK_CLOSE(J[0], 2 * 0.5 * 2.0, 1e-13);  // ∂/∂x x²y = 2xy
  BOOST_CHECK_CLOSE(J[1], 0.25, 1e-13);           // ∂/∂y = x²
  BOOST_CHECK_EQUAL(J[2], 0.0);
  BOOST_CHECK_CLOSE(J[3], std::cos(0.5), 1e-13);
  BOOST_CHECK_EQUAL(J[4], 0.0);
  BOOST_CHECK_EQUAL(J[5], 1.0);
  s.hessians(u, p, H);
  BOOST_CHECK_CLOSE(H[0], 4.0, 1e-13);             // ∂²/∂x² x²y = 2y
  BOOST_CHECK_CLOSE(H[1], 1.0, 1e-13);             // ∂²/∂x∂y = 2x
  BOOST_CHECK_CLOSE(H[9], -std::sin(0.5), 1e-13);  // ∂²/∂x² sin x
  s.world_point(u, p, w);
  BOOST_CHECK_EQUAL(w[0], 0.5);
  BOOST_CHECK_EQUAL(w[1], 2.0);
  BOOST_CHECK_EQUAL(w[2], -1.0);

  // No unknowns: coefficients in parameters only (as LinePolynomial compiles them).
  CompiledSystem coefficients({a * a, 2 * a + 1}, {}, {a});
  BOOST_CHECK_EQUAL(coefficients.n_unknowns(), 0u);
  double c[2];
  coefficients.values(static_cast<const double*>(nullptr), p, c);
  BOOST_CHECK_EQUAL(c[0], 9.0);
  BOOST_CHECK_EQUAL(c[1], 7.0);
  {
    RoundingGuard guard;
    const Interval pi[1] = {Interval(-1, 2)};
    Interval ci[2];
    coefficients.values(static_cast<const Interval*>(nullptr), pi, ci);
    BOOST_CHECK_EQUAL(ci[0].inf(), 0.0);
    BOOST_CHECK_EQUAL(ci[0].sup(), 4.0);
  }
  BOOST_CHECK_THROW(coefficients.world_point(static_cast<const double*>(nullptr), p, w), PreconditionViolation);
  BOOST_CHECK_THROW(coefficients.hessians(static_cast<const double*>(nullptr), p, H), PreconditionViolation);
  BOOST_CHECK_THROW(coefficients.values_and_derivatives(static_cast<const double*>(nullptr), p, c, H),
                    PreconditionViolation);
  BOOST_CHECK(!coefficients.has_hessians());

  // Moved-from and moved-to systems keep working.
  CompiledSystem moved = std::move(coefficients);
  moved.values(static_cast<const double*>(nullptr), p, c);
  BOOST_CHECK_EQUAL(c[1], 7.0);
}

BOOST_AUTO_TEST_CASE(misuse_throws) {
  GiNaC::symbol x("x"), y("y");
  BOOST_CHECK_THROW(CompiledSystem({x + y}, {x}, {}), PreconditionViolation);             // y unknown to it
  BOOST_CHECK_THROW(CompiledSystem({GiNaC::pow(x, y)}, {x, y}, {}), PreconditionViolation);  // symbolic power
  PrimitiveSystem bad;
  bad.name = "bad";
  bad.unknowns = {x, y};
  bad.equations = {x * y};
  bad.jacobian = GiNaC::matrix(1, 1);
  bad.world_point = {x, y, 0};
  BOOST_CHECK_THROW(CompiledSystem{bad}, PreconditionViolation);
}

BOOST_AUTO_TEST_SUITE_END()
