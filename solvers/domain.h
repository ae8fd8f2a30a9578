#pragma once
//! \file domain.h
//! Solver domains: an axis-aligned box in the unknowns intersected with half-spaces, i.e. a convex
//! polytope (a Voronoi facet polygon in plane coordinates (u, v); a clipped Voronoi cell in x, y, z).

#include <vector>

#include "solvers/solve_result.h"

namespace delmesh {

//! {u : ⟨normal, u⟩ ≤ offset} in the solver's unknowns.
struct HalfSpace {
  std::vector<double> normal;
  double offset = 0;
};

//! box ∩ ⋂ half_spaces.  Roots are searched in the (slightly enlarged) box and then classified
//! as inside or outside the polytope; classification is decided exactly or the box is refined.
struct Domain {
  SolverBox box;
  std::vector<HalfSpace> half_spaces;
  std::size_t dimension() const { return box.bounds.size(); }
  //! The box [lo0,hi0]×…; no half-spaces.
  static Domain from_box(std::vector<std::array<double, 2>> bounds);
};

}  // namespace delmesh
