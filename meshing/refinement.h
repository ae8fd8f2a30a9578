#pragma once
//! \file refinement.h
//! The refinement driver of DelMesh: Topology(S) (§5.4, steps (a)–(e)), Quality and Smooth
//! (§6.2, steps 2–3) and the optional size bound, as one loop over an ordered table of steps.
//! The table is the check registry (meshing/check_registry.h), one step per row, with the paper's
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
//! **Lemma (recheck only new faces).**  Let x be inserted into S (no deletion), Del S of
//! dimension 3 before and after.  Then:
//!  1. (Bowyer–Watson) the Delaunay simplices that do not contain x and survive are exactly those
//!     not strictly inside the cavity; the dual Voronoi face of a surviving simplex σ is
//!     V(σ) ∩ {y : |y − s| ≤ |y − x|} for any vertex s of σ, a subset of the old face in the same
//!     affine hull (equal unless σ is on the cavity boundary).
//!  2. Each topology check's witness set W(f) of a face f is monotone: f′ ⊆ f ⇒ W(f′) ⊆ W(f)
//!     restricted to f′, provided the check's generic directions depend only on the face's
//!     defining sites.  VorEdge: tangencies of Σ with e′ ⊆ e, and |e′ ∩ Σ| ≤ |e ∩ Σ| ≤ 1.
//!     FacetContact: contacts of Σ with F′ ⊆ F.  FacetCycle: the critical points of Σ ∩ F′ in
//!     direction d are those of Σ ∩ F lying in F′, and ℓ_y ∩ Σ ∩ F′ ⊆ ℓ_y ∩ Σ ∩ F (d is seeded by
//!     the edge's ids).  Silhouette: J_{n_p} ∩ V′_p ⊆ J_{n_p} ∩ V_p = ∅ (n_p, d′ depend on p only),
//!     and the facets of V′_p are subsets of V_p.
//!  3. Hence a face whose check found no witness still has none, and only the faces dual to
//!     simplices containing x need their topology checks: VorEdge on the triangles xqr,
//!     FacetContact and FacetCycle on the edges xq, Silhouette on V_x.  Of these, an edge xq
//!     whose facet F is proved to miss Σ (RestrictedDelaunay::facet_misses_surface, from the
//!     records and third vertices of the triangles xqr, and the box) needs no FacetContact or
//!     FacetCycle: both look for points of Σ ∩ F (rows marked silent_off_surface).
//!  4. TopoDisk(p) is a function of the restricted star of p (and, for its witness, of the
//!     crossings of p's triangles): it is re-queued for x and for the vertices of every triangle
//!     that entered or left Tri S|Σ (new, destroyed, or shrunk with a lost crossing).  Quality,
//!     size and Smooth read a triangle's restricted status and dual point (Smooth also its
//!     neighbours across its edges, which are then re-queued themselves): they are re-queued for
//!     the new triangles and the shrunk triangles whose status or dual point changed.  Every
//!     such record is computed at once; VorEdge is a function of the record alone, so a new
//!     triangle waits for it only if its record has a witness (the row's may_fire), and Quality,
//!     size and Smooth wait only for restricted triangles.
//! The faces in the lemma are those of Vor S.  Each computed face holds its exact face: the
//! half-spaces are the exact bisectors moved outwards only, and the boxes built from Voronoi
//! vertices are widened by their certified error radii (voronoi_geometry.h), so a check that
//! found no witness in the computed F found none in the exact F ⊇ F′.  The computed F′ need not
//! lie in the computed F (its cuts hold the new circumcentres, whose errors no constant margin
//! bounds for slivers), and nothing relies on it.  A Voronoi edge as the faces see it has
//! connectors from its line to its shared vertices (restricted_delaunay.h): e′'s connector to the
//! new vertex is not part of e, so a kept record of e′ is checked on it (prepare_star()).
//! In the registry's terms: parts 1–3 are Dirtied::new_faces, part 4 is Dirtied::restricted_star
//! (TopoDisk) and Dirtied::restricted_triangles (Quality, Smooth).
//! Conditions: the checks' generic choices depend only on the face's sites (so it is for the
//! seeded frames of restricted_delaunay.h and silhouette.h, and for the in-plane direction of the
//! facet certificate), and only a clean result is kept (an undecided region is a candidate
//! witness, not a clean result; a face that gave a witness is queued again).  A deletion (seed deletion,
//! Lemma 5.4) grows faces, so after deleting p every face dual to a simplex within N(p) is
//! checked again (a kept Silhouette proof of a cell V_q, q ∈ N(p), is completed on V_q ∩ old V_p
//! only: V_q grew into the old V_p and nowhere else; RestrictedDelaunay::invalidate()); so is
//! everything when the change is not local (dimension < 3).
//! RecheckPolicy::changed_faces re-queues the shrunk faces too, for the new_faces and
//! restricted_star rows (for testing the lemma).
//!
//! Threads.  Each insertion's new and shrunk triangles get their records on several threads
//! (RestrictedDelaunay::prepare_star), alongside the new vertex's cell certificate: each item is
//! computed on its own from the current Del S and installed in a fixed order, so the run does the
//! same work and writes the same mesh for every thread count.  The checks themselves run one at a
//! time, in the table's order.  The facet of a new edge, and its section certificate, are
//! computed when its first check asks (RestrictedDelaunay::add_facets), and kept until the last
//! enabled edge row finds the edge clean.
//!
//! Witnesses within tolerances::duplicate_sample_relative_distance of an existing sample are not
//! inserted (counted as `rejected_witnesses`), so the loop cannot cycle on a degenerate answer.
//! A check lists its witnesses in order of preference; when the first is rejected the next is
//! tried.  When all are, a row with a generic choice (CheckInfo::generic_choice: FacetCycle,
//! Silhouette) is run on the face again at once with the next alternative choice
//! (CheckContext::attempt), up to tolerances::generic_choice_attempts choices in all (counted as
//! `generic_choice_retries`); a clean answer with any choice settles the face (by the lemma above
//! it stays clean as the face shrinks, for that choice).  When no choice gives a witness that can
//! be inserted, the face is left unsettled (rejected_witness).
//!
//! **Opposite-sheet partners.**  Where two sheets of Σ (two components, or the two sides of a
//! thin part) are closer than the sample spacing, the Voronoi cells of one sheet's samples reach
//! the other sheet, and the witnesses of VorEdge and TopoDisk, one at a time, drive the spacing
//! down to the local gap: about π/g points for two unit spheres a gap g apart (Quality's, which
//! break the pairs, then do the same).  A sample whose partner on the other sheet lies across the
//! gap, near its mirror image, keeps its cell on its own side whatever the spacing.  So after a
//! witness w of any row is inserted at distance d from its nearest sample, SurfaceLine searches
//! the normal line of Σ at w within tolerances::opposite_sheet_reach·d of w, and the nearest
//! other point y of Σ found there (if the search left nothing undecided) is inserted as well,
//! provided |⟨n(w), n(y)⟩| ≥
//! c = tolerances::opposite_sheet_min_cosine and every sample is at least
//! s·|w − y| from y, s = tolerances::opposite_sheet_spacing.  y is logged with partner_of = w
//! and counted as `opposite_sheet`, not as a witness of the check.  The search is skipped when
//! three interval evaluations show that it has no y to find: ⟨∇E, n⟩ of one sign σ on the
//! segment (SurfaceOracle::gradient_sign), so that E(w + t n) is strictly monotone in t there and
//! has at most one zero, and E(w − δ n), E(w + δ n) of signs −σ and σ, δ the distance below which
//! a root counts as w's own, so that its one zero is w's own.
//!  - The guarantee does not change: y is a point of Σ (a certified root of SurfaceLine), and
//!    the output theorem asks only that every check be clean on the final S, which the loop
//!    establishes for whatever S it ends with.
//!  - Termination does not change: lfs(y) ≤ |w − y|/(2c).  Proof: let ν be the unit normal at y
//!    on the side of w, so ⟨w − y, ν⟩ = |w − y|·|cos φ| ≥ c|w − y| (w − y lies along n(w)).  The
//!    ball tangent to Σ at y with centre y + rν holds w in its interior once
//!    r > |w − y|²/(2⟨w − y, ν⟩), so the largest such ball with no point of Σ inside has
//!    r ≤ |w − y|/(2c), and its centre is a point of the medial axis.  Hence y is at least
//!    s·|w − y| ≥ 2cs·lfs(y) = lfs(y)/2 from every sample (with c = s = 1/2), and from the nearest
//!    sample p at least lfs(p)/3 (lfs is 1-Lipschitz): the packing argument of Lemma 5.1 bounds
//!    these insertions as it bounds the witnesses'.
//!
//! Unsettled faces.  A check that leaves something unsettled (witness.h: UnsettledReason) keeps
//! its face on a list.  When every queue is empty, each face on the list that is still in Del S
//! is checked again if S has changed since its check; the run ends when no such face remains.
//! unsettled() then lists what the current faces' latest checks could not settle: the caller
//! (del_mesh) reports the run as uncertified unless it is empty.

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
#include "meshing/check_registry.h"
#include "meshing/delaunay.h"
#include "meshing/detail/key_order.h"
#include "meshing/mesh_status.h"
#include "meshing/restricted_delaunay.h"
#include "meshing/surface_oracle.h"
#include "meshing/witness.h"

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
  std::function<void(const std::string&)> progress;
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
  std::chrono::steady_clock::time_point last_progress_;
};

}  // namespace delmesh
