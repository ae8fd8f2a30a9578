#pragma once
//! \file surface_box.h
//! A box that holds the part of a surface inside a larger box, proved by interval arithmetic:
//!
//!     given Σ = {E = 0} and a box B, find B′ ⊆ B with Σ ∩ B ⊆ B′.
//!
//! Every face of the mesher's Voronoi diagram is clipped to a box (voronoi_geometry.h) and every
//! check of it is about Σ only, so the box B′ does as well as B and is often much smaller: the
//! cells of samples on the convex hull are unbounded and reach the faces of B, where they flare
//! out far from Σ, and each certificate or solve over them pays for the volume (on the catalog
//! genus-2 surface, whose z stays within ±0.1415, B′ is about [−1.10, 1.14] × [−0.65, 0.68] ×
//! [−0.15, 0.15] inside B = [−1.3, 1.3] × [−0.9, 0.9] × [−0.4, 0.4]).
//!
//! Method: the bound of each of the six sides is found by its own best-first search.  For the
//! upper bound along axis k, a max-heap holds boxes keyed by their upper end in x_k; it starts
//! with B.  The top box X is taken out and dropped when an enclosure of E on it excludes 0 — the
//! natural form E(X), or the mean-value form E(c) + Σ_j ∂_jE(X)(X_j − c_j) with c the centre of
//! X — and otherwise bisected across its widest side, both halves going back.  The search stops
//! when the heap is empty, when the top box is narrower along x_k than `resolution` times B's
//! side k, or after `evaluations_per_side` boxes; the bound is then the top box's key (B's upper
//! end if the heap never shrank below B; nothing if the heap is empty).
//!
//! Proof.  At every step the boxes in the heap cover Σ ∩ B: B does at the start; a box is dropped
//! only when an enclosure of E on it (a rigorous interval enclosure, computed under a
//! RoundingGuard) excludes 0, so it holds no point of Σ; a bisected box is the union of its two
//! halves.  Every point x of Σ ∩ B therefore lies in some box of the heap, whose key (its upper end
//! along k) is at most the top's: x_k ≤ the bound.  An empty heap proves Σ ∩ B = ∅.  The lower
//! bounds are the same search with the keys negated.  The budget and the resolution only decide
//! when to stop, not whether the bound holds.

#include <cstddef>

#include "common/tolerances.h"
#include "symbolic/compiled_system.h"
#include "symbolic/surface.h"

namespace delmesh {

struct SurfaceBoxOptions {
  //! A side's search stops when the top box is narrower than this fraction of B's side.
  double resolution = tolerances::surface_box_resolution;
  //! A side's search stops after this many boxes (its bound then is the top box's key).
  std::size_t evaluations_per_side = tolerances::surface_box_evaluations_per_side;
};

struct SurfaceBox {
  //! Σ ∩ B = ∅ was proved; `box` is then B.
  bool empty = false;
  //! B′ ⊆ B with Σ ∩ B ⊆ B′ (the side bounds of the file comment).
  Box3 box;
  //! Interval evaluations of E in all (each box costs one natural and, if needed, one mean-value
  //! enclosure).
  std::size_t evaluations = 0;
};

//! The box of the file comment.  `E` has one equation in the unknowns (x, y, z), no parameters,
//! and its Jacobian ∇E.  Throws PreconditionViolation if E is not of that shape, or if
//! options.resolution is not in (0, 1] or options.evaluations_per_side is 0.
SurfaceBox surface_bounding_box(const CompiledSystem& E, const Box3& box, const SurfaceBoxOptions& options = {});

}  // namespace delmesh
