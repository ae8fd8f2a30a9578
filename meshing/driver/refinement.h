#pragma once
//! \file refinement.h
//! The refinement driver of DelMesh: Topology(S) (§5.4, steps (a)–(e)), Quality and Smooth
//! (§6.2, steps 2–3) and the optional size bound, as one loop over an ordered table of steps.
//! The table is the check registry (meshing/checks/check_registry.h), one step per row, with the paper's
//! rows first:
//!
//!   | row             | queue holds (FaceKind)                         | dirtied           |
//!   |-----------------|------------------------------------------------|-------------------|
//!   | (a) vor_edge    | triangles whose dual Voronoi edge is new       | new_faces         |
//!   | (b) facet_contact| edges whose dual Voronoi facet is new         | new_faces         |
//!   | (c) topo_disk   | samples whose restricted star may have changed | restricted_star   |
//!   | (d) facet_cycle | edges whose dual Voronoi facet is new          | new_faces         |
//!   | (e) silhouette  | samples whose Voronoi cell is new              | new_faces         |
//!   | quality (+ size)| restricted triangles whose dual edge changed   | restricted_triangles |
//!   | smooth          | restricted triangles whose dual edge changed   | restricted_triangles |
//!
//! with the registered rows after the paper's rows of their phase.  The driver names no check:
//! it queues a face for the rows whose FaceKind and Dirtied rule say so, and runs each row's
//! function.
//!
//! Each iteration takes one item of the first non-empty queue; a witness is inserted, the item
//! goes back on its queue (its face has not been shown clean) and the loop starts again at (a),
//! so the paper's order holds (Quality before Smooth, a topology witness
//! before any geometric one).  The geometry rows (Quality, Smooth) run only after
//! enable_geometry() (DelMesh step 2 starts after SampleTopology).  run() returns complete when
//! every queue is empty.
//!
//! Each row's witness set only shrinks with its face (the recheck lemma), so after inserting x
//! only the faces dual to simplices containing x get the topology checks again (VorEdge on the
//! triangles xqr, FacetContact and FacetCycle on the edges xq, Silhouette on V_x), TopoDisk is
//! re-queued for the vertices of triangles that entered or left Tri S|Σ, and Quality, size and
//! Smooth for the triangles whose restricted status or dual point changed.  Conditions: a check's
//! generic choices depend only on its face's sites, only clean results are kept, and a deletion
//! (Lemma 5.4) re-queues every face within N(p).  RecheckPolicy::changed_faces re-queues the
//! shrunk faces too (for testing the lemma).
//!
//! Threads: the records of each insertion's new and shrunk triangles are computed on several
//! threads and installed in a fixed order, so the output does not depend on the thread count; the
//! checks run one at a time, in the table's order.
//!
//! Witnesses within tolerances::duplicate_sample_relative_distance of a sample are not inserted
//! (`rejected_witnesses`); the next witness of the check is tried, then (FacetCycle, Silhouette)
//! the next generic choice, up to tolerances::generic_choice_attempts; a face with none left is
//! unsettled (rejected_witness).  Opposite-sheet partners: after a witness w is inserted, the
//! nearest other point y of Σ on the normal line of Σ at w may be inserted too (partner_of = w,
//! `opposite_sheet`), under conditions that keep the guarantee and Lemma 5.1's termination.
//!
//! Unsettled faces stay on a list; when every queue is empty each is checked again if S changed
//! since its check, and unsettled() lists what remains: del_mesh then reports uncertified.
//!
//! The lemma with its proof, the threading, the witness policy and the partners' termination
//! argument are in docs/refinement.md.

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/run_limits.h"
#include "common/tolerances.h"
#include "meshing/checks/check_registry.h"
#include "meshing/core/detail/key_order.h"
#include "meshing/core/mesh_status.h"
#include "meshing/core/progress_report.h"
#include "meshing/core/surface_oracle.h"
#include "meshing/core/witness.h"
#include "meshing/voronoi/delaunay.h"
#include "meshing/voronoi/restricted_delaunay.h"

