#pragma once
// The part of a parametric line {x0 + t·d} inside a convex polytope, narrowed one half-space at
// a time.  Used for Voronoi edges (in space) and for FacetCycle's lines in a facet (in its plane).

#include <algorithm>
#include <cmath>

#include "common/tolerances.h"

namespace delmesh::detail {

//! The parameter interval [t0, t1] kept so far; `cut0`/`cut1` say whether an end came from a
//! half-space rather than from the starting interval.
struct LineClip {
  double t0, t1;
  bool cut0 = false, cut1 = false;
  bool emptied = false;  //!< a half-space parallel to the line excluded all of it

  LineClip(double start, double end) : t0(start), t1(end) {}

  //! Keeps {t : slope·t ≤ rhs}, the half-space {⟨n, x⟩ ≤ c} with slope = ⟨n, d⟩ and
  //! rhs = c − ⟨n, x0⟩; `scale` = |n|·|d|.  A half-space with
  //! |slope| ≤ tolerances::parallel_half_space_relative_slope·scale is parallel to the line: it
  //! keeps all of it (rhs ≥ 0) or nothing.
  void keep(double slope, double rhs, double scale) {
    if (std::abs(slope) <= tolerances::parallel_half_space_relative_slope * scale) {
      if (rhs < 0) emptied = true;
      return;
    }
    const double bound = rhs / slope;
    if (slope > 0) {
      if (bound < t1) {
        t1 = bound;
        cut1 = true;
      }
    } else if (bound > t0) {
      t0 = bound;
      cut0 = true;
    }
  }

  //! Whether the kept part has positive length.
  bool nonempty() const { return !emptied && t0 < t1; }
};

}  // namespace delmesh::detail
