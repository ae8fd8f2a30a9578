#include "solvers/detail/complex_krawczyk.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "common/errors.h"
#include "common/tolerances.h"

namespace delmesh::detail {

namespace tol = tolerances;

namespace {

using CMatrix = Eigen::Matrix<Complex, Eigen::Dynamic, Eigen::Dynamic>;
using CVector = Eigen::Matrix<Complex, Eigen::Dynamic, 1>;

double centre(const Interval& a) { return 0.5 * a.inf() + 0.5 * a.sup(); }

bool finite(const Interval& a) { return std::isfinite(a.inf()) && std::isfinite(a.sup()); }

//! (1 − t) and t γ as point rectangles, enclosed.  Needs a live RoundingGuard.
void homotopy_weights(const HomotopyMap& map, ComplexInterval& a, ComplexInterval& b) {
  const Interval t(map.t);
  a = ComplexInterval(Interval(1.0) - t, Interval(0.0));
  b = ComplexInterval(t * Interval(map.gamma.real()), t * Interval(map.gamma.imag()));
}

std::vector<ComplexInterval> lifted_parameters(const HomotopyMap& map) {
  std::vector<ComplexInterval> p;
  for (double v : map.parameters) p.emplace_back(Interval(v), Interval(0.0));
  return p;
}

//! H_t and its Jacobian over `box`.  Needs a live RoundingGuard.
void enclose_homotopy(const HomotopyMap& map, const ComplexBox& box, ComplexBox& values, ComplexBox& jacobian) {
  using Tr = ScalarTraits<ComplexInterval>;
  const std::size_t n = box.size();
  const std::vector<ComplexInterval> p = lifted_parameters(map);
  values.assign(n, {});
  jacobian.assign(n * n, {});
  map.f.values_and_jacobian(box.data(), p.data(), values.data(), jacobian.data());
  ComplexInterval a, b;
  homotopy_weights(map, a, b);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) Tr::mul(jacobian[i * n + j], jacobian[i * n + j], a);
    Tr::mul(values[i], values[i], a);
    const int d = map.degrees[i];
    ComplexInterval power, g, dg;
    Tr::pow(power, box[i], d - 1);  // u_i^{d−1}
    Tr::mul(g, power, box[i]);
    Tr::sub(g, g, ComplexInterval(Interval(1.0), Interval(0.0)));
    Tr::mul(dg, power, ComplexInterval(Interval(static_cast<double>(d)), Interval(0.0)));
    Tr::mul(g, g, b);
    Tr::mul(dg, dg, b);
    Tr::add(values[i], values[i], g);
    Tr::add(jacobian[i * n + i], jacobian[i * n + i], dg);
  }
}

//! H_t and its Jacobian at u in complex double.
void evaluate_point(const HomotopyMap& map, const std::vector<Complex>& u, CVector& values, CMatrix& jacobian) {
  const std::size_t n = u.size();
  std::vector<Complex> v(n), J(n * n);
  const std::vector<Complex> p(map.parameters.begin(), map.parameters.end());
  map.f.values_and_jacobian<Complex>(u.data(), p.data(), v.data(), J.data());
  const Complex a = 1.0 - map.t, b = map.t * map.gamma;
  values.resize(static_cast<Eigen::Index>(n));
  jacobian.resize(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  for (std::size_t i = 0; i < n; ++i) {
    const int d = map.degrees[i];
    const Complex power = std::pow(u[i], d - 1);
    values[static_cast<Eigen::Index>(i)] = a * v[i] + b * (power * u[i] - 1.0);
    for (std::size_t j = 0; j < n; ++j)
      jacobian(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = a * J[i * n + j];
    jacobian(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i)) += b * static_cast<double>(d) * power;
  }
}

double max_abs(const std::vector<Complex>& u) {
  double m = 0;
  for (const Complex& c : u) m = std::max(m, std::abs(c));
  return m;
}

double box_width(const ComplexBox& box) {
  double w = 0;
  for (const auto& c : box) w = std::max({w, c.re.sup() - c.re.inf(), c.im.sup() - c.im.inf()});
  return w;
}

bool strictly_inside(const Interval& a, const Interval& b) { return a.inf() > b.inf() && a.sup() < b.sup(); }

}  // namespace

