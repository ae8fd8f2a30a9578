#pragma once
//! \file surface_oracle.h
//! What the mesher asks of a surface Σ inside a box B: the six primitives of §5.2, the sign of
//! Σ's defining function (or inside/outside), the outward normal, projection onto Σ and the box.
//! Every check (vor_edge, facet_contact, facet_cycle, silhouette, sample_topology, the restricted
//! Delaunay records) and the drivers (refinement, del_mesh) talk to Σ through this interface
//! only.  Two kinds of input implement it:
//!  - ImplicitOracle (meshing/inputs/implicit_oracle.h): Σ = {E = 0} for a symbolic E, answered by the
//!    certified solvers;
//!  - MeshOracle (meshing/inputs/mesh_oracle.h): Σ a closed, outward-oriented triangle mesh, answered
//!    exactly with CGAL's predicates.
//! A third kind of input is one more implementation of this class.
//!
//! Conventions shared by every implementation.  "E" below is the implementation's defining
//! function: negative inside Σ, positive outside, zero on Σ (for a mesh: the side of the mesh).
//! Each primitive returns a SolveResult (solvers/solve_result.h): its roots are points of Σ the
//! answer proves, its undecided regions are what the oracle could not decide (a tangency is
//! reported as an undecided region with reason singular_root, a zero at the end of a segment as
//! boundary_root); the checks turn undecided regions into candidate witnesses by project()
//! (meshing/checks/detail/candidates.h).  The unknowns of the roots and regions are those of the
//! registry's systems (solvers/primitive_registry.h): t for surface_line, (u, v) in the plane
//! frame (o, a, b) for the facet primitives, world (x, y, z) for the cell primitives; `world`
//! always holds the world point.
//!
//! Threads: the primitives may be called from several threads at once (implementations keep
//! their statistics under a lock); set_run_controls() is called before that.

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/tolerances.h"
#include "common/vec3.h"
#include "solvers/domain.h"
#include "solvers/gradient_cone.h"
#include "solvers/solve_result.h"
#include "symbolic/surface.h"

namespace delmesh {

class FlowDistance;  // flow_distance.h

class SurfaceOracle {
 public:
  virtual ~SurfaceOracle() = default;

  //! The run's controls for every later call: `seed` for any seeded choice of the oracle, and
  //! `deadline`, if set, an absolute end after which a primitive returns status time_limit with
  //! what it did not examine undecided (budget).  Defaults until called: seed 1, no deadline.
  virtual void set_run_controls(std::uint64_t seed, std::optional<std::chrono::steady_clock::time_point> deadline) = 0;

  //! The box B; Σ lies in its interior.
  virtual const Box3& box() const = 0;
  double diagonal() const { return box().diagonal(); }
  //! A box B′ ⊆ B that holds Σ ∩ B in its interior (proved, not assumed): the mesher clips every
  //! Voronoi face to it (voronoi_geometry.h) and seeds in it, since all it checks of a face is
  //! about Σ.  B itself by default.
  virtual const Box3& clip_box() const { return box(); }

 protected:
  //! The clip box of an implementation that has proved Σ ∩ box ⊆ tight: `tight` widened on every
  //! side by tolerances::surface_box_relative_margin · box.diagonal(), so that Σ lies in its
  //! interior, and met with `box`.
  static Box3 clip_box_around(const Box3& tight, const Box3& box) {
    const double margin = tolerances::surface_box_relative_margin * box.diagonal();
    Box3 clip;
    for (int k = 0; k < 3; ++k) {
      clip.lo[k] = std::max(box.lo[k], tight.lo[k] - margin);
      clip.hi[k] = std::min(box.hi[k], tight.hi[k] + margin);
    }
    return clip;
  }

 public:
  //! SurfaceLine: the points of Σ on {p + t v : t ∈ [t0, t1]} (roots: transversal crossings;
  //! undecided: tangencies as singular_root, zeros at t0 or t1 as boundary_root).
  virtual SolveResult surface_line(const Vec3& p, const Vec3& v, double t0, double t1) = 0;
  //! SurfaceCritical: the critical points of the height ⟨x, d⟩ on Σ in a 3-D domain.
  virtual SolveResult surface_critical(const Vec3& d, const Domain& domain, std::size_t box_budget) = 0;
  //! SurfacePlaneContact: the points of the facet polygon (domain, in the plane frame o, a, b)
  //! where Σ touches the plane (the plane's normal is normal to Σ there).
  virtual SolveResult surface_plane_contact(const Vec3& o, const Vec3& a, const Vec3& b, const Domain& domain) = 0;
  //! CurveCritical: the critical points in direction a of the curve Σ ∩ {o + u a + v b} over a
  //! facet polygon.
  virtual SolveResult curve_critical(const Vec3& o, const Vec3& a, const Vec3& b, const Domain& domain) = 0;
  //! SilhouettePlane: the silhouette J_d of Σ in direction d (points where d is tangent to Σ)
  //! intersected with the plane {o + u a + v b} over a facet polygon.
  virtual SolveResult silhouette_plane(const Vec3& o, const Vec3& a, const Vec3& b, const Vec3& d,
                                       const Domain& domain) = 0;
  //! SilhouetteCritical: the critical points of the curve J_d in direction d2 over a 3-D polytope.
  virtual SolveResult silhouette_critical(const Vec3& d, const Vec3& d2, const Domain& domain) = 0;
  //! The primitive called `primitive` (a registry name) with the given parameters (in the order
  //! of its system's parameters) over `domain`.  Throws InvalidInput for an unknown name (or one
  //! the implementation does not answer by name), PreconditionViolation for a line system (use
  //! surface_line()) or a wrong number of parameters.
  virtual SolveResult solve(const std::string& primitive, const std::vector<double>& parameters,
                            const Domain& domain, std::size_t box_budget) = 0;

