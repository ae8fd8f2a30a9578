#pragma once
//! \file bernstein.h
//! Interval Bernstein-basis tools for the univariate isolator (internal).  Every function needs a
//! live RoundingGuard; every result is an enclosure (each exact coefficient of every polynomial
//! of the input family lies in the corresponding output interval).

#include "symbolic/scalar_types.h"

namespace delmesh::detail {

//! Largest degree the Bernstein conversion accepts.  The conversion computes every binomial
//! coefficient C(n, k), n ≤ this, exactly in 64-bit unsigned integers (Pascal's triangle;
//! C(60, 30) < 2^57) and enters it into the interval arithmetic as an enclosure: the exact double
//! when C(n, k) is one (every C(n, k) with n ≤ 56 is below 2^53), else the two neighbouring doubles
//! (C(57, 28) and beyond exceed 2^53 and need not be doubles).  Every use is an interval operation,
//! so it rounds outward either way.
inline constexpr int max_bernstein_degree = 60;

//! Bernstein coefficients b_0..b_d on s ∈ [0, 1] of q(s) = Σ_k c_k (t0 + h s)^k, for every
//! c_k ∈ c[k] and h ∈ h_range (Taylor shift, scaling, then b_i = Σ_{k≤i} C(i,k)/C(d,k) q_k, with the
//! binomials enclosed as described at max_bernstein_degree).
//! `scratch` holds d + 1 intervals.  Precondition: 0 ≤ d ≤ max_bernstein_degree.
void bernstein_from_monomial(int d, const Interval* c, double t0, const Interval& h_range, Interval* b,
                             Interval* scratch);

//! de Casteljau subdivision at λ ∈ (0, 1) (a double, taken exactly): left holds the Bernstein
//! coefficients of the piece [0, λ], right those of [λ, 1], each reparametrized to [0, 1].
//! left[d] = right[0] encloses q(λ).  `scratch` holds d + 1 intervals; outputs must not alias b.
void de_casteljau(int d, const Interval* b, double lambda, Interval* left, Interval* right, Interval* scratch);

//! Horner evaluation of Σ_k c_k x^k over the interval x.
Interval horner(int d, const Interval* c, const Interval& x);
//! Horner evaluation of the derivative Σ_k k c_k x^{k−1} over the interval x.
Interval horner_derivative(int d, const Interval* c, const Interval& x);

}  // namespace delmesh::detail
