#pragma once
//! \file eps_sample.h
//! ε-samples of Σ by greedy farthest-point selection from a dense reference sample R, relative to
//! a local feature size given at the points of R.  The size of an ε-sample is the yardstick of
//! Theorem 6.1(iii): an ε-sample of Σ has Θ(∫_Σ dA / (ε lfs)²) points, and the theorem bounds the
//! mesh's |S| by O(that) for ε ~ λ.
//!
//! Selection: start from R's first point; repeatedly choose the point x of R with the largest
//! ratio ρ(x) = d(x, C) / lfs(x) to the chosen set C, until max ρ ≤ ε.  The selection order does
//! not depend on ε, so one run yields the ε-samples for every ε (prefixes of one order).
//! Properties of the prefix C_ε chosen for ε:
//!   - covering: every x ∈ R has d(x, C_ε) ≤ ε · lfs(x) (an ε-sample of R, hence an
//!     (ε + δ)-sample of Σ if R is a δ-sample of Σ);
//!   - separation: each c ∈ C_ε had ρ(c) > ε when chosen, so d(c, c') > ε · lfs(c) for every
//!     point c' chosen before c.
//! Implementation: C is kept in a Delaunay triangulation (CGAL, exact predicates); every x ∈ R is
//! assigned to its nearest chosen point; inserting c can only take points from the cells of c's
//! Delaunay neighbours, so only those are rescanned.  A heap over chosen points, keyed by the
//! largest ρ among their assigned points, gives the next choice.

#include <array>
#include <vector>

namespace delmesh {

struct [[nodiscard]] EpsSampleResult {
  std::vector<double> epsilons;     //!< as given, in decreasing order
  std::vector<std::size_t> order;   //!< indices into R, in selection order
  std::vector<std::size_t> sizes;   //!< sizes[k] = |C_ε| for ε = epsilons[k]: the prefix order[0..sizes[k])
  std::vector<double> covering;     //!< covering[k] = max_{x ∈ R} d(x, C_ε) / lfs(x) ≤ epsilons[k]
};

//! The ε-samples of the reference R = points for each ε in epsilons (see the file comment).
//! Preconditions: points non-empty; lfs.size() == points.size(), every lfs value finite and > 0;
//! epsilons non-empty, each > 0 (else PreconditionViolation).  Deterministic: the result depends
//! only on the inputs (ties go to the lower index).
EpsSampleResult eps_sample(const std::vector<std::array<double, 3>>& points, const std::vector<double>& lfs,
                           std::vector<double> epsilons);

}  // namespace delmesh