namespace delmesh {

//! One insertion, as the mesher saw it (for Lemma 5.1 / Theorem 6.1 experiments).
struct InsertionRecord {
  Vec3 point{};
  CheckKind kind = CheckKind::seed;
  VertexId id = -1;
  VertexId nearest = -1;           //!< nearest sample at insertion time (−1 for the first point)
  double nearest_distance = 0;     //!< |point − nearest|
  bool from_undecided = false;
  //! An opposite-sheet partner (see above): the id of the witness it pairs; −1 otherwise.
  VertexId partner_of = -1;
};

struct RefinementLimits {
  std::size_t max_points = 200000;
  //! Absolute deadline; none if empty.  run() tests it at its clock readings: after an
  //! insertion, when the row of the checks changes, and at least every
  //! tolerances::checks_per_clock_reading checks (the progress line likewise).
  std::optional<std::chrono::steady_clock::time_point> deadline;
  //! Called at the clock readings at most every tolerances::progress_interval_seconds with the
  //! phase (topology, or geometry once enable_geometry() ran), the samples and the enabled
  //! rows' queue sizes; may be empty.
  std::function<void(const ProgressReport&)> progress;
  //! The run's start, from which the reports' elapsed_seconds count; the Refinement's
  //! construction if empty.
  std::optional<std::chrono::steady_clock::time_point> start;
  //! Stops the run (interrupted) when it reads true; none if null.
  const std::atomic<bool>* interrupt = nullptr;
  //! A witness this close to a sample (relative to the box diagonal) is rejected as a duplicate.
  double duplicate_relative_distance = tolerances::duplicate_sample_relative_distance;
  //! The termination floor (world units, 0: none): a witness of a geometry row (Quality, Smooth,
  //! the size bound, a registered geometry check) closer than this to its nearest sample, or a
  //! witness of a topology row (or a seed) closer than tolerances::topology_floor_fraction times
  //! this, is not inserted but recorded (floor_json()); its face is then left unsettled
  //! (rejected_witness), so the run cannot end complete.  Either floor bounds the number of
  //! insertions (a packing argument in the box).
  double min_spacing = 0;
};

//! How a finished run stands: its status, judged on the final Vor S and Tri S|Σ.
struct Certification {
  MeshStatus status = MeshStatus::complete;
  std::vector<Unsettled> unsettled;  //!< Refinement::unsettled() and the unresolved edge regions
  std::size_t unresolved_edge_regions = 0;
};

//! Which faces are checked again after an insertion (see the lemma above).
enum class RecheckPolicy {
  new_faces,     //!< the faces dual to simplices containing the new sample (the default)
  changed_faces  //!< also every face that shrank (the lemma says this finds nothing more)
};

class Refinement {
 public:
  //! `threads` threads (0: every hardware thread) compute the records and facets of the faces an
  //! insertion changes, in batches large enough to pay for it (detail::ParallelFor; every batch
  //! with `parallel_every_batch`); the result is the same for every number of threads.
  Refinement(SurfaceOracle& oracle, std::uint64_t seed, RefinementLimits limits,
             RecheckPolicy policy = RecheckPolicy::new_faces, int threads = 1, bool parallel_every_batch = false);

  //! Inserts the witness into S (unless it duplicates a sample), logs it, and queues the faces
  //! it created or changed.  Returns the new id, or nothing if rejected.
  std::optional<VertexId> insert(const Witness& witness);
  //! Deletes p from S (a seed, Lemma 5.4) and queues every face within its former neighbours.
  void remove(VertexId p);

  //! Turns on the geometry rows (Quality with the size bound H and the distance bound δ if given,
  //! the latter with the oracle's flow_distance(); Smooth is skipped for
  //! λ ≥ 1/6, where β(λ) is undefined: CheckInfo::runs_at), and queues every current face each
  //! of them would examine (for Quality and Smooth: every restricted triangle).
  //! Precondition: 0 < lambda < 1/3, size_bound > 0 if given, max_distance > 0 if given and then
  //! the oracle bounds distances (SurfaceOracle::flow_distance() not null).
  void enable_geometry(double lambda, std::optional<double> size_bound,
                       std::optional<double> max_distance = std::nullopt);
  //! True once the deadline has passed or the interrupt flag is set (the clock read now).  For
  //! loops outside run() that insert or queue many faces (seed insertion); run() itself reads
  //! them at its own clock readings.
  bool limit_passed() const { return run_limits_.expired_now() != StopReason::none; }
  //! The threads in use (the constructor's request capped by the hardware).
  int threads() const { return parallel_.threads(); }

  //! Runs the table until every queue is empty (complete) or a limit is reached.  "complete"
  //! means every queued check ran on its current face; what a check could not settle (see
  //! unsettled()) is examined again whenever S has changed since, until nothing changes.
  [[nodiscard]] MeshStatus run();
  //! What the checks could not settle on the faces of the current Vor S (each face's latest
  //! check), and what report_unsettled() recorded, in a fixed order.  Empty after a complete run
  //! means every check of every current face came out clean.
  std::vector<Unsettled> unsettled() const;
  //! The final judgement: `run_status` unless it is complete and either something is unsettled
  //! (unsettled(), an unresolved region on a current Voronoi edge, a current Voronoi-edge record on
  //! which VorEdge fires, UnsettledReason::vor_edge_fires, or records that are not one per
  //! Delaunay triangle, UnsettledReason::record_count_mismatch) or the output has a defect
  //! (`output_defective`: Tri S|Σ is not a closed, consistently oriented 2-manifold); then
  //! uncertified.  Precondition: no insertion since the last run().
  Certification certify(MeshStatus run_status, bool output_defective) const;
  //! Silhouette's premise at p (silhouette.h, facets_clean): no facet of V_p is left unsettled by
  //! FacetContact or FacetCycle.  The driver passes it to every Silhouette check; since the steps
  //! run in order, the facet checks' queues are empty whenever Silhouette runs, so an unsettled
  //! facet is the only way the premise can fail.
  bool silhouette_premise(VertexId p) const;
  //! Records something left unsettled outside any face's check (e.g. a seed region).
  void report_unsettled(const Unsettled& u) { standing_unsettled_.push_back(u); }

