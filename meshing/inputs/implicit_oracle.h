#pragma once
//! \file implicit_oracle.h
//! The surface oracle (meshing/core/surface_oracle.h) of an implicit surface Σ = {E = 0} inside a box
//! B: the systems of the primitives compiled once and solved by the certified solvers.  The
//! primitives are those of the registry
//! (solvers/primitive_registry.h), in its order: the six of §5.2 have a method each below, and
//! any primitive can be solved by name with solve().  The oracle has a solver backend (certified
//! subdivision, or homotopy for square polynomial systems), per-call budgets from tolerances.h,
//! the run's controls (seed and deadline, set_run_controls()), and statistics (calls, certified
//! roots, undecided regions, boxes, seconds, homotopy fallbacks and solves cut by the deadline per
//! primitive).
//!
//! Backend homotopy: the square systems of surface_critical, curve_critical, silhouette_plane and
//! silhouette_critical are solved by solve_homotopy() when E is polynomial; when E is not
//! polynomial (or a system's degrees cannot be computed) they are solved by subdivision instead,
//! and every such call counts one homotopy fallback of its primitive.  surface_plane_contact (an
//! over-determined system, exclusion mode) is always solved by subdivision, and counts one
//! fallback per call under this backend too.  surface_line always uses the univariate isolator
//! (certified, under either backend) and counts none.  A homotopy solve's pieces of the domain
//! that its certificate of completeness leaves unproved are answered by subdivision with the
//! call's box budget (HomotopyOptions::subdivision_budget_for_unproved; counted).
//!
//! The primitives and the certificate may be called from several threads at once: the compiled
//! systems keep their scratch per thread, and the statistics are updated under a lock.
//!
//! Policy for undecided regions (docs/certificates.md, What "certified" means): a region that the
//! solver can neither exclude nor certify is a candidate witness.  project() moves its centre onto
//! Σ by Newton steps along ∇E; the caller inserts the projected point if it lies in the Voronoi
//! face under test.  Inserting a false witness is harmless (§3, Lemma 5.1).  Undecided regions
//! are counted here (`undecided`) and never dropped silently.

#include <array>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "meshing/core/surface_oracle.h"
#include "solvers/domain.h"
#include "solvers/gradient_cone.h"
#include "solvers/solve_result.h"
#include "solvers/solver_backend.h"
#include "symbolic/surface.h"

namespace delmesh {

struct PrimitiveStatistics {
  std::size_t calls = 0, certified_roots = 0, undecided = 0, boxes = 0;
  //! Calls answered by subdivision although the backend is homotopy (see the file comment).
  std::size_t homotopy_fallbacks = 0;
  //! Calls whose solve the deadline stopped (status time_limit; the rest is undecided, budget).
  std::size_t time_limited = 0;
  //! Homotopy solves: paths tracked, near-real endpoints and diverging paths near the domain
  //! (solve_homotopy(), rules 2–4).
  std::size_t homotopy_paths = 0, homotopy_near_real = 0, homotopy_diverging_near_domain = 0;
  //! Homotopy solves whose certificate of completeness (solvers/homotopy_certificate.h) was not
  //! proved on every piece of the domain, and those proved; the unproved pieces, answered by the
  //! subdivision solver with the call's box budget.
  std::size_t homotopy_uncertified = 0, homotopy_certified = 0, homotopy_pieces_by_subdivision = 0;
  double seconds = 0;
};

class ImplicitOracle final : public SurfaceOracle {
 public:
  //! Compiles the system of every primitive of the registry for `surface`.  Precondition: box is
  //! non-empty; the registry holds the six primitives of §5.2 (else PreconditionViolation).
  ImplicitOracle(const Surface& surface, const Box3& box, SolverBackend backend);
  ~ImplicitOracle() override;
  ImplicitOracle(ImplicitOracle&&) noexcept;
  ImplicitOracle& operator=(ImplicitOracle&&) noexcept;

