#pragma once
//! \file surface_oracle.h
//! The numerical primitives of §5.2 for one surface Σ = {E = 0} inside a box B, compiled once,
//! behind one interface used by every check of the mesher: a solver backend (certified
//! subdivision, or homotopy for square polynomial systems), per-call budgets from tolerances.h,
//! and statistics (calls, certified roots, undecided regions, boxes, seconds per primitive).
//!
//! The primitives and the certificate may be called from several threads at once: the compiled
//! systems keep their scratch per thread, and the statistics are updated under a lock.
//!
//! Policy for undecided regions (design notes, "Meaning of a certified result"): a region that the
//! solver can neither exclude nor certify is a candidate witness.  project() moves its centre onto
//! Σ by Newton steps along ∇E; the caller inserts the projected point if it lies in the Voronoi
//! face under test.  Inserting a false witness is harmless (§3, Lemma 5.1).  Undecided regions
//! are counted here (`undecided`) and never dropped silently.

#include <array>
#include <chrono>
#include <memory>
#include <optional>
#include <ostream>
#include <vector>

#include <nlohmann/json.hpp>

#include "meshing/del_mesh.h"
#include "solvers/domain.h"
#include "solvers/gradient_cone.h"
#include "solvers/solve_result.h"
#include "symbolic/surface.h"

namespace delmesh {

using Vec3 = std::array<double, 3>;

//! The six primitives of §5.2, in the paper's order.
enum class Primitive {
  surface_critical,
  surface_line,
  surface_plane_contact,
  curve_critical,
  silhouette_plane,
  silhouette_critical
};
std::ostream& operator<<(std::ostream& out, Primitive primitive);
inline constexpr int primitive_count = 6;

struct PrimitiveStatistics {
  std::size_t calls = 0, certified_roots = 0, undecided = 0, boxes = 0;
  double seconds = 0;
};

class SurfaceOracle {
 public:
  //! Compiles the six primitive systems of `surface`.  Precondition: box is non-empty.
  SurfaceOracle(const Surface& surface, const Box3& box, SolverBackend backend);
  ~SurfaceOracle();
  SurfaceOracle(SurfaceOracle&&) noexcept;
  SurfaceOracle& operator=(SurfaceOracle&&) noexcept;

  const Box3& box() const { return box_; }
  const Surface& surface() const;
  double diagonal() const { return box_.diagonal(); }

  //! SurfaceLine: zeros of E(p + t v) for t ∈ [t0, t1] (certified, or undecided regions:
  //! singular_root for a tangency, boundary_root for a zero at t0 or t1).
  SolveResult surface_line(const Vec3& p, const Vec3& v, double t0, double t1);
  //! SurfaceCritical in direction d over a 3-D domain.
  SolveResult surface_critical(const Vec3& d, const Domain& domain, std::size_t box_budget);
  //! SurfacePlaneContact over a facet polygon (exclusion mode: never certifies, undecided boxes
  //! are possible contacts).
  SolveResult surface_plane_contact(const Vec3& o, const Vec3& a, const Vec3& b, const Domain& domain);
  //! CurveCritical in direction a of Σ ∩ {o + u a + v b} over a facet polygon.
  SolveResult curve_critical(const Vec3& o, const Vec3& a, const Vec3& b, const Domain& domain);
  //! SilhouettePlane: J_d ∩ {o + u a + v b} over a facet polygon.
  SolveResult silhouette_plane(const Vec3& o, const Vec3& a, const Vec3& b, const Vec3& d,
                               const Domain& domain);
  //! SilhouetteCritical: critical points of J_d in direction d2 over a 3-D polytope.
  SolveResult silhouette_critical(const Vec3& d, const Vec3& d2, const Domain& domain);

  //! Tries to prove ⟨∇E, w⟩ ≠ 0 on Σ ∩ P, P = domain in the chart (solvers/gradient_cone.h):
  //! true is a proof, false proves nothing.  Counted under `cone_certificates`.
  bool prove_gradient_cone(const AffineChart& chart, const Domain& domain, const Vec3& w);

  //! E(x) in double.
  double E(const Vec3& x) const;
  //! ∇E(x) in double.
  Vec3 gradient(const Vec3& x) const;
  //! The unit outward normal ∇E/|∇E| at x (zero vector if ∇E(x) = 0).
  Vec3 normal(const Vec3& x) const;
  //! Newton iteration x ← x − E(x) ∇E(x)/|∇E(x)|² until |E|/|∇E| is below the projection
  //! tolerance; nothing if it does not converge or leaves the box.
  std::optional<Vec3> project(const Vec3& x) const;

  const std::array<PrimitiveStatistics, primitive_count>& statistics() const { return stats_; }
  //! {systems, certified_roots, undecided, boxes, seconds, per_primitive: {...},
  //!  cone_certificates: {attempts, proved, boxes, seconds}}
  nlohmann::json statistics_json() const;

 private:
  SolveResult finish(Primitive primitive, SolveResult result, std::chrono::steady_clock::time_point start);
  SolveResult solve_square(int index, const std::vector<double>& parameters, const Domain& domain,
                           std::size_t box_budget);

  struct Impl;
  std::unique_ptr<Impl> impl_;
  Box3 box_;
  SolverBackend backend_;
  std::array<PrimitiveStatistics, primitive_count> stats_{};
  struct ConeStatistics {
    std::size_t attempts = 0, proved = 0, boxes = 0;
    double seconds = 0;
  } cone_stats_;
};

}  // namespace delmesh