  //! What prove_gradient_cone() or gradient_cone_slope() found.
  struct ConeAnswer {
    bool proved = false;  //!< ⟨∇E, w⟩ ≠ 0 on Σ ∩ P is proved; false proves nothing
    //! When the attempt failed because it proved a point of Σ ∩ P where ⟨∇E, w⟩ = 0
    //! (solvers/gradient_cone.h, test (iv)): that point, to the rounding of its enclosure
    //! (GradientConeResult::vanishing_point).  An implementation may never report one.
    std::optional<Vec3> vanishing_point;
    //! gradient_cone_slope() only: the slope ρ, > 0 exactly when proved.
    double slope = 0;
    //! When proved, if the implementation bounds it: a box {lo, hi} (world coordinates) that
    //! holds Σ ∩ P, empty (lo[k] > hi[k] for some k) when Σ ∩ P = ∅ is proved
    //! (GradientConeResult::surface_lo, surface_hi).
    std::optional<std::array<Vec3, 2>> surface_box;
    //! When proved, if the implementation bounds it: +1 if ⟨∇E, w⟩ > 0 on all of Σ ∩ P, −1 if
    //! < 0 there; 0 if not known (GradientConeResult::orientation).
    int orientation = 0;
  };
  //! Tries to prove ⟨∇E, w⟩ ≠ 0 on Σ ∩ P, P = domain in the chart (an implementation may never
  //! prove).
  virtual ConeAnswer prove_gradient_cone(const AffineChart& chart, const Domain& domain, const Vec3& w) = 0;
  //! The same certificate with its slope (solvers/gradient_cone.h): a slope ρ > 0 is a proof of
  //! |⟨∇E, w⟩| ≥ ρ |∇E| > 0 on Σ ∩ P (ρ = +∞: Σ ∩ P = ∅); 0 proves nothing.  The cover may be
  //! refined to raise ρ towards `target` (SlopeRefinement).  The default, for an oracle that
  //! bounds no slopes, proves nothing.
  virtual ConeAnswer gradient_cone_slope(const AffineChart& chart, const Domain& domain, const Vec3& w,
                                         double target) {
    (void)chart, (void)domain, (void)w, (void)target;
    return {};
  }
  //! Whether gradient_cone_slope() can return a slope (false: it always returns 0).
  virtual bool bounds_cone_slopes() const { return false; }
  //! The proved sign of ⟨∇E, w⟩ on the segment [a, b], or 0 (nothing proved).
  virtual int gradient_sign(const Vec3& a, const Vec3& b, const Vec3& w) const = 0;
  //! The proved sign of E(x): −1 inside Σ, +1 outside, 0 on Σ or not decided.
  int value_sign(const Vec3& x) const { return value_sign(x, x); }
  //! The proved sign of E on the box [lo, hi], or 0: non-zero proves Σ misses the box.
  virtual int value_sign(const Vec3& lo, const Vec3& hi) const = 0;

  //! A vector along the outward normal of Σ near x (∇E(x) for an implicit surface; not
  //! necessarily of unit length); the zero vector if there is none.
  virtual Vec3 gradient(const Vec3& x) const = 0;
  //! The unit outward normal at x (zero vector if there is none).
  virtual Vec3 normal(const Vec3& x) const = 0;
  //! A point of Σ near x (within the box), or nothing if the implementation cannot find one.
  virtual std::optional<Vec3> project(const Vec3& x) const = 0;
  //! The certified distance bound of triangles to Σ along the flow of ∇E (flow_distance.h), or
  //! null for an oracle without a gradient field (the default).  Safe to call from several
  //! threads; the object lives as long as the oracle.
  virtual const FlowDistance* flow_distance() const { return nullptr; }

  //! Whether some answer given so far rests on a computation that is not certified: then the
  //! answers may miss a point of Σ on a face (a missed root is not reported as undecided), and a
  //! run that used them cannot be `complete`.  False by default (every answer certified or reported
  //! undecided, solve_result.h).
  virtual bool gave_uncertified_answers() const { return false; }

  //! The oracle's work counters as JSON for the statistics (implementation-specific keys; every
  //! implementation has "systems", the number of primitive calls, and "backend").
  virtual nlohmann::json statistics_json() const = 0;

 protected:
  // Copied or moved only as part of an implementation (no slicing through the interface).
  SurfaceOracle() = default;
  SurfaceOracle(const SurfaceOracle&) = default;
  SurfaceOracle& operator=(const SurfaceOracle&) = default;
};

}  // namespace delmesh
