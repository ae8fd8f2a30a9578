#pragma once
//! \file dense_sample.h
//! A dense, seeded, reproducible reference sample of Σ = {E = 0} inside a box, fine relative to a
//! local feature size: the reference against which ε-samples are built
//! (experiments/sampling/eps_sample.h) and on which lfs is estimated
//! (experiments/sampling/lfs_estimate.h).  Not part of the mesher.
//!
//! Construction (octree with an interval exclusion test and Newton projection):
//!   1. The box is cut into a grid of cells of edge at most max_spacing (relative to the diagonal).
//!   2. A cell whose interval enclosure of E excludes 0 misses Σ and is dropped.
//!   3. A cell is split into eight while its longest edge s exceeds relative_spacing · ℓ and
//!      min_spacing (relative to the diagonal), where ℓ is a lower bound of lfs on the cell: the
//!      centre c is projected onto Σ (Newton steps along ∇E) at p, and ℓ = lfs(p) − |p − c| − s√3/2
//!      (lfs is 1-Lipschitz); ℓ = 0 when the projection fails.  Without an lfs the cells stop at
//!      max_spacing (a uniform sample).
//!   4. Each remaining cell contributes at most one point: the Newton projection onto Σ of a
//!      seeded random point of the cell, or else of its centre, kept if it lies in the cell
//!      (half-open, so no point is found twice).
//! The points lie on Σ up to the projection tolerance of tolerances.h, about one per cell of edge
//! ≤ relative_spacing · lfs; the order and the coordinates depend only on (E, box, options, lfs).

#include <array>
#include <cstdint>
#include <functional>
#include <ostream>
#include <vector>

#include "common/enum_names.h"
#include "symbolic/surface.h"

namespace delmesh {

struct DenseSampleOptions {
  std::uint64_t seed = 1;         //!< seeds the point drawn in each cell
  double max_spacing = 1.0 / 256; //!< coarsest cell edge, as a fraction of the box diagonal
  double relative_spacing = 0.04; //!< cell edge ≤ relative_spacing · lfs (when an lfs is given)
  double min_spacing = 1e-4;      //!< finest cell edge, as a fraction of the box diagonal
  std::size_t max_points = 4000000; //!< the construction stops (status point_limit) beyond this
};

enum class DenseSampleStatus { complete, point_limit };
constexpr auto enum_names(DenseSampleStatus) {
  return name_table<DenseSampleStatus>("DenseSampleStatus", {{DenseSampleStatus::complete, "complete"},
                                                             {DenseSampleStatus::point_limit, "point_limit"}});
}
inline std::ostream& operator<<(std::ostream& out, DenseSampleStatus status) { return write_enum(out, status); }

struct [[nodiscard]] DenseSample {
  DenseSampleStatus status = DenseSampleStatus::complete;
  std::vector<std::array<double, 3>> points; //!< on Σ, in a deterministic order
  std::size_t cells = 0;        //!< leaf cells that may meet Σ (by the interval test)
  std::size_t finest_cells = 0; //!< leaf cells stopped by min_spacing, not by the lfs criterion
};

//! lfs(p) for p ∈ Σ (the value elsewhere is not used).
using LfsFunction = std::function<double(const std::array<double, 3>&)>;

//! The reference sample of Σ ∩ box described in the file comment; an empty lfs gives the uniform
//! sample at max_spacing.  Preconditions: box non-empty; 0 < min_spacing ≤ max_spacing ≤ 1;
//! relative_spacing > 0 (else PreconditionViolation).  The sample may miss a part of Σ smaller
//! than a cell that no Newton projection reaches; the interval test never drops a cell Σ meets.
DenseSample dense_sample(const Surface& surface, const Box3& box, const DenseSampleOptions& options,
                         const LfsFunction& lfs = {});

}  // namespace delmesh