  //! The run's controls, for every later call: `seed` seeds each homotopy solve (γ and the
  //! projective patch; HomotopyOptions::seed), and `deadline`, if set, is an absolute end for every
  //! solve: each homotopy solve gets it as HomotopyOptions::deadline (read before every path step),
  //! each subdivision solve and univariate isolation the time left as time_limit_seconds (the least
  //! positive double once it has passed, so they stop at their first clock check).  A solve the
  //! deadline stops returns status time_limit with its unexplored region undecided (budget).
  //! Defaults until called: seed 1, no deadline.  Call before the primitives are used from
  //! several threads (the controls are read without a lock).
  void set_run_controls(std::uint64_t seed, std::optional<std::chrono::steady_clock::time_point> deadline) override;

  const Box3& box() const override { return box_; }
  //! surface_bounding_box() of E in B (solvers/surface_box.h), computed at construction, widened by
  //! tolerances::surface_box_relative_margin · diagonal() and met with B; B itself if the search
  //! proved Σ ∩ B empty.
  const Box3& clip_box() const override { return clip_box_; }
  const Surface& surface() const;

  //! SurfaceLine: zeros of E(p + t v) for t ∈ [t0, t1] (certified, or undecided regions:
  //! singular_root for a tangency, boundary_root for a zero at t0 or t1).
  SolveResult surface_line(const Vec3& p, const Vec3& v, double t0, double t1) override;
  //! SurfaceCritical in direction d over a 3-D domain.
  SolveResult surface_critical(const Vec3& d, const Domain& domain, std::size_t box_budget) override;
  //! SurfacePlaneContact over a facet polygon (exclusion mode: never certifies, undecided boxes
  //! are possible contacts).
  SolveResult surface_plane_contact(const Vec3& o, const Vec3& a, const Vec3& b, const Domain& domain) override;
  //! CurveCritical in direction a of Σ ∩ {o + u a + v b} over a facet polygon.
  SolveResult curve_critical(const Vec3& o, const Vec3& a, const Vec3& b, const Domain& domain) override;
  //! SilhouettePlane: J_d ∩ {o + u a + v b} over a facet polygon.
  SolveResult silhouette_plane(const Vec3& o, const Vec3& a, const Vec3& b, const Vec3& d,
                               const Domain& domain) override;
  //! SilhouetteCritical: critical points of J_d in direction d2 over a 3-D polytope.
  SolveResult silhouette_critical(const Vec3& d, const Vec3& d2, const Domain& domain) override;

  //! The primitive called `primitive` (a registry name) with the given parameters (in the order
  //! of its system's parameters) over `domain`: a square system as the six above are (homotopy
  //! under that backend, else subdivision with box_budget), an over-determined one by
  //! subdivision in exclusion mode.  Spurious roots are dropped (drop_spurious_roots).  Throws
  //! InvalidInput for an unknown name, PreconditionViolation for a line system (use
  //! surface_line()) or a wrong number of parameters.
  SolveResult solve(const std::string& primitive, const std::vector<double>& parameters, const Domain& domain,
                    std::size_t box_budget) override;

  //! Tries to prove ⟨∇E, w⟩ ≠ 0 on Σ ∩ P, P = domain in the chart (solvers/gradient_cone.h):
  //! a proof, with a box holding Σ ∩ P, or nothing, with the point of Σ ∩ P where ⟨∇E, w⟩ = 0
  //! that refuted the attempt, if one did.  Within tolerances::gradient_cone_cell_box_budget boxes over a 3-D domain (a
  //! Voronoi cell), tolerances::gradient_cone_box_budget over a facet.  Counted under
  //! `cone_certificates`.
  ConeAnswer prove_gradient_cone(const AffineChart& chart, const Domain& domain, const Vec3& w) override;
  //! The slope of that certificate, 0 if it fails (solvers/gradient_cone.h): within
  //! tolerances::cell_slope_cover_budget boxes, refined towards `target` within
  //! tolerances::cell_slope_box_budget more; counted likewise.
  ConeAnswer gradient_cone_slope(const AffineChart& chart, const Domain& domain, const Vec3& w,
                                 double target) override;
  bool bounds_cone_slopes() const override { return true; }
  //! Built at the first call.
  const FlowDistance* flow_distance() const override;
  //! The proved sign of ⟨∇E, w⟩ on the segment [a, b], or 0 (solvers/gradient_cone.h).
  int gradient_sign(const Vec3& a, const Vec3& b, const Vec3& w) const override;
  //! The proved sign of E(x), or 0 if E(x) is zero up to rounding (solvers/gradient_cone.h).
  using SurfaceOracle::value_sign;
  //! The proved sign of E on the box [lo, hi], or 0: non-zero proves Σ misses the box.
  int value_sign(const Vec3& lo, const Vec3& hi) const override;