  Delaunay& delaunay() { return del_; }
  const Delaunay& delaunay() const { return del_; }
  RestrictedDelaunay& restricted() { return restricted_; }
  SurfaceOracle& oracle() { return oracle_; }
  std::uint64_t seed() const { return seed_; }

  const std::vector<InsertionRecord>& insertion_log() const { return log_; }
  std::size_t insertions(CheckKind kind) const { return insertions_[static_cast<int>(kind)]; }
  std::size_t seeds_deleted() const { return seeds_deleted_; }
  std::size_t rejected_witnesses() const { return rejected_; }
  //! Checks run again with another generic choice after every witness was rejected.
  std::size_t generic_choice_retries() const { return retries_; }
  //! Opposite-sheet partners inserted (see above; not counted in insertions()).
  std::size_t opposite_sheet_partners() const { return partners_; }
  //! Seconds spent in each check (with the recording of its clean results), and the number of
  //! items each step examined.
  double seconds(CheckKind kind) const { return seconds_[static_cast<int>(kind)]; }
  std::size_t checks(CheckKind kind) const { return checks_[static_cast<int>(kind)]; }
  //! Seconds spent inserting: updating Del S and the records and facets of the changed faces.
  double seconds_insertion() const { return seconds_insertion_; }

  //! {seeds, vor_edge, …, size, (registered checks), seeds_deleted, rejected_witnesses,
  //! generic_choice_retries, opposite_sheet}
  nlohmann::json insertions_json() const;
  //! The termination floor: {value, topology_value, reached, witnesses_below (count), locations
  //! (the first tolerances::floor_locations_listed distinct ones)}.
  nlohmann::json floor_json() const;
  //! {vor_edge: n, …}: items examined per step, keyed by the row's name.
  nlohmann::json checks_json() const;
  //! {vor_edge: s, …}: seconds spent in each step's check, keyed by the row's name.
  nlohmann::json seconds_json() const;

 private:
  //! A queued simplex: a vertex {v, −1, −1}, an edge {p, q, −1} or a triangle {p, q, r}, sorted.
  using Simplex = DelaunayFace;
  //! Simplices taken smallest key first, each distinct simplex once however often it was queued
  //! (a binary heap; equal entries come out together and are merged).  The order depends only on
  //! what is queued, not on when, so re-queuing an item that waits changes nothing (the lemma's
  //! test relies on this).  The heap compares keys by detail::KeyLess, which orders them as
  //! std::array's operator< does (key_order.h).
  class WorkQueue {
   public:
    void push(const Simplex& s) {
      heap_.push_back(s);
      std::push_heap(heap_.begin(), heap_.end(), Later{});
    }
    Simplex pop() {
      const Simplex s = heap_.front();
      while (!heap_.empty() && detail::KeyEqual{}(heap_.front(), s)) {
        std::pop_heap(heap_.begin(), heap_.end(), Later{});
        heap_.pop_back();
      }
      return s;
    }
    bool empty() const { return heap_.empty(); }
    //! Entries waiting, counting repeats.
    std::size_t size() const { return heap_.size(); }

   private:
    //! The heap's order: a comes out after b (std::greater<> on the keys).
    struct Later {
      bool operator()(const Simplex& a, const Simplex& b) const { return detail::KeyLess{}(b, a); }
    };
    std::vector<Simplex> heap_;
  };
  //! One step of the table: a row of the registry and its queue.
  struct Step {
    const CheckInfo* row = nullptr;
    WorkQueue queue;
    bool enabled = true;  //!< topology rows from the start, geometry rows after enable_geometry()
  };

