#pragma once
//! \file complex_krawczyk.h
//! Internal: the Krawczyk test over complex boxes for the homotopy H_t(u) = t γ g(u) + (1 − t) f(u),
//! g_i(u) = u_i^{d_i} − 1, of solvers/homotopy_solver.h, and the interval evaluation of f and g
//! that the certificate of completeness (solvers/homotopy_certificate.h) needs.
//!
//! Theorem (Krawczyk; Moore's existence form, Neumaier's uniqueness form, "Interval methods for
//! systems of equations", Thm 5.1.8, applied on R^{2n} ≅ C^n).  Let U ⊂ C^n be a rectangular box,
//! m ∈ U, Y an n×n complex matrix, and
//!     K(U) = m − Y H_t(m) + (I − Y J(U)) (U − m)
//! evaluated in rectangular complex interval arithmetic (symbolic/complex_interval.h), where J(U)
//! encloses the complex Jacobian of H_t over U.  If K(U) ⊂ int U, then H_t has exactly one zero in
//! U, and it is regular.  If K(U) ∩ U = ∅, or some component of H_t(U) excludes 0, H_t has no zero
//! in U.  Why the complex form is the real theorem: H_t is holomorphic, so for x, m ∈ U,
//! H_t(x) − H_t(m) = A (x − m) with A = ∫₀¹ J(m + s(x − m)) ds, a complex matrix lying entrywise in
//! the convex rectangles of J(U); and rectangular complex products and sums are, written on
//! (Re, Im), exactly the real interval products and sums of the 2×2 real blocks [[a, −b], [b, a]].
//! So K(U) is the real Krawczyk operator of the map x ↦ H_t(x) on R^{2n} with the real interval
//! matrix of J(U)'s real form (which holds every slope A) and the real form of Y, and the real
//! theorem (krawczyk.h) applies unchanged.

#include <cstddef>
#include <vector>

#include "solvers/krawczyk.h"
#include "symbolic/compiled_system.h"
#include "symbolic/complex_interval.h"
#include "symbolic/scalar_types.h"

namespace delmesh::detail {

using ComplexBox = std::vector<ComplexInterval>;

//! H_t(u) = t γ g(u) + (1 − t) f(u) over C^n, f a square CompiledSystem with real parameters.
struct HomotopyMap {
  const CompiledSystem& f;
  const std::vector<double>& parameters;
  const std::vector<int>& degrees;  //!< d_i of g_i = u_i^{d_i} − 1
  Complex gamma;
  double t = 0;                     //!< t = 0: H_t = f
};

//! Encloses f(U) (natural interval extension) and g(U) over the complex box U.  Needs a live
//! RoundingGuard.
void enclose_f_and_g(const HomotopyMap& map, const ComplexBox& box, ComplexBox& f_values, ComplexBox& g_values);

//! Encloses f(U) by the mean-value form f(m) + J_f(U)(U − m) at the centre m of U (holomorphic f:
//! the slope between two points of U lies entrywise in the convex rectangles of J_f(U)); tighter
//! than the natural extension on small boxes.  Needs a live RoundingGuard.
void enclose_f_centred(const HomotopyMap& map, const ComplexBox& box, ComplexBox& f_centred);

struct ComplexKrawczykResult {
  KrawczykOutcome outcome = KrawczykOutcome::inconclusive;
  ComplexBox contracted;  //!< K(U) ∩ U (U itself when the test is inconclusive before K exists)
};

//! The test of the theorem above for H_t on `box` (every side finite), with m the box centre and
//! Y the inverse of the midpoint Jacobian at m (computed in complex double; inconclusive if it
//! is singular).  Sets up its own RoundingGuard.
ComplexKrawczykResult complex_krawczyk_test(const HomotopyMap& map, const ComplexBox& box);

//! Newton's method on H_t in complex double from u (at most `iterations` steps); returns the size
//! ‖Δu‖∞ of the last step (∞ if the Jacobian was singular or a value not finite).  Not certified.
double complex_newton(const HomotopyMap& map, std::vector<Complex>& u, int iterations);

//! A zero of H_t near u certified by complex_krawczyk_test: boxes of half-width r around the
//! Newton-polished u, r from tolerances::homotopy_certify_radius·(1 + ‖u‖∞) (or a multiple of the
//! last Newton step, if larger) growing by homotopy_certify_growth, at most
//! homotopy_certify_attempts boxes; the box proved is then contracted by Krawczyk iteration.
//! True with `out` the box holding exactly one zero (regular) of H_t; false if no box was proved.
bool certify_complex_zero(const HomotopyMap& map, std::vector<Complex> u, ComplexBox& out);

//! True iff a and b share a point.
bool boxes_meet(const ComplexBox& a, const ComplexBox& b);

}  // namespace delmesh::detail
