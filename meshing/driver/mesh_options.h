#pragma once
//! \file mesh_options.h
//! The options of a DelMesh run (del_mesh.h) and their ranges, stated once: the library checks
//! them with DelMeshOptions::validate(), and a program maps each MeshOption to its own flag.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <ostream>
#include <string>

#include "common/enum_names.h"
#include "meshing/core/progress_report.h"
#include "meshing/core/theorem_bounds.h"
#include "solvers/solver_backend.h"

namespace delmesh {

enum class MeshPhase { topology, all };
constexpr auto enum_names(MeshPhase) {
  return name_table<MeshPhase>("MeshPhase", {{MeshPhase::topology, "topology"}, {MeshPhase::all, "all"}});
}
inline std::ostream& operator<<(std::ostream& out, MeshPhase phase) { return write_enum(out, phase); }

struct OptionViolation;

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
  //! A triangle-mesh input only: the feature angle θ (degrees, 0 < θ < 180) at which its sharp
  //! edges are detected (meshing/inputs/sharp_features.h; the default is default_feature_angle_deg),
  //! whose Voronoi facets the Smooth check exempts (meshing/checks/smooth.h); empty: no features,
  //! Smooth exempts nothing.  An implicit surface does not read it.
  std::optional<double> feature_angle_deg = 60.0;
  std::size_t max_points = 200000;
  double time_limit_seconds = 0;         //!< 0: none
  std::uint64_t seed = 1;                //!< generic directions; same seed → same mesh
  //! Threads for each insertion's work: the new cell's certificate runs beside the records of
  //! the changed faces (two threads), and batches of records and facets of at least
  //! tolerances::parallel_least_* run on all threads (smaller ones on one); 0: every hardware
  //! thread.  The mesh does not depend on it.
  int threads = 0;
  //! If given, the run stops (status interrupted) at the first check after it becomes true; it
  //! is read between checks, so a signal handler may set it.
  const std::atomic<bool>* interrupt = nullptr;
  //! Progress callback, on the thread of the run (meshing/core/progress_report.h): the refinement's
  //! reports at most every tolerances::progress_interval_seconds, then one when the distance
  //! certificate starts; elapsed seconds count from the call's start.  May be empty.
  std::function<void(const ProgressReport&)> progress;

  //! The first option, in the order of all_mesh_options, that is out of its range
  //! (violated_range), or nothing if every option lies in its range.
  std::optional<OptionViolation> validate() const;
};

//! The longest time limit of a run (about 31 years): the deadline, start + limit, must stay
//! representable in the steady clock's nanoseconds.
inline constexpr double max_time_limit_seconds = 1e9;

//! The options of DelMeshOptions that have a range, in the order validate() checks them.
enum class MeshOption { lambda, size_bound, max_distance, max_points, time_limit, threads, min_spacing, feature_angle };
constexpr auto enum_names(MeshOption) {
  return name_table<MeshOption>("MeshOption", {{MeshOption::lambda, "lambda"},
                                               {MeshOption::size_bound, "size_bound"},
                                               {MeshOption::max_distance, "max_distance"},
                                               {MeshOption::max_points, "max_points"},
                                               {MeshOption::time_limit, "time_limit_seconds"},
                                               {MeshOption::threads, "threads"},
                                               {MeshOption::min_spacing, "min_spacing"},
                                               {MeshOption::feature_angle, "feature_angle_deg"}});
}
inline std::ostream& operator<<(std::ostream& out, MeshOption option) { return write_enum(out, option); }
inline constexpr MeshOption all_mesh_options[] = {MeshOption::lambda,       MeshOption::size_bound,
                                                  MeshOption::max_distance, MeshOption::max_points,
                                                  MeshOption::time_limit,   MeshOption::threads,
                                                  MeshOption::min_spacing,  MeshOption::feature_angle};

//! The range of `option` that `options` violates, in words that follow "must" ("satisfy 0 <
//! lambda < 1/3"), or nothing if the option lies in its range: 0 < lambda < 1/3 (Theorem 6.1
//! covers lambda ≤ 0.06); size_bound and max_distance, when set, positive finite lengths;
//! max_points ≥ 1;
//! 0 ≤ time_limit_seconds ≤ max_time_limit_seconds; threads ≥ 0; min_spacing finite and ≥ 0;
//! feature_angle_deg, when set, in (0, 180).
//! The one statement of these ranges: DelMeshOptions::validate() reads them, and the programs
//! map each option to their own flag.
std::optional<std::string> violated_range(MeshOption option, const DelMeshOptions& options);

//! An option out of its range: which one, and its range in words that follow "must".
struct OptionViolation {
  MeshOption option;
  std::string requirement;
};

//! The run's deadline, `start` plus options.time_limit_seconds, or none without a time limit.
std::optional<std::chrono::steady_clock::time_point> deadline_of(const DelMeshOptions& options,
                                                                 std::chrono::steady_clock::time_point start);

}  // namespace delmesh
