#include "solvers/detail/bernstein.h"

#include <array>
#include <cstdint>

namespace delmesh::detail {

namespace {

constexpr int pascal_rows = max_bernstein_degree + 1;
using PascalTriangle = std::array<std::array<std::uint64_t, pascal_rows>, pascal_rows>;

//! C(n, k) for 0 ≤ k ≤ n ≤ max_bernstein_degree, by Pascal's rule in exact integer arithmetic;
//! entries with k > n are 0.
constexpr PascalTriangle pascal_triangle() {
  PascalTriangle c{};
  for (int n = 0; n < pascal_rows; ++n) {
    c[n][0] = 1;
    for (int k = 1; k <= n; ++k) c[n][k] = c[n - 1][k - 1] + c[n - 1][k];
  }
  return c;
}

constexpr PascalTriangle binomials = pascal_triangle();

//! No sum of Pascal's rule wrapped around 2^64 (each entry is at least both of its summands).
constexpr bool pascal_triangle_exact() {
  for (int n = 1; n < pascal_rows; ++n)
    for (int k = 1; k <= n; ++k)
      if (binomials[n][k] < binomials[n - 1][k - 1] || binomials[n][k] < binomials[n - 1][k]) return false;
  return true;
}
static_assert(pascal_triangle_exact(), "max_bernstein_degree: binomial coefficients must fit in 64 bits");

//! An enclosure of the integer C(n, k): the high and low 32-bit halves are exact doubles, and
//! their interval sum is the exact double C(n, k) when it is one, else the two doubles around it.
//! Needs a live RoundingGuard.
Interval binomial_enclosure(int n, int k) {
  const std::uint64_t c = binomials[n][k];
  return Interval(static_cast<double>(c >> 32) * 0x1p32) + Interval(static_cast<double>(c & 0xffffffffu));
}

//! a · x for an enclosure a that may be a point: by the double itself then (the same correctly
//! rounded end products as the product of intervals, with one vector multiplication instead of
//! four).  Needs a live RoundingGuard.
Interval times(const Interval& a, const Interval& x) { return a.is_point() ? a.inf() * x : a * x; }

}  // namespace

void bernstein_from_monomial(int d, const Interval* c, double t0, const Interval& h_range, Interval* b,
                             Interval* q) {
  // Taylor shift and scaling by Horner's scheme on polynomials: q ← q · (t0 + h s) + c_k.
  if (t0 == 0) {
    // No shift: q_k = c_k h^k.
    Interval power(1.0);
    for (int k = 0; k <= d; ++k, power *= h_range) q[k] = c[k] * power;
  } else {
    q[0] = c[d];
    for (int k = d - 1, deg = 0; k >= 0; --k, ++deg) {
      q[deg + 1] = h_range * q[deg];
      for (int j = deg; j >= 1; --j) q[j] = t0 * q[j] + h_range * q[j - 1];
      q[0] = t0 * q[0] + c[k];
    }
  }
  // Monomial in s → Bernstein: b_i = Σ_{k ≤ i} C(i, k) q_k / C(d, k).
  for (int k = 0; k <= d; ++k) q[k] = q[k] / binomial_enclosure(d, k);
  for (int i = 0; i <= d; ++i) {
    Interval acc = q[0];
    for (int k = 1; k <= i; ++k) acc += times(binomial_enclosure(i, k), q[k]);
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

// A product by a point interval [t, t] is taken as the product by the double t, which gives the
// same enclosure (the two products of the bounds by t, rounded outward) with one vector
// multiplication instead of four.
Interval horner(int d, const Interval* c, const Interval& x) {
  Interval acc = c[d];
  if (x.is_point()) {
    const double t = x.inf();
    for (int k = d - 1; k >= 0; --k) acc = acc * t + c[k];
  } else {
    for (int k = d - 1; k >= 0; --k) acc = acc * x + c[k];
  }
  return acc;
}

Interval horner_derivative(int d, const Interval* c, const Interval& x) {
  if (d == 0) return Interval(0);
  Interval acc = c[d] * static_cast<double>(d);
  if (x.is_point()) {
    const double t = x.inf();
    for (int k = d - 1; k >= 1; --k) acc = acc * t + c[k] * static_cast<double>(k);
  } else {
    for (int k = d - 1; k >= 1; --k) acc = acc * x + c[k] * static_cast<double>(k);
  }
  return acc;
}

}  // namespace delmesh::detail