  static std::vector<Step> make_table();
  //! {row name: counts[row kind]} for the steps of the table.
  template <class T>
  nlohmann::json per_step(const std::vector<T>& counts) const;
  //! insert() for a witness or, with partner_of ≥ 0, for the opposite-sheet partner of that
  //! sample; the time goes to seconds_insertion().
  std::optional<VertexId> timed_insert(const Witness& witness, VertexId partner_of);
  std::optional<VertexId> insert_and_queue(const Witness& witness, VertexId partner_of);
  //! Enters the facets of the edges xq of x's closed star (RestrictedDelaunay::add_facets) and
  //! queues their checks, except for facets proved to miss Σ from the records and third vertices
  //! of the triangles xqr (`records`, prepare_star()'s answer for `star`); `neighbours` are the
  //! q, ascending.
  void prepare_new_edges(VertexId x, const std::vector<Delaunay::StarTriangle>& star,
                         const std::vector<RestrictedDelaunay::StarRecord>& records,
                         const std::vector<VertexId>& neighbours);
  //! Whether t / e is in Del S now: t exactly when it has a record (every current triangle has
  //! one here, and only those); e when it has a cached facet (see restricted_delaunay.h), else
  //! Del S is asked.
  bool current(const TriangleKey& t) const;
  bool current(const EdgeKey& e) const;
  //! Whether a queued vertex, edge or triangle is in Del S now.
  bool face_current(const Simplex& s) const;
  //! Inserts the first witness of `result` that is not rejected, and keeps the face's unsettled
  //! findings (a rejection of every witness included).  Returns whether a witness went in.
  bool settle(int step, const Simplex& item, CheckResult result);

  //! Inserts the opposite-sheet partner of the witness w just inserted (the last log entry), if
  //! it has one (see above).
  void insert_partner(const Witness& w);
  //! Queues again the unsettled faces still in Del S whose check predates the last change of S.
  //! Returns whether it queued any.
  bool requeue_unsettled();
  //! Queues f for the enabled rows of its FaceKind and rule `dirtied`; a triangle's `record`, if
  //! given, lets a row's may_fire skip it (under RecheckPolicy::new_faces), and an edge whose
  //! facet is proved to miss Σ skips the rows silent off the surface.
  void queue(const Simplex& f, FaceKind kind, Dirtied dirtied, const VoronoiEdgeRecord* record = nullptr,
             bool facet_misses_surface = false);
  //! Queues t for the rows of Dirtied::restricted_triangles if it is restricted, and for the
  //! new_faces rows if `new_face`.
  void queue_triangle(const TriangleKey& t, bool new_face);
  void queue_triangle(const TriangleKey& t, bool new_face, const VoronoiEdgeRecord& record);
  void queue_edge(const EdgeKey& e, bool facet_misses_surface = false);
  //! Queues the sample for the vertex rows: restricted_star ones, and also new_faces ones if
  //! `new_cell`.
  void queue_vertex(VertexId v, bool new_cell);
  //! Sets last_edge_step_ from the enabled steps.
  void set_last_edge_step();
  //! Queues every face among `sorted_vertices`, computing the record of each triangle.  Stops
  //! (leaving the rest unqueued and unrecorded) once limit_passed(): the run then ends at its next
  //! limit test, with the limit's status.
  void queue_everything_within(const std::vector<VertexId>& sorted_vertices);
  std::optional<MeshStatus> limit_reached(std::chrono::steady_clock::time_point now);

  SurfaceOracle& oracle_;
  std::uint64_t seed_;
  RefinementLimits limits_;
  RunLimits run_limits_;  //!< limits_'s deadline and interrupt, for the loops outside run()
  RecheckPolicy policy_;
  Delaunay del_;
  RestrictedDelaunay restricted_;
  std::vector<Step> steps_;
  detail::ParallelFor parallel_;
  double lambda_ = 0;
  std::optional<double> size_bound_;
  std::optional<double> max_distance_;
  const FlowDistance* flow_distance_ = nullptr;
  bool geometry_enabled_ = false;
  int last_edge_step_ = -1;  //!< the last enabled edge row (it releases the facets), or −1
  std::vector<InsertionRecord> log_;
  //! Indexed by CheckKind.
  std::vector<std::size_t> insertions_, checks_;
  std::vector<double> seconds_;
  double seconds_insertion_ = 0;
  std::size_t seeds_deleted_ = 0, rejected_ = 0, retries_ = 0, partners_ = 0;
  //! Insertions and deletions so far: a face checked at this count has seen the current S.
  std::size_t changes() const { return log_.size() + seeds_deleted_; }
  struct UnsettledFace {
    std::vector<Unsettled> what;
    std::size_t changes = 0;  //!< changes() when the face was checked
  };
  std::map<std::pair<int, Simplex>, UnsettledFace> unsettled_;
  std::vector<Unsettled> standing_unsettled_;
  //! The floor of min_spacing for a witness of this kind, by the phase of its row in the table.
  double floor_for(CheckKind kind) const;
  std::size_t floor_hits_ = 0;           //!< witnesses not inserted because of min_spacing
  std::vector<Vec3> floor_locations_;    //!< the first of them
  std::chrono::steady_clock::time_point start_;  //!< limits_.start, or the construction
  std::chrono::steady_clock::time_point last_progress_;
};

}  // namespace delmesh
