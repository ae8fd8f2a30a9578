#pragma once
//! \file univariate_isolator.h
//! Certified isolation of the zeros of E on a segment p + t v, t ∈ [t0, t1] (SurfaceLine, VorEdge).
//! Polynomial E: coefficients in t enclosed rigorously (LinePolynomial over Interval), then
//! Bernstein/Descartes isolation; non-polynomial E: interval Newton on t.  A double root (the line
//! tangent to Σ, Lemma 4.7(ii)) is reported as an undecided box with reason singular_root.

#include <array>
#include <optional>

#include "solvers/solve_result.h"
#include "symbolic/compiled_system.h"
#include "symbolic/line_polynomial.h"

namespace delmesh {

struct UnivariateOptions {
  std::size_t box_budget = 100000;
};

//! Roots of E(p + t v) on [t0, t1] (t0 < t1).  `line` is the compiled surface_line system;
//! `polynomial` may be null (then interval Newton is used).  Certified roots carry t as
//! midpoint[0] and the world point.  A root within the isolator's resolution of t0 or t1 is
//! reported as undecided with reason boundary_root.
SolveResult isolate_line_roots(const CompiledSystem& line, const LinePolynomial* polynomial,
                               const std::array<double, 3>& p, const std::array<double, 3>& v,
                               double t0, double t1, const UnivariateOptions& options = {});

}  // namespace delmesh
