#pragma once
//! \file solve_progress.h
//! Internal: the stop / undecided / status bookkeeping shared by the certified solvers
//! (subdivision_solver.cpp, univariate_isolator.cpp).  A solve stops early on its box budget, its
//! time budget, or when it has left more than tolerances::non_isolated_box_count regions
//! unresolved (the solution set is then taken to be non-isolated); what it had not explored comes
//! back undecided with the reason of the stop.

#include <cstddef>

#include "common/tolerances.h"
#include "solvers/solve_result.h"

namespace delmesh::detail {

class SolveProgress {
 public:
  //! Stops the solve with `status` (box_limit, time_limit or non_isolated); a later stop replaces it.
  void stop(SolveStatus status) {
    stopped_ = true;
    status_ = status;
  }
  bool stopped() const { return stopped_; }
  //! True if the solve stopped because too many regions were left unresolved.
  bool non_isolated() const { return stopped_ && status_ == SolveStatus::non_isolated; }

  //! Counts one region left unresolved (singular root, boundary root, precision); the one past
  //! tolerances::non_isolated_box_count stops the solve with non_isolated.
  void count_unresolved() {
    if (++unresolved_ > tolerances::non_isolated_box_count) stop(SolveStatus::non_isolated);
  }

  //! The reason of a region the solve did not explore: non_isolated after that stop, else budget.
  UndecidedReason unexplored_reason() const {
    return non_isolated() ? UndecidedReason::non_isolated : UndecidedReason::budget;
  }

  //! The solve's status: the stop's if it stopped, else undecided if some region is undecided,
  //! else complete.
  SolveStatus status(bool any_undecided) const {
    return stopped_ ? status_ : (any_undecided ? SolveStatus::undecided : SolveStatus::complete);
  }

 private:
  std::size_t unresolved_ = 0;
  bool stopped_ = false;
  SolveStatus status_ = SolveStatus::complete;
};

}  // namespace delmesh::detail
