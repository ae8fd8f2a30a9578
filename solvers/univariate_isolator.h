#pragma once
//! \file univariate_isolator.h
//! Certified isolation of the zeros of E on a segment p + t v, t ∈ [t0, t1] (SurfaceLine, VorEdge).
//! Polynomial E: coefficients in t enclosed rigorously (LinePolynomial over Interval), then
//! Bernstein/Descartes isolation; non-polynomial E: interval Newton on t.  What rounding keeps
//! double intervals from deciding is re-examined in MPFI (tolerances::escalation_precisions).  A
//! double root (the line tangent to Σ, Lemma 4.7(ii)) is reported as an undecided box with reason
//! singular_root.

#include <array>
#include <chrono>
#include <optional>

#include "common/tolerances.h"
#include "solvers/solve_result.h"
#include "symbolic/compiled_system.h"
#include "symbolic/line_polynomial.h"

namespace delmesh {

struct UnivariateOptions {
  //! Subintervals visited before the isolation stops with status box_limit.
  std::size_t box_budget = tolerances::default_univariate_box_budget;
  //! Wall-clock budget in seconds (0: none), from the call's start: once it has passed (checked
  //! every few subintervals), the isolation stops with status time_limit and returns every
  //! unexplored interval, and every interval whose MPFI escalation had not been done, undecided
  //! with reason budget.
  double time_limit_seconds = 0;
  //! The call's start, when the caller has just read the clock: the time limit and
  //! counters.seconds count from it.  Without it the clock is read at the call.
  std::optional<std::chrono::steady_clock::time_point> start;
};

//! The zeros of E(p + t v) for t in the closed interval [t0, t1], certified in the sense of
//! solve_result.h: every zero lies in a returned certified interval (box.bounds[0], with t as
//! midpoint[0] and the world point p + t v) or in an undecided interval; each certified interval
//! contains exactly one zero, proved by
//!  - (polynomial E) the interval Bernstein coefficients of E(p + t v) on a subinterval, all of
//!    certain sign with exactly one sign variation (Descartes' rule for the Bernstein basis), or
//!    a derivative whose Bernstein coefficients have one certain sign with certain opposite end
//!    values; coefficients are enclosed by evaluating `polynomial` over Interval and shifting to
//!    [t0, t1] in interval arithmetic.  The whole of [t0, t1] is first tried on the monomial
//!    coefficients themselves (Horner enclosures): no zero when E or its mean-value form over
//!    [t0, t1] excludes 0, and when E′ excludes 0 there, none or exactly one by the certain signs
//!    of E(t0) and E(t1); the Bernstein form is computed only when these do not decide;
//!  - (any E, polynomial == null or degree > 60) interval Newton on the compiled `line` system:
//!    a derivative enclosure excluding 0 with certain opposite signs at the ends;
//! and then narrowed to a tight interval around the Newton-refined zero, re-certified by a sign
//! change and a derivative excluding 0 inside the isolating interval.  Subdivision avoids split
//! points where the value is not certainly nonzero.
//! Rounding-limited subintervals (tolerances::univariate_precision_limited_ratio): a Bernstein
//! node whose coefficient enclosures are nearly as wide as the coefficients (the expanded
//! coefficients cancel) is isolated by interval Newton on the compiled `line` system instead.
//! MPFI escalation (tolerances::escalation_precisions, 106 then 212 bits) of what rounding, not
//! the geometry, leaves undecided:
//!  - an interval Newton subinterval on which E at the midpoint is nearly as uncertain as the
//!    mean-value enclosure over it is escalated when it is met;
//!  - once the double pass is over, every interval left undecided with reason precision or
//!    boundary_root (adjacent ones merged) is escalated.
//! In MPFI, E(p + t v) and dE/dt are evaluated by the compiled `line` system (the exact
//! expression at p, v, not the double coefficient enclosures), and the interval is subdivided
//! depth first: exclusion by the natural or mean-value enclosure, or by E' ≠ 0 with equal certain
//! end signs; certification by an MPFI enclosure of E' excluding 0 with opposite certain end
//! signs, narrowed by bisection on certain MPFI signs.  The interval is replaced by its certified
//! zeros only if every piece of it is decided (tolerances::univariate_escalation_*; a piece on
//! which E' may vanish, narrower than the singular width, is not split: that is the singular_root
//! rule); otherwise it stays undecided with its reason (a rounding-limited subinterval is then
//! subdivided in double as before, without a second escalation).  Each (interval, precision)
//! attempt counts one counters.precision_escalations.  Certified intervals that meet and on which
//! E' ≠ 0 is proved hold the same zero and are reported once.  Undecided reasons:
//!  - singular_root: E and E' cannot be excluded from 0 on an interval narrower than
//!    tolerances::singular_box_relative_width·(t1 − t0): a double root (the line tangent to Σ,
//!    Lemma 4.7(ii)), a near-tangency (two zeros closer than that, or a line missing Σ by less
//!    than rounding) — never certified, never dropped, not escalated (a double root cannot be
//!    certified at any precision: every interval containing it has E' ∋ 0; the mesher treats
//!    such regions as candidate witnesses);
//!  - boundary_root: a zero at t0 or t1 within the resolution (the end value's enclosure
//!    contains 0 on the last subinterval, in double and in MPFI);
//!  - precision: monotone but undecidable at min_box_relative_width, in double and in MPFI;
//!  - non_isolated: more than tolerances::non_isolated_box_count undecided intervals (E ≡ 0 along
//!    the line, the line lies in Σ); the remaining intervals are returned at once;
//!  - budget: options.box_budget subintervals visited (status box_limit), or
//!    options.time_limit_seconds passed (status time_limit).
//! Adjacent undecided intervals with the same reason are merged.  Certified roots are sorted by t.
//! Preconditions (else PreconditionViolation): `line` is a surface_line system (1 unknown,
//! 1 equation, 6 parameters p, v); t0 < t1 finite; p, v finite, v ≠ 0; `polynomial`, when
//! given, is the LinePolynomial of the same surface; options.time_limit_seconds finite and ≥ 0.
//! Creates its own RoundingGuard; its MPFI work runs inside detail::MpfiPrecisionScope, which holds the
//! process-wide MPFI precision lock, so concurrent calls from several threads are safe (their
//! escalations are serialized).
SolveResult isolate_line_roots(const CompiledSystem& line, const LinePolynomial* polynomial,
                               const std::array<double, 3>& p, const std::array<double, 3>& v,
                               double t0, double t1, const UnivariateOptions& options = {});

}  // namespace delmesh
