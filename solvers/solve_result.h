#pragma once
//! \file solve_result.h
//! The result of a certified solve.  "Certified" means:
//!  1. every root of the system in the (closed) domain lies in a returned certified box or in a
//!     returned undecided box; the certified boxes are pairwise distinct roots (de-duplicated
//!     through their uniqueness boxes), so no root is counted twice;
//!  2. every certified box provably contains exactly one root of the system, and that root is
//!     provably inside the domain (strictly inside every face: CertifiedRoot::inside_domain);
//!     the proof is Krawczyk's theorem (K(X) ⊂ int X, interval arithmetic under a
//!     RoundingGuard or MPFI) in n ≥ 2 unknowns, and in one unknown either a Bernstein
//!     coefficient sequence with exactly one sign variation, all signs certain, or an exact
//!     sign change at the ends of the interval with a derivative enclosure excluding 0;
//!  3. every region that could be neither excluded (interval evaluation proving no root) nor
//!     certified is returned as an UndecidedBox with the best reason: a tangency / double root
//!     (singular_root: the derivative, resp. the interval Jacobian determinant, cannot be
//!     excluded from 0 on a tiny box where the values cannot be excluded either), a root on or
//!     within rounding of the domain boundary (boundary_root), a curve of solutions
//!     (non_isolated), precision exhausted after MPFI escalation (precision), or a budget
//!     (budget).  Nothing is ever silently dropped: complete ⇔ no undecided box.
//! Certified roots that lie outside the polytope are not returned; they are counted in
//! SolverCounters::roots_outside.

#include <array>
#include <cstddef>
#include <ostream>
#include <vector>

#include "common/enum_names.h"

namespace delmesh {

//! Overall outcome of a solve.
enum class SolveStatus {
  complete,      //!< every root is in a certified box; no undecided region
  undecided,     //!< some regions could not be decided (see UndecidedBox::reason)
  non_isolated,  //!< evidence of a curve or surface of solutions (non-isolated roots)
  box_limit,     //!< the box budget ran out; unexplored boxes are returned as undecided
  time_limit     //!< the time budget ran out; unexplored boxes are returned as undecided
};
constexpr auto enum_names(SolveStatus) {
  return name_table<SolveStatus>("SolveStatus", {{SolveStatus::complete, "complete"},
                                                 {SolveStatus::undecided, "undecided"},
                                                 {SolveStatus::non_isolated, "non_isolated"},
                                                 {SolveStatus::box_limit, "box_limit"},
                                                 {SolveStatus::time_limit, "time_limit"}});
}
inline std::ostream& operator<<(std::ostream& out, SolveStatus status) { return write_enum(out, status); }

//! Why a region is undecided.
enum class UndecidedReason {
  singular_root,     //!< a multiple root / tangency: Jacobian singular near a zero
  boundary_root,     //!< a zero lies on (or too near) the boundary of the domain
  cluster,           //!< several roots closer than the minimal box width (homotopy: paths meeting
                     //!< at one ill-conditioned endpoint; the subdivision solvers cannot tell a
                     //!< cluster of simple roots closer than the singular width from a multiple
                     //!< root — every Jacobian over a box holding both is singular — and report
                     //!< either as singular_root)
  non_isolated,      //!< a curve of solutions passes through the region
  precision,         //!< even the highest MPFI precision could not decide
  budget             //!< not examined: a box or time budget ran out
};
constexpr auto enum_names(UndecidedReason) {
  return name_table<UndecidedReason>("UndecidedReason", {{UndecidedReason::singular_root, "singular_root"},
                                                         {UndecidedReason::boundary_root, "boundary_root"},
                                                         {UndecidedReason::cluster, "cluster"},
                                                         {UndecidedReason::non_isolated, "non_isolated"},
                                                         {UndecidedReason::precision, "precision"},
                                                         {UndecidedReason::budget, "budget"}});
}
inline std::ostream& operator<<(std::ostream& out, UndecidedReason reason) { return write_enum(out, reason); }

//! An axis-aligned box in the solver's unknowns (n ≤ 3 entries used).
struct SolverBox {
  std::vector<std::array<double, 2>> bounds;  //!< [lo, hi] per unknown
};

//! A certified root (item 2 above).
struct CertifiedRoot {
  SolverBox box;                    //!< contains exactly one root
  std::vector<double> midpoint;     //!< a point of the box (the refined estimate), unknowns
  std::array<double, 3> world{};    //!< the midpoint mapped to world coordinates
  bool inside_domain = true;        //!< classification against the polytope (always decided)
};

//! A region that could be neither excluded nor certified (item 3 above).
struct UndecidedBox {
  SolverBox box;                    //!< the region, in the solver's unknowns
  UndecidedReason reason = UndecidedReason::precision;
  std::array<double, 3> world{};    //!< world point of the box centre (a candidate witness)
};

//! Work counters of one solve (summed over solves with +=) for the statistics.
struct SolverCounters {
  std::size_t boxes = 0;                 //!< boxes visited
  std::size_t exclusions = 0;            //!< boxes excluded by interval evaluation
  std::size_t krawczyk_successes = 0;    //!< uniqueness proofs
  std::size_t precision_escalations = 0; //!< boxes re-examined with MPFI
  std::size_t paths = 0;                 //!< homotopy paths tracked
  std::size_t roots_outside = 0;         //!< certified roots found outside the polytope (not returned)
  double seconds = 0;
  SolverCounters& operator+=(const SolverCounters& other);
};

//! The certified answer of one solve: roots, undecided regions, status and counters.
struct [[nodiscard]] SolveResult {
  SolveStatus status = SolveStatus::complete;
  std::vector<CertifiedRoot> roots;      //!< only roots inside the domain
  std::vector<UndecidedBox> undecided;
  SolverCounters counters;
  bool is_complete() const { return status == SolveStatus::complete; }
};

}  // namespace delmesh
