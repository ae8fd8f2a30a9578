#pragma once
//! \file taylor_form.h
//! Taylor forms of polynomial equations on boxes (internal to the subdivision solver).  On a box
//! X = {c + r∘s : s ∈ [−1, 1]^n} an equation is held as g(s) = f(c + r∘s) = Σ_α a_α s^α with
//! interval coefficients a_α enclosing the exact ones (MonomialBasis order).  Ranges come from
//! the exact ranges of the monomials on the cube (s^α ranges over [0, ρ^|α|] when every
//! exponent is even, else over [−ρ^|α|, ρ^|α|]), so they converge linearly in the box width with
//! the optimal first-order constant — unlike the natural interval form of an expanded expression,
//! whose overestimate does not shrink relative to the box.  Bisection and contraction re-centre
//! the form along one axis by an affine substitution.  Every operation is interval arithmetic
//! under a live RoundingGuard, so each result encloses the exact one.

#include <cstddef>
#include <vector>

#include "symbolic/monomial_basis.h"
#include "symbolic/scalar_types.h"

namespace delmesh::detail {

//! a ← the coefficients of s ↦ g(s with s_axis replaced by μ + ρ s_axis), for every μ ∈ mu and
//! ρ ∈ rho (an enclosure; exact point intervals give the tightest).  a has basis.size() entries.
void substitute_affine(const MonomialBasis& basis, std::size_t axis, const Interval& mu, const Interval& rho,
                       Interval* a);

//! The half of the cube on `side` (−1: s_axis ≤ 0, +1: s_axis ≥ 0) as a new cube: substitute_affine
//! with μ = side/2, ρ = 1/2, computed with exact power-of-two scalings and additions only.
void bisect_axis(const MonomialBasis& basis, std::size_t axis, int side, Interval* a);

//! Enclosures of ρ^0, …, ρ^degree for a cube of half-width ρ ≥ 1 (the `rho_powers` below).
std::vector<Interval> radius_powers(double rho, int degree);

//! An enclosure of {g(s) : s ∈ [−ρ, ρ]^n}, ρ ≥ 1 given by its powers: rho_powers[j] ⊇ ρ^j for
//! j ≤ basis.degree().
Interval range_on_cube(const MonomialBasis& basis, const Interval* a, const Interval* rho_powers);

//! gradient[k] ⊇ {∂g/∂s_k (s) : s ∈ [−ρ, ρ]^n}, k < n, ρ as in range_on_cube.
void gradient_on_cube(const MonomialBasis& basis, const Interval* a, const Interval* rho_powers, Interval* gradient);

}  // namespace delmesh::detail
