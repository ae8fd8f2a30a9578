#pragma once
//! \file homotopy_certificate.h
//! A proof that the total-degree homotopy of solvers/homotopy_solver.h found every root of f in
//! the domain: a complex barrier box, the Bézout count at an intermediate t, and Krawczyk
//! certificates of the zeros, with no step of the path tracking taken on trust.
//!
//! Setting.  f: C^n → C^n polynomial with real coefficients, equation i of total degree d_i ≥ 1;
//! g_i(u) = u_i^{d_i} − 1; H_t = t γ g + (1 − t) f (|γ| = 1), so H_0 = f and equation i of every
//! H_t has degree ≤ d_i.  D = ∏ d_i.  The domain's bounding box R = ∏ [lo_i, hi_i] ⊂ R^n.
//!
//! Theorem.  Let C ⊂ C^n be the open box Re u_i ∈ (lo_i − μ, hi_i + μ), Im u_i ∈ (−μ, μ) (μ > 0,
//! so R ⊂ C) and 0 < t_e < 1.  Suppose
//!  (B) barrier: for every u ∈ ∂C there is an i with (1 − t_e) |f_i(u)| > t_e |g_i(u)|;
//!  (I) intermediate zeros: D pairwise disjoint boxes K_1 … K_D ⊂ C^n each hold exactly one zero
//!      of H_{t_e}, and each K_j lies either inside C or outside its closure; k of them lie inside;
//!  (Z) zeros of f: k pairwise disjoint boxes Z_1 … Z_k ⊂ C each hold exactly one zero of f,
//!      regular.
//! Then the zeros of f in C are exactly the k zeros of (Z); in particular every real root of f in
//! the domain is one of them.
//! Proof.  (B) gives H_t(u) ≠ 0 for u ∈ ∂C and every t ∈ [0, t_e]: |t γ g_i| = t |g_i| ≤ t_e |g_i|
//! < (1 − t_e)|f_i| ≤ (1 − t)|f_i|.  By Bézout's theorem in its refined form (Fulton,
//! "Intersection theory", Example 8.4.6: the degrees of the irreducible components of the zero set
//! in P^n of n homogeneous polynomials of degrees d_i sum to at most ∏ d_i), the D distinct zeros
//! of (I) are all the zeros of H_{t_e} in C^n, each an isolated component.  So H_{t_e} has exactly
//! k zeros in C, all regular (Krawczyk's K ⊂ int U gives a non-singular Jacobian), and its
//! Brouwer degree on C is k (at a regular zero of a holomorphic map the real Jacobian determinant
//! is |det J|² > 0, so its local degree is +1).  The degree is invariant along the homotopy t ∈ [0, t_e] since no H_t vanishes on ∂C, so
//! deg(f, C) = k.  The zeros of f in the closure of C form a compact analytic subset of C^n, hence
//! a finite set, none on ∂C; each has local degree equal to its multiplicity, ≥ 1.  The k regular
//! zeros of (Z) contribute k: there is no other.  ∎
//! Real roots.  A zero z of f alone in a box Z whose imaginary sides are symmetric about 0 is real:
//! f has real coefficients, so its conjugate is a zero in the same box, hence equal to z.  A zero
//! alone in a box one of whose imaginary sides excludes 0 is not real.
//!
//! Pieces.  The theorem applies to any box C: the domain's box R is covered by pieces R_j, each
//! with its own barrier box C_j ⊃ R_j, and the zeros of f in C_j are those of (Z) inside C_j.
//! Every real root of the domain lies in some R_j, so it is one of them.  (I) and the
//! certification of f's zeros are done once; k_j counts the boxes of (I) inside C_j.
//!
//! What is computed, and what is trusted.  Nothing is trusted.  The path tracker (uncertified,
//! detail/homotopy_tracker.h) only proposes points: H_{t_e}'s zeros (tracked from the start
//! solutions) and f's (the endgame's endpoints).  t_e = tolerances::homotopy_barrier_t.  The first
//! piece is R itself; a piece whose barrier box is not proved — (B) not proved within
//! homotopy_barrier_piece_budget face boxes, a box of (I) meeting ∂C_j, or fewer than k_j certified
//! zeros of f in C_j — is bisected along its widest side (breadth first), up to
//! homotopy_barrier_max_pieces pieces and homotopy_barrier_box_budget face boxes in all; the
//! pieces still unproved then are reported, and the caller returns them undecided.  μ_j is the first of
//! homotopy_barrier_margins (times the piece's widest side) whose ∂C_j keeps
//! homotopy_barrier_clearance · μ_j from every proposed zero of f (else the one with the largest
//! clearance).  (B) is proved by bisecting the 4n faces of ∂C_j (2n − 1 free real coordinates each,
//! depth first) until every face box U has an i with (1 − t_e) mig|f_i(U)| > t_e mag|g_i(U)|,
//! decided in interval arithmetic, with f(U) enclosed by rectangular complex interval arithmetic
//! (natural and mean-value forms, detail/complex_krawczyk.h).  (I) and (Z) are complex Krawczyk
//! tests on boxes around the proposed points.  Any part that fails leaves the certificate
//! unproved with its reason: the caller then reports its answer as undecided, never as complete.

