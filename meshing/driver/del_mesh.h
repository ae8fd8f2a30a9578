#pragma once
//! \file del_mesh.h
//! DelMesh (§6.2): SampleTopology, then Quality and Smooth with Topology re-run locally after
//! every insertion, until nothing changes.  Theorem 6.1: for 0 < λ ≤ 0.06 the output Tri S|Σ is
//! homeomorphic to Σ, every triangle has radius-edge ratio ≤ 1+λ and every edge roughness ≤ 2β(λ).

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/enum_names.h"
#include "meshing/core/mesh_status.h"
#include "meshing/core/progress_report.h"
#include "meshing/core/surface_mesh.h"
#include "meshing/core/theorem_bounds.h"
#include "solvers/solver_backend.h"
#include "symbolic/surface.h"

namespace delmesh {

enum class MeshPhase { topology, all };
constexpr auto enum_names(MeshPhase) {
  return name_table<MeshPhase>("MeshPhase", {{MeshPhase::topology, "topology"}, {MeshPhase::all, "all"}});
}
inline std::ostream& operator<<(std::ostream& out, MeshPhase phase) { return write_enum(out, phase); }

struct DelMeshOptions {
  double lambda = lambda0;               //!< 0 < λ < 1/3; Theorem 6.1 covers λ ≤ λ₀ = 0.06
  MeshPhase phase = MeshPhase::all;
  SolverBackend solver = SolverBackend::subdivision;
  std::optional<double> size_bound;      //!< H: also refine triangles with Delaunay-ball radius > H
  //! δ: also refine triangles of Tri S|Σ not proved within δ of Σ (quality.h, distance_witness);
  //! the run is then complete only if the gradient-flow certificate of the output proves a
  //! two-sided Hausdorff bound ≤ δ.  Needs an oracle with SurfaceOracle::flow_distance() (an
  //! implicit surface) and phase all.
  std::optional<double> max_distance;
  //! del_mesh(surface, …) ends with certify_distance() (always when max_distance is given).
  //! Off for programs that time the mesher alone against meshers that certify nothing.
  bool distance_certificate = true;
  //! The termination floor: a witness closer than this (world units) to its nearest sample is
  //! not inserted but recorded (statistics "min_spacing"), and the run is then uncertified.
  //! 0: no floor.  Meant for surfaces that are not C² (Lemma 5.1's spacing argument needs C²).
  double min_spacing = 0;
  std::size_t max_points = 200000;
  double time_limit_seconds = 0;         //!< 0: none
  std::uint64_t seed = 1;                //!< generic directions; same seed → same mesh
  //! Threads for each insertion's work: the new cell's certificate runs beside the records of
  //! the changed faces (two threads), and batches of records and facets of at least
  //! tolerances::parallel_least_* run on all threads (smaller ones on one, unless
  //! parallel_every_batch, for tests of that independence); 0: every hardware thread.  The mesh
  //! does not depend on it.
  int threads = 0;
  bool parallel_every_batch = false;
  //! If given, the run stops (status interrupted) at the first check after it becomes true; it
  //! is read between checks, so a signal handler may set it.
  const std::atomic<bool>* interrupt = nullptr;
  //! Progress callback, on the thread of the run (meshing/core/progress_report.h): the refinement's
  //! reports at most every tolerances::progress_interval_seconds, then one when the distance
  //! certificate starts; elapsed seconds count from the call's start.  May be empty.
  std::function<void(const ProgressReport&)> progress;
};

struct [[nodiscard]] DelMeshResult {
  MeshStatus status = MeshStatus::complete;
  SurfaceMesh mesh;              //!< Tri S|Σ, consistently outward oriented
  nlohmann::json statistics;     //!< the run's statistics (the JSON of `delmesh mesh --stats`, built in del_mesh.cpp)
  //! Per face of mesh, in index order: the bound that certify_distance()'s certificate proved on
  //! the distance from every point of the face to Σ (gradient_flow_certificate.h,
  //! triangle_distance_bounds), when it certified the mesh; else empty.
  std::vector<double> triangle_distance_bounds;
};

//! The longest time limit of a run (about 31 years): the deadline, start + limit, must stay
//! representable in the steady clock's nanoseconds.
inline constexpr double max_time_limit_seconds = 1e9;

//! The options of DelMeshOptions that have a range, in the order del_mesh checks them.
enum class MeshOption { lambda, size_bound, max_distance, max_points, time_limit, threads, min_spacing };
constexpr auto enum_names(MeshOption) {
  return name_table<MeshOption>("MeshOption", {{MeshOption::lambda, "lambda"},
                                               {MeshOption::size_bound, "size_bound"},
                                               {MeshOption::max_distance, "max_distance"},
                                               {MeshOption::max_points, "max_points"},
                                               {MeshOption::time_limit, "time_limit_seconds"},
                                               {MeshOption::threads, "threads"},
                                               {MeshOption::min_spacing, "min_spacing"}});
}
inline std::ostream& operator<<(std::ostream& out, MeshOption option) { return write_enum(out, option); }
inline constexpr MeshOption all_mesh_options[] = {MeshOption::lambda,       MeshOption::size_bound,
                                                  MeshOption::max_distance, MeshOption::max_points,
                                                  MeshOption::time_limit,   MeshOption::threads,
                                                  MeshOption::min_spacing};

//! The range of `option` that `options` violates, in words that follow "must" ("satisfy 0 <
//! lambda < 1/3"), or nothing if the option lies in its range: 0 < lambda < 1/3 (Theorem 6.1
//! covers lambda ≤ 0.06); size_bound and max_distance, when set, positive finite lengths;
//! max_points ≥ 1;
//! 0 ≤ time_limit_seconds ≤ max_time_limit_seconds; threads ≥ 0; min_spacing finite and ≥ 0.
//! The one statement of these ranges: del_mesh checks them, and so do the programs, before
//! their other work, to name their own flags.
std::optional<std::string> violated_range(MeshOption option, const DelMeshOptions& options);

//! Meshes Σ = {E = 0} ⊂ interior(box): make_oracle() on the ImplicitInput (surface, box,
//! options.solver), then del_mesh() on it; the time limit and the statistics' seconds count the
//! validation.  Throws InvalidInput if Σ is empty in the box, meets the box boundary, or is
//! singular (∇E = 0 somewhere on Σ), if the box is empty, or if an option is out of its range
//! (violated_range: "lambda must satisfy 0 < lambda < 1/3"), the options before the surface.
DelMeshResult del_mesh(const Surface& surface, const Box3& box, const DelMeshOptions& options);

struct PreparedInput;
//! Meshes an input made ready by make_oracle() (meshing/inputs/make_oracle.h), of any kind: the
//! run on its oracle, with the options' lengths at the oracle's unit scale and the result brought
//! back (meshing/driver/scaled_run.h); the statistics get the input's description under its key
//! ("surface" or "input_mesh") and its validation seconds; an implicit surface then gets
//! certify_distance() when options.distance_certificate or options.max_distance asks for it.
//! Throws InvalidInput as del_mesh(oracle, …) does.
DelMeshResult del_mesh(PreparedInput& input, const DelMeshOptions& options);

//! The gradient-flow certificate of a run's output (gradient_flow_certificate.h, under the run's
//! time limit counted from `start`, with options.max_distance as its distance radius), if the run
//! ended complete or uncertified: the statistics' "distance" gets that certificate's JSON, or
//! {status: "not attempted", reason} after any other ending, and max_distance (null if not given).
//! With max_distance, a complete run becomes uncertified unless the certificate proves a
//! two-sided Hausdorff bound ≤ δ; that failure is listed under "unsettled" (reason
//! distance_not_certified in by_reason, check "distance" with the certificate's reason in regions).
//! A certificate stopped by the interrupt flag or the time limit makes such a run interrupted or
//! time_limit instead.  Precondition: validate_input(surface, box) succeeded (the run
//! did it).  A caller of del_mesh(oracle, …) on an implicit surface calls this itself.
void certify_distance(DelMeshResult& result, const Surface& surface, const Box3& box, const DelMeshOptions& options,
                      std::chrono::steady_clock::time_point start);

class SurfaceOracle;
//! Meshes the surface of `oracle` (any implementation of meshing/core/surface_oracle.h) in its box.
//! The caller has validated the input (its seconds go to the statistics' seconds_validation);
//! options.solver is not read (the oracle has its own backend).  Throws InvalidInput as above,
//! and if max_distance is given to an oracle without flow_distance().  It does not run
//! certify_distance(): the oracle does not give E.
DelMeshResult del_mesh(SurfaceOracle& oracle, const DelMeshOptions& options, double seconds_validation = 0);

}  // namespace delmesh
