#pragma once
//! \file interval_box.h
//! Small helpers on interval boxes shared by the certified solvers (internal).  Every function on
//! Interval values requires a live RoundingGuard unless it only reads bounds.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <mutex>

#include "symbolic/scalar_types.h"

namespace delmesh::detail {

//! A point of [a.inf(), a.sup()] near its centre (exact for finite bounds: the sum is rounded,
//! then clamped back into the interval).
inline double midpoint(const Interval& a) {
  const double m = 0.5 * a.inf() + 0.5 * a.sup();
  return std::min(std::max(m, a.inf()), a.sup());
}
//! sup − inf rounded upward (requires the guard) or to nearest (an estimate otherwise).
inline double width(const Interval& a) { return a.sup() - a.inf(); }

//! True iff both bounds are finite numbers.
inline bool is_finite(const Interval& a) { return std::isfinite(a.inf()) && std::isfinite(a.sup()); }

//! a ⊂ interior(b).
inline bool strictly_inside(const Interval& a, const Interval& b) {
  return a.inf() > b.inf() && a.sup() < b.sup();
}
//! a ⊂ b.
inline bool inside(const Interval& a, const Interval& b) { return a.inf() >= b.inf() && a.sup() <= b.sup(); }
//! a ∩ b = ∅ (false when a bound is NaN: no information).
inline bool disjoint(const Interval& a, const Interval& b) { return a.inf() > b.sup() || a.sup() < b.inf(); }
//! a ∩ b, precondition: !disjoint(a, b) and finite bounds.
inline Interval intersection(const Interval& a, const Interval& b) {
  return Interval(std::max(a.inf(), b.inf()), std::min(a.sup(), b.sup()));
}
//! [a.inf() − r, a.sup() + r] for r ≥ 0 (outward under the guard).
inline Interval inflate(const Interval& a, double r) { return Interval(-(r - a.inf()), a.sup() + r); }

//! An enclosure of ⟨normal, x⟩ − offset over the box x of n intervals (normal: n doubles), the
//! signed excess of a half-space ⟨normal, u⟩ ≤ offset: inf > 0 proves the box outside it,
//! sup < 0 strictly inside.
//! Computed bound by bound with the guard's upward rounding: the upper bound sums a_i·x_i.sup
//! (a_i ≥ 0) or a_i·x_i.inf (a_i < 0), rounded up; the lower bound is the negation of the same
//! upper sum for −⟨normal, x⟩ + offset.  A zero coefficient contributes nothing (not 0·∞, which
//! is NaN for an unbounded side; it adds 0, which changes no sum but the sign of a zero one).
//! The term is taken without a branch on the sign of a_i, which the many half-spaces of a Voronoi
//! cell make hard to predict: a_i·x_i.sup and a_i·x_i.inf are both rounded up and rounding is
//! monotone, so the larger of the two is the term that sign picks (likewise for the negation).
inline Interval half_space_excess(const double* normal, double offset, const Interval* x, std::size_t n) {
  double upper = -offset, negated_lower = offset;
  for (std::size_t i = 0; i < n; ++i) {
    const double a = normal[i], lo = x[i].inf(), hi = x[i].sup();
    const double up = std::max(a * hi, a * lo), down = std::max((-a) * lo, (-a) * hi);
    upper += a != 0 ? up : 0.0;
    negated_lower += a != 0 ? down : 0.0;
  }
  return Interval(-negated_lower, upper);
}

//! The widest side of a box of n intervals, and its index.
inline std::size_t widest_side(const Interval* box, std::size_t n, double* w = nullptr) {
  std::size_t best = 0;
  double wb = -1;
  for (std::size_t i = 0; i < n; ++i) {
    const double wi = width(box[i]);
    if (wi > wb) wb = wi, best = i;
  }
  if (w) *w = wb;
  return best;
}

//! The MPFI default precision (Boost's default_precision(), a process-wide setting that the
//! compiled programs use for their temporaries) set to `bits` for the lifetime of the scope.
//!
//! Thread safety.  Boost 1.74 keeps that default in one process-wide variable (there is no
//! thread-local default), so the scope also holds a process-wide std::recursive_mutex from
//! construction to destruction: while a scope is alive on one thread, a scope on any other thread
//! waits, and the precision it reads is the one its own scope set.  Scopes nest on one thread (the
//! inner one sets, then restores, the precision; the mutex is recursive).  Consequences:
//!  - every MpfiInterval / MpfrReal that is created, or computed into (CompiledSystem evaluation
//!    over MPFI included), must be created and used inside a scope, and destroyed before the
//!    scope ends or after it (destruction reads no precision); code outside any scope must not
//!    touch them, since another thread may be changing the default precision;
//!  - MPFI work of concurrent solves is serialized (escalations are rare, so this costs little);
//!  - code inside a scope must not wait for another thread that may itself open a scope.
class MpfiPrecisionScope {
 public:
  explicit MpfiPrecisionScope(int bits);
  ~MpfiPrecisionScope();
  MpfiPrecisionScope(const MpfiPrecisionScope&) = delete;
  MpfiPrecisionScope& operator=(const MpfiPrecisionScope&) = delete;

 private:
  std::unique_lock<std::recursive_mutex> lock_;  // first member: taken before the precision is read
  unsigned old_interval_digits_, old_real_digits_;
};

//! The MPFI interval [lo, hi] (exact: doubles are representable at every precision ≥ 53 bits).
MpfiInterval to_mpfi(const Interval& a);
MpfiInterval to_mpfi(double lo, double hi);
//! The smallest double interval containing a (bounds rounded outward).
Interval to_interval(const MpfiInterval& a);

}  // namespace delmesh::detail
