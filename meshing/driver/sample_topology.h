#pragma once
//! \file sample_topology.h
//! SampleTopology(Σ) (§5.4): seeds S₀ = SurfaceCritical(Σ) in a generic height direction;
//! Topology(S₀) (the refinement driver with Quality and Smooth off); then delete the seeds one at
//! a time, re-running Topology after each deletion (Lemma 5.4, Corollary 5.2).
//!
//! Choices: the height direction is a seeded pseudo-random unit vector (the paper's x3 is not
//! generic for e.g. a torus with axis x3, whose critical points form circles).  If the solver
//! reports non_isolated, another seeded direction is tried, at most
//! tolerances::mesher_height_direction_retries times, then InvalidInput.  Regions the seed solve's
//! box budget left unexplored are solved again, each with a budget of its own, in rounds while a
//! round certifies a root, within tolerances::seed_solve_budget_factor budgets in all.  Undecided regions of the seed solve are
//! projected onto Σ and inserted as seeds too (they are deleted again in step 3).
//! Seeds are deleted in increasing id order.

#include <cstdint>

#include "meshing/driver/refinement.h"
#include "meshing/inputs/seed_solve.h"

namespace delmesh {

struct SeedReport {
  Vec3 height_direction{};
  std::size_t seeds = 0;        //!< seeds inserted
  std::size_t undecided = 0;    //!< undecided regions of the seed solve
  int attempts = 0;             //!< height directions tried
  bool time_limited = false;    //!< the run's deadline stopped the seed solve: no seed inserted
};

//! Step 1: inserts the seeds into S.  Throws InvalidInput if Σ is empty in the box (the seed
//! solve found no critical point and left no undecided region) or no generic height direction
//! is found.  An undecided region that cannot be projected onto Σ is reported unsettled
//! (CheckKind::seed, unprojectable_region) and inserts nothing; if every region is such, no seed
//! is inserted and the run ends uncertified, never "empty".  If the run's deadline
//! (SurfaceOracle::set_run_controls) stops the seed solve, inserts nothing and says so.
SeedReport insert_seeds(Refinement& refinement);

//! What sample_topology() did: its seeds, and the status of its last Topology run (a limit stops
//! it early; time_limit also when the deadline stopped the seed solve).
struct SampleTopologyResult {
  SeedReport seeds;
  MeshStatus status = MeshStatus::complete;
};

//! Steps 1–3.
[[nodiscard]] SampleTopologyResult sample_topology(Refinement& refinement);

}  // namespace delmesh
