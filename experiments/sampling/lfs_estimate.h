#pragma once
//! \file lfs_estimate.h
//! The local feature size of Σ estimated from a dense sample by the poles of its Voronoi diagram
//! (N. Amenta, M. Bern, "Surface reconstruction by Voronoi filtering", Discrete Comput. Geom. 22
//! (1999) 481–504; the poles approximate the medial axis: N. Amenta, S. Choi, R. K. Kolluri, "The
//! power crust, unions of balls, and the medial axis transform", Comput. Geom. 19 (2001) 127–153).
//!
//! For a sample P of Σ, the positive pole p⁺ of p ∈ P is the vertex of the Voronoi cell Vor(p)
//! farthest from p, and the negative pole p⁻ the vertex farthest from p among those v with
//! (v − p)·(p⁺ − p) < 0.  Vor(p) contains the centres of the medial balls touching Σ at p, so
//! |p − p^±| ≥ lfs(p); for an r-sample the poles lie within O(r) lfs of the medial axis M and the
//! poles of the points nearest to a point of M approach it.  The estimate is the distance to the
//! nearest pole, lfs̃(x) = min_{p ∈ P} min(|x − p⁺|, |x − p⁻|), which converges to lfs(x) =
//! d(x, M) on Σ as the sample densifies.  lfs̃ is 1-Lipschitz in x (a distance to a point set).
//! Voronoi cells are bounded by eight points far outside the box, whose own poles are not used.

#include <array>
#include <memory>
#include <vector>

#include "experiments/sampling/dense_sample.h"
#include "symbolic/surface.h"

namespace delmesh {

class PoleLfsEstimate {
 public:
  //! Builds Del(P ∪ far corners) (CGAL, exact predicates; circumcentres in double) and the poles.
  //! Preconditions: P has at least 4 points, all in box (else PreconditionViolation).
  PoleLfsEstimate(const std::vector<std::array<double, 3>>& sample, const Box3& box);
  ~PoleLfsEstimate();
  PoleLfsEstimate(PoleLfsEstimate&&) noexcept;
  PoleLfsEstimate& operator=(PoleLfsEstimate&&) noexcept;

  //! lfs̃(x): the distance from x to the nearest pole.  Thread-safe.
  double operator()(const std::array<double, 3>& x) const;
  //! The poles (two per sample point, fewer where a cell has no vertex on the negative side).
  const std::vector<std::array<double, 3>>& poles() const;
  //! The estimator's name as experiments report it ("voronoi_poles").
  static const char* name() { return "voronoi_poles"; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

struct LfsEstimateOptions {
  //! The refined sample of pass 2.  The default cells (edge ≤ 0.1 lfs̃₁) are coarser than an
  //! ε-sample's reference needs: the poles are accurate at that density (max relative error below
  //! 10 % on the catalog torus, tests/experiments/lfs_estimate_test.cpp).
  DenseSampleOptions sample = [] {
    DenseSampleOptions options;
    options.relative_spacing = 0.1;
    return options;
  }();
  double first_pass_spacing = 1.0 / 256; //!< uniform spacing of pass 1, fraction of the box diagonal
};

struct [[nodiscard]] LfsEstimateResult {
  DenseSample first_pass;   //!< the uniform sample of pass 1
  DenseSample sample;       //!< the reference sample of pass 2, refined for lfs̃₁
  std::unique_ptr<PoleLfsEstimate> estimate; //!< lfs̃₂, from the poles of `sample`
  std::vector<double> values;                //!< lfs̃₂ at the points of `sample`
};

//! lfs of Σ ∩ box by two passes: pass 1 samples Σ uniformly at first_pass_spacing and builds the
//! pole estimate lfs̃₁; pass 2 samples Σ adaptively (dense_sample with lfs̃₁, so cell edges ≤
//! relative_spacing · lfs̃₁) and builds lfs̃₂ from the poles of that sample.  Preconditions as
//! dense_sample; throws InvalidInput if a pass finds fewer than 4 points of Σ.
LfsEstimateResult estimate_lfs(const Surface& surface, const Box3& box, const LfsEstimateOptions& options);

//! Relative error |lfs̃ − lfs| / lfs of an estimate against an exact lfs over points of Σ.
struct LfsErrorSummary {
  double max = 0, median = 0, mean = 0;
  std::size_t points = 0;
};
//! Precondition: estimate.size() == exact.size() > 0, exact values > 0 (else PreconditionViolation).
LfsErrorSummary lfs_relative_error(const std::vector<double>& estimate, const std::vector<double>& exact);

}  // namespace delmesh