#include <array>
#include <chrono>
#include <cstddef>
#include <functional>
#include <optional>
#include <ostream>
#include <vector>

#include "common/enum_names.h"
#include "solvers/domain.h"
#include "symbolic/compiled_system.h"
#include "symbolic/scalar_types.h"

namespace delmesh {

//! The outcome of certify_homotopy(): proved, or the first part that failed.
enum class HomotopyCertificateStatus {
  proved,
  barrier_not_proved,           //!< (B) not proved on a piece that could not be bisected further
  intermediate_path_failed,     //!< the tracker did not reach t_e on some path
  intermediate_not_certified,   //!< (I): a point at t_e not certified by Krawczyk
  intermediate_not_distinct,    //!< (I): two certified boxes at t_e meet (a path may have jumped)
  intermediate_straddles,       //!< (I): a box at t_e meets ∂C_j of a piece not bisected further
  zeros_not_certified,          //!< (Z): fewer than k_j distinct certified zeros of f in C_j
  real_not_decided,             //!< a zero of f in C neither proved real nor proved non-real
  out_of_time                   //!< the deadline passed
};
constexpr auto enum_names(HomotopyCertificateStatus) {
  using S = HomotopyCertificateStatus;
  return name_table<S>("HomotopyCertificateStatus",
                       {{S::proved, "proved"},
                        {S::barrier_not_proved, "barrier_not_proved"},
                        {S::intermediate_path_failed, "intermediate_path_failed"},
                        {S::intermediate_not_certified, "intermediate_not_certified"},
                        {S::intermediate_not_distinct, "intermediate_not_distinct"},
                        {S::intermediate_straddles, "intermediate_straddles"},
                        {S::zeros_not_certified, "zeros_not_certified"},
                        {S::real_not_decided, "real_not_decided"},
                        {S::out_of_time, "out_of_time"}});
}
inline std::ostream& operator<<(std::ostream& out, HomotopyCertificateStatus s) { return write_enum(out, s); }

//! One piece of the domain's box and the margin μ of its barrier box C (the file comment).
struct BarrierPiece {
  std::vector<std::array<double, 2>> box;
  double margin = 0;
};

//! What certify_homotopy() proved.
struct HomotopyCertificate {
  HomotopyCertificateStatus status = HomotopyCertificateStatus::barrier_not_proved;
  double t_barrier = 0;              //!< t_e
  //! The pieces proved (the theorem holds on each barrier box); with `unproved` they cover the
  //! domain's box.  status is proved iff `unproved` is empty, else the reason of its first piece.
  std::vector<BarrierPiece> pieces;
  //! Pieces of the domain's box not proved once the limits on pieces and face boxes were reached;
  //! the whole domain's box (and no piece proved) when a failure concerns the whole solve: a path
  //! not tracked to t_e or a point there not certified or not distinct, f's zeros not told apart,
  //! a zero neither proved real nor non-real, or the deadline.
  std::vector<std::vector<std::array<double, 2>>> unproved;
  std::size_t barrier_boxes = 0;     //!< face boxes evaluated for (B), over every piece tried
  std::size_t zeros_inside = 0;      //!< Σ k over the pieces proved (a zero in two counts twice)
  //! The real zeros of f in the barrier boxes of `pieces`, each a real box holding exactly one
  //! zero of f (the real part of its certified complex box); every real root of f in a proved
  //! piece is in one.
  std::vector<std::vector<Interval>> real_zeros;
  std::size_t nonreal_zeros = 0;  //!< zeros of f in C proved not real
};

//! The inputs certify_homotopy() needs from the solve.
struct HomotopyProblem {
  const CompiledSystem& f;                //!< square, polynomial, real parameters
  const std::vector<double>& parameters;
  const std::vector<int>& degrees;        //!< total degrees d_i ≥ 1 (equation_degrees())
  Complex gamma;                          //!< the homotopy's γ, |γ| = 1
  const Domain& domain;
};

//! Proves the theorem above for `problem` or says which part failed.
//!  - start_count: D, the number of paths; point_at(j, t) tracks path j (its start solution in
//!    total_degree_start_solutions() order) to t and returns its point, or nothing if that failed;
//!  - proposed_zeros: approximate zeros of f (the finite and singular endpoints of the paths);
//!  - deadline: checked between paths and between barrier boxes (out_of_time when passed).
//! Preconditions (PreconditionViolation): degrees.size() == f.n_unknowns() == f.n_equations() ==
//! domain.dimension(), start_count == ∏ d_i.
HomotopyCertificate certify_homotopy(
    const HomotopyProblem& problem, std::size_t start_count,
    const std::function<std::optional<std::vector<Complex>>(std::size_t, double)>& point_at,
    const std::vector<std::vector<Complex>>& proposed_zeros,
    std::optional<std::chrono::steady_clock::time_point> deadline = std::nullopt);

}  // namespace delmesh