  //! E(x) in double.
  double E(const Vec3& x) const;
  //! ∇E(x) in double.
  Vec3 gradient(const Vec3& x) const override;
  //! The unit outward normal ∇E/|∇E| at x (zero vector if ∇E(x) = 0).
  Vec3 normal(const Vec3& x) const override;
  //! Newton iteration x ← x − E(x) ∇E(x)/|∇E(x)|² until |E|/|∇E| is below the projection
  //! tolerance; nothing if it does not converge or leaves the box.
  std::optional<Vec3> project(const Vec3& x) const override;

  //! Per primitive, in the registry's order.
  const std::vector<PrimitiveStatistics>& statistics() const { return stats_; }
  //! The statistics of the primitive called `primitive`; throws InvalidInput for an unknown name.
  const PrimitiveStatistics& statistics(const std::string& primitive) const;
  //! {systems, certified_roots, undecided, boxes, seconds, homotopy_fallbacks, time_limited,
  //!  homotopy_paths, homotopy_near_real, homotopy_diverging_near_domain, homotopy_certified,
  //!  homotopy_uncertified, homotopy_pieces_by_subdivision, per_primitive: {name:
  //!  {the same counts for that primitive}}, cone_certificates: {attempts, proved, boxes, seconds},
  //!  backend: "subdivision" or "homotopy"}
  nlohmann::json statistics_json() const override;

 private:
  //! Keeps the roots inside the domain that no side condition disproves, and counts the call: its
  //! seconds since `start`, or `seconds` when the solver measured them from `start`.
  SolveResult finish(std::size_t primitive, const std::vector<double>& parameters, SolveResult result,
                     std::chrono::steady_clock::time_point start, std::optional<double> seconds = std::nullopt);
  SolveResult solve_square(std::size_t primitive, const std::vector<double>& parameters, const Domain& domain,
                           std::size_t box_budget);
  SolveResult solve_over_determined(std::size_t primitive, const std::vector<double>& parameters,
                                    const Domain& domain, std::size_t box_budget);
  //! time_limit_seconds for a subdivision solve or univariate isolation started now: 0 without a
  //! deadline, else the time left (at least the least positive double).
  double seconds_left() const;
  void count_fallback(std::size_t primitive);

  struct Impl;
  std::unique_ptr<Impl> impl_;
  Box3 box_;
  Box3 clip_box_;
  SolverBackend backend_;
  std::uint64_t seed_ = 1;
  std::optional<std::chrono::steady_clock::time_point> deadline_;
  std::vector<PrimitiveStatistics> stats_;
  //! The certificate within `budget` boxes, counted.
  GradientConeResult gradient_cone(const AffineChart& chart, const Domain& domain, const Vec3& w, std::size_t budget,
                                   const SlopeRefinement& refinement);
  //! The answer of a certificate: the proof, its slope and its box around Σ ∩ P, or the refuting
  //! point.
  static ConeAnswer answer(const GradientConeResult& r);
  //! Cone certificates attempted, proved, refuted (solvers/gradient_cone.h, test (iv)), their
  //! boxes and time; the boxes and time of the failed ones (each of which leads to a full solve)
  //! apart.
  struct ConeStatistics {
    std::size_t attempts = 0, proved = 0, refuted = 0, boxes = 0, failed_boxes = 0;
    double seconds = 0, failed_seconds = 0;
  } cone_stats_;
};

}  // namespace delmesh
