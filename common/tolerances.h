#pragma once
//! \file tolerances.h
//! Every numerical tolerance of delmesh lives here; there are no magic epsilons elsewhere.
//! Certified answers never depend on these values for their correctness, only for how much work
//! is done before a region is reported as undecided.

#include <cstddef>

namespace delmesh::tolerances {

//! A box whose widest side is below this (relative to the domain's widest side) is not bisected
//! further by the subdivision solvers; it is reported undecided unless it was certified.
inline constexpr double min_box_relative_width = 1e-12;

//! Default maximum number of boxes one subdivision solve may visit before it stops with
//! status box_limit (the remaining boxes are returned as undecided).
inline constexpr std::size_t default_box_budget = 200000;

//! MPFI precisions (bits) tried, in order, when double intervals cannot decide a box.
inline constexpr int escalation_precisions[] = {106, 212};

//! Certified roots whose midpoints are closer than this (absolute, world units) are the same
//! root found twice; used only after uniqueness boxes have been compared.
inline constexpr double duplicate_root_distance = 1e-10;

//! Homotopy continuation: smallest step in the path parameter before a path is declared failed.
inline constexpr double homotopy_min_step = 1e-14;

//! Homotopy continuation: a solution whose largest imaginary part is below this is a candidate
//! real root (it is then certified by Krawczyk over the reals, so this only filters candidates).
inline constexpr double homotopy_real_candidate = 1e-6;

//! Relative perturbation used to make a user-given direction generic when the solver reports
//! non-isolated solutions for it.
inline constexpr double generic_direction_perturbation = 1e-3;

}  // namespace delmesh::tolerances