void enclose_f_and_g(const HomotopyMap& map, const ComplexBox& box, ComplexBox& f_values, ComplexBox& g_values) {
  using Tr = ScalarTraits<ComplexInterval>;
  const std::size_t n = box.size();
  const std::vector<ComplexInterval> p = lifted_parameters(map);
  f_values.assign(n, {});
  g_values.assign(n, {});
  map.f.values(box.data(), p.data(), f_values.data());
  for (std::size_t i = 0; i < n; ++i) {
    Tr::pow(g_values[i], box[i], map.degrees[i]);
    Tr::sub(g_values[i], g_values[i], ComplexInterval(Interval(1.0), Interval(0.0)));
  }
}

void enclose_f_centred(const HomotopyMap& map, const ComplexBox& box, ComplexBox& f_centred) {
  using Tr = ScalarTraits<ComplexInterval>;
  const std::size_t n = box.size();
  const std::vector<ComplexInterval> p = lifted_parameters(map);
  ComplexBox values(n), jacobian(n * n), mid(n), offset(n);
  map.f.values_and_jacobian(box.data(), p.data(), values.data(), jacobian.data());
  for (std::size_t j = 0; j < n; ++j) {
    mid[j] = ComplexInterval(Interval(centre(box[j].re)), Interval(centre(box[j].im)));
    Tr::sub(offset[j], box[j], mid[j]);
  }
  f_centred.assign(n, {});
  map.f.values(mid.data(), p.data(), f_centred.data());
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) {
      ComplexInterval term;
      Tr::mul(term, jacobian[i * n + j], offset[j]);
      Tr::add(f_centred[i], f_centred[i], term);
    }
}

ComplexKrawczykResult complex_krawczyk_test(const HomotopyMap& map, const ComplexBox& box) {
  const std::size_t n = box.size();
  if (n != map.f.n_unknowns() || map.degrees.size() != n)
    throw PreconditionViolation("complex_krawczyk_test: the box, the degrees and the system differ in dimension");
  ComplexKrawczykResult result;
  result.contracted = box;
  for (const auto& c : box)
    if (!finite(c.re) || !finite(c.im)) return result;
  // the preconditioner Y = J(m)^{-1}, in complex double (round to nearest)
  std::vector<Complex> m(n);
  for (std::size_t i = 0; i < n; ++i) m[i] = Complex(centre(box[i].re), centre(box[i].im));
  CVector value_at_m;
  CMatrix jacobian_at_m;
  evaluate_point(map, m, value_at_m, jacobian_at_m);
  const Eigen::FullPivLU<CMatrix> lu(jacobian_at_m);
  if (!lu.isInvertible()) return result;
  const CMatrix Y = lu.inverse();
  if (!Y.allFinite()) return result;

  RoundingGuard guard;
  using Tr = ScalarTraits<ComplexInterval>;
  ComplexBox mid(n), fm, jm, fx, jx;
  for (std::size_t i = 0; i < n; ++i) mid[i] = ComplexInterval(m[i]);
  enclose_homotopy(map, mid, fm, jm);
  enclose_homotopy(map, box, fx, jx);
  for (const auto& v : fx)
    if (certainly_nonzero(v)) {
      result.outcome = KrawczykOutcome::no_root;
      return result;
    }
  ComplexBox k(n);
  bool inside = true, empty = false;
  for (std::size_t i = 0; i < n; ++i) {
    ComplexInterval sum = mid[i], term;
    for (std::size_t j = 0; j < n; ++j) {
      const ComplexInterval y(Y(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)));
      Tr::mul(term, y, fm[j]);
      Tr::sub(sum, sum, term);  // m − Y H(m)
      // (I − Y J(U))_{ij}
      ComplexInterval c(Interval(i == j ? 1.0 : 0.0), Interval(0.0));
      for (std::size_t l = 0; l < n; ++l) {
        const ComplexInterval y_il(Y(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(l)));
        Tr::mul(term, y_il, jx[l * n + j]);
        Tr::sub(c, c, term);
      }
      ComplexInterval offset;
      Tr::sub(offset, box[j], mid[j]);
      Tr::mul(term, c, offset);
      Tr::add(sum, sum, term);
    }
    k[i] = sum;
    if (!finite(sum.re) || !finite(sum.im)) return result;
    inside = inside && strictly_inside(sum.re, box[i].re) && strictly_inside(sum.im, box[i].im);
    const double re_lo = std::max(sum.re.inf(), box[i].re.inf()), re_hi = std::min(sum.re.sup(), box[i].re.sup());
    const double im_lo = std::max(sum.im.inf(), box[i].im.inf()), im_hi = std::min(sum.im.sup(), box[i].im.sup());
    if (re_lo > re_hi || im_lo > im_hi) {
      empty = true;
    } else {
      result.contracted[i] = ComplexInterval(Interval(re_lo, re_hi), Interval(im_lo, im_hi));
    }
  }
  if (empty) {
    result.outcome = KrawczykOutcome::no_root;
    result.contracted = box;
  } else if (inside) {
    result.outcome = KrawczykOutcome::unique_root;
  }
  return result;
}

