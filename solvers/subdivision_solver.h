#pragma once
//! \file subdivision_solver.h
//! Certified subdivision solver for n = 2 or 3 unknowns over a convex polytope (Domain):
//! interval exclusion (natural and mean-value forms), exclusion of boxes outside the polytope,
//! Krawczyk contraction and uniqueness, bisection, de-duplication through uniqueness boxes,
//! inside/outside classification of each root, escalation to MPFI for boxes double intervals
//! cannot decide.  See solve_result.h for what "certified" means.

#include <ostream>
#include <vector>

#include "common/enum_names.h"
#include "common/tolerances.h"
#include "solvers/domain.h"
#include "solvers/solve_result.h"
#include "symbolic/compiled_system.h"

namespace delmesh {

//! When the subdivision solver works on Taylor forms of a polynomial system (see solve_subdivision).
enum class TaylorForms {
  automatic,  //!< when the system has a PolynomialForm, its compiled values+Jacobian program has
              //!< at least tolerances::taylor_form_instruction_ratio instructions per Taylor
              //!< coefficient (dense expanded polynomials; factored forms are cheaper as written),
              //!< and the coefficient program (run once per solve) is no longer than it
  always,     //!< whenever the system has a PolynomialForm
  never       //!< only the compiled expressions
};

constexpr auto enum_names(TaylorForms) {
  return name_table<TaylorForms>("TaylorForms", {{TaylorForms::automatic, "automatic"},
                                                 {TaylorForms::always, "always"}, {TaylorForms::never, "never"}});
}
inline std::ostream& operator<<(std::ostream& out, TaylorForms choice) { return write_enum(out, choice); }

struct SubdivisionOptions {
  std::size_t box_budget = tolerances::default_box_budget;  //!< boxes visited before status box_limit
  double time_limit_seconds = 0;  //!< 0: none
  //! Over-determined systems (m > n, SurfacePlaneContact): prove that there is no solution, or
  //! return as undecided the boxes that could not be excluded.  Never certifies roots.
  bool exclusion_mode = false;
  TaylorForms taylor_forms = TaylorForms::automatic;
  //! The singular width relative to the domain's scale (Domain::scale); 0: the tolerance of the
  //! mode (singular_box_relative_width, or exclusion_singular_box_relative_width).
  double singular_relative_width = 0;
};

//! Solves f(u; parameters) = 0 for u in the polytope `domain` (box ∩ half-spaces), certified in
//! the sense of solve_result.h.  Per box of a depth-first work list: exclusion by the half-spaces
//! (box certainly outside one), by the natural interval form of f, and by the mean-value form
//! f(m) + J(X')(X − m); then (square systems) one Krawczyk step on the ε-inflated box X' (no
//! zero → excluded; K ⊂ int X' → a unique zero, refined by Krawczyk iteration, de-duplicated
//! against the zeros already found through their uniqueness boxes, and classified against every
//! face: inside → returned, outside → counted in roots_outside, undecidable → undecided
//! boundary_root); a strongly contracting step is repeated, otherwise the widest side is
//! bisected.  A box narrower than tolerances::singular_box_relative_width whose interval
//! Jacobian determinant contains 0 (or narrower than min_box_relative_width) is re-examined in
//! MPFI at tolerances::escalation_precisions, then returned undecided (singular_root, or
//! precision).  More than tolerances::non_isolated_box_count such boxes → status non_isolated
//! (a curve of solutions) and the rest of the work list is returned undecided at once.  Budgets
//! return the unexplored boxes undecided (budget).  Roots and undecided boxes carry world
//! points via system.world_point ((0, 0, 0) if the system has none).
//! Exclusion mode (m > n): only the exclusion tests; the boxes that cannot be excluded down to
//! the singular width come back undecided (singular_root if every equation's enclosure still
//! contains 0, else precision); status complete means "no solution in the domain" is proved.
//! Precondition: system.n_unknowns() == domain.dimension() ∈ {2, 3};
//! parameters.size() == system.n_parameters() (finite); m == n unless exclusion_mode (then
//! n ≤ m ≤ 6); domain valid (Domain::validate).  Violations throw PreconditionViolation.
//! Creates its own RoundingGuard; its MPFI work runs inside detail::MpfiPrecisionScope (the
//! process-wide MPFI precision lock), so concurrent solves from several threads are safe and
//! their escalations serialized.
SolveResult solve_subdivision(const CompiledSystem& system, const std::vector<double>& parameters,
                              const Domain& domain, const SubdivisionOptions& options = {});

//! A second look at the singular regions of a square solve.  A region left undecided as
//! singular_root at singular_box_relative_width may hold a singular root, or only a place where
//! the system is small without a zero (two sheets of Σ closer than the width, where every
//! equation's enclosure keeps 0 until the boxes separate the sheets); enough of those make the
//! solve stop as non_isolated.  So for `result`, a solve_subdivision() of `system` over `domain`
//! with status undecided or non_isolated, each region of reason singular_root or non_isolated is
//! solved again on its own: the domain's half-spaces over the region's box, bisected down to
//! tolerances::refined_singular_box_relative_width of the domain's scale, within
//! tolerances::singular_refinement_box_budget boxes.  If that solve ends complete, the region is
//! replaced by the roots it certified (a root whose box and the box of a root already in
//! `result` nest is that root, since each box holds exactly one, and is not added again; a root
//! on the region's edge may otherwise be listed twice, never lost); otherwise the region stays as
//! it was, and so do all the regions after it (a true singular root or a curve of solutions,
//! whose other regions would each cost the budget and stay undecided too).  Nothing is dropped
//! that is not proved: an excluded box has no zero, and the new roots are Krawczyk-certified.
//! The status becomes complete when no region is left.  Other statuses (limits) and exclusion
//! mode are left untouched; the solves share what is left of options.time_limit_seconds (a
//! region not reached in time stays), and a region whose box has a side that is not a proper
//! interval stays.  The work is added to result.counters.  Same preconditions as
//! solve_subdivision().
void refine_singular_regions(const CompiledSystem& system, const std::vector<double>& parameters,
                             const Domain& domain, SolveResult& result, SubdivisionOptions options = {});

}  // namespace delmesh
