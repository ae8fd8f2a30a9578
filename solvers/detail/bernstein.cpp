#include "solvers/detail/bernstein.h"

namespace delmesh::detail {

void bernstein_from_monomial(int d, const Interval* c, double t0, const Interval& h_range, Interval* b,
                             Interval* q) {
  // Taylor shift and scaling by Horner's scheme on polynomials: q ← q · (t0 + h s) + c_k.
  if (t0 == 0) {
    // No shift: q_k = c_k h^k.
    Interval power(1.0);
    for (int k = 0; k <= d; ++k, power *= h_range) q[k] = c[k] * power;
  } else {
    const Interval T0(t0);
    q[0] = c[d];
    for (int k = d - 1, deg = 0; k >= 0; --k, ++deg) {
      q[deg + 1] = h_range * q[deg];
      for (int j = deg; j >= 1; --j) q[j] = T0 * q[j] + h_range * q[j - 1];
      q[0] = T0 * q[0] + c[k];
    }
  }
  // Monomial in s → Bernstein: b_i = Σ_{k ≤ i} C(i, k) q_k / C(d, k).  Binomials are exact doubles.
  double binom_d[max_bernstein_degree + 1];
  binom_d[0] = 1;
  for (int k = 1; k <= d; ++k) binom_d[k] = binom_d[k - 1] * (d - k + 1) / k;  // exact: integers < 2^53
  for (int k = 0; k <= d; ++k) q[k] = q[k] / Interval(binom_d[k]);
  double binom_i[max_bernstein_degree + 1];
  for (int i = 0; i <= d; ++i) {
    // binom_i[k] = C(i, k), updated row by row of Pascal's triangle.
    binom_i[i] = 1;
    for (int k = i - 1; k >= 1; --k) binom_i[k] += binom_i[k - 1];
    binom_i[0] = 1;
    Interval acc = q[0];
    for (int k = 1; k <= i; ++k) acc += Interval(binom_i[k]) * q[k];
    b[i] = acc;
  }
}

void de_casteljau(int d, const Interval* b, double lambda, Interval* left, Interval* right, Interval* tmp) {
  for (int i = 0; i <= d; ++i) tmp[i] = b[i];
  left[0] = tmp[0];
  right[d] = tmp[d];
  if (lambda == 0.5) {
    for (int r = 1; r <= d; ++r) {
      for (int i = 0; i <= d - r; ++i) tmp[i] = (tmp[i] + tmp[i + 1]) * 0.5;
      left[r] = tmp[0];
      right[d - r] = tmp[d - r];
    }
    return;
  }
  const Interval L(lambda), M = Interval(1.0) - Interval(lambda);
  for (int r = 1; r <= d; ++r) {
    for (int i = 0; i <= d - r; ++i) tmp[i] = M * tmp[i] + L * tmp[i + 1];
    left[r] = tmp[0];
    right[d - r] = tmp[d - r];
  }
}

Interval horner(int d, const Interval* c, const Interval& x) {
  Interval acc = c[d];
  for (int k = d - 1; k >= 0; --k) acc = acc * x + c[k];
  return acc;
}

Interval horner_derivative(int d, const Interval* c, const Interval& x) {
  if (d == 0) return Interval(0);
  Interval acc = c[d] * Interval(static_cast<double>(d));
  for (int k = d - 1; k >= 1; --k) acc = acc * x + c[k] * Interval(static_cast<double>(k));
  return acc;
}

}  // namespace delmesh::detail