double complex_newton(const HomotopyMap& map, std::vector<Complex>& u, int iterations) {
  double last = std::numeric_limits<double>::infinity();
  CVector values;
  CMatrix jacobian;
  for (int k = 0; k < iterations; ++k) {
    evaluate_point(map, u, values, jacobian);
    const Eigen::FullPivLU<CMatrix> lu(jacobian);
    if (!lu.isInvertible()) return std::numeric_limits<double>::infinity();
    const CVector delta = lu.solve(-values);
    if (!delta.allFinite()) return std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < u.size(); ++i) u[i] += delta[static_cast<Eigen::Index>(i)];
    const double size = delta.cwiseAbs().maxCoeff();
    if (size > last && k >= tol::homotopy_newton_noise_after_steps) break;  // round-off level reached
    last = size;
    if (size <= tol::homotopy_newton_converged_ulps * std::numeric_limits<double>::epsilon() * (1 + max_abs(u))) break;
  }
  return last;
}

bool certify_complex_zero(const HomotopyMap& map, std::vector<Complex> u, ComplexBox& out) {
  const double correction = complex_newton(map, u, tol::homotopy_polish_iterations);
  const double scale = max_abs(u);
  if (!std::isfinite(scale)) return false;
  double radius = tol::homotopy_certify_radius * (1 + scale);
  if (std::isfinite(correction)) radius = std::max(radius, tol::homotopy_correction_box_factor * correction);
  for (int attempt = 0; attempt < tol::homotopy_certify_attempts; ++attempt, radius *= tol::homotopy_certify_growth) {
    ComplexBox box;
    for (const Complex& c : u)
      box.emplace_back(Interval(c.real() - radius, c.real() + radius), Interval(c.imag() - radius, c.imag() + radius));
    ComplexKrawczykResult r = complex_krawczyk_test(map, box);
    if (r.outcome != KrawczykOutcome::unique_root) continue;
    out = r.contracted;
    for (int k = 0; k < tol::homotopy_contract_iterations; ++k) {
      const ComplexKrawczykResult again = complex_krawczyk_test(map, out);
      if (again.outcome != KrawczykOutcome::unique_root || !(box_width(again.contracted) < box_width(out))) break;
      out = again.contracted;
    }
    return true;
  }
  return false;
}

bool boxes_meet(const ComplexBox& a, const ComplexBox& b) {
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].re.sup() < b[i].re.inf() || b[i].re.sup() < a[i].re.inf()) return false;
    if (a[i].im.sup() < b[i].im.inf() || b[i].im.sup() < a[i].im.inf()) return false;
  }
  return true;
}

}  // namespace delmesh::detail
