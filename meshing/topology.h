#pragma once
//! \file topology.h
//! Topology(S) (§5.4): repeat steps (a)–(e) — (a) VorEdge on every Voronoi edge, (b) FacetContact
//! on every facet, (c) TopoDisk at every sample, (d) FacetCycle on every facet, (e) Silhouette at
//! every sample — inserting the first witness found and starting again at (a), until no check
//! returns a witness.  Corollary 5.1: on return Tri S|Σ is homeomorphic to Σ.
//!
//! Local work queues (the paper's remark in §6.2, and issue 4): after inserting x, the Voronoi
//! faces that changed are those dual to the Delaunay simplices all of whose vertices lie in
//! {x} ∪ N(x) (a new tetrahedron pqrx is needed to change the edge of pqr, a new triangle pqx to
//! change the facet of pq); after removing p, those with all vertices in N(p).  Exactly these
//! are re-queued and their cached results forgotten; every other simplex stays clean.  Each step
//! runs only when the queues of all earlier steps are empty, so the order of the paper holds:
//! a witness from any step sends the loop back to (a).
//!
//! Witnesses within tolerances::duplicate_sample_relative_distance of an existing sample are not
//! inserted (counted as `rejected_witnesses`), so the loop cannot cycle on a degenerate answer.

#include <array>
#include <chrono>
#include <functional>
#include <optional>
#include <ostream>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "meshing/delaunay.h"
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
};

enum class TopologyStatus { complete, point_limit, time_limit };
std::ostream& operator<<(std::ostream& out, TopologyStatus status);

struct TopologyLimits {
  std::size_t max_points = 200000;
  //! Absolute deadline; none if empty.
  std::optional<std::chrono::steady_clock::time_point> deadline;
  std::function<void(const std::string&)> progress;
};

class Topology {
 public:
  Topology(SurfaceOracle& oracle, std::uint64_t seed, TopologyLimits limits);

  //! Inserts the witness into S (unless it duplicates a sample), logs it, dirties the changed
  //! simplices.  Returns the new id, or nothing if rejected.
  std::optional<VertexId> insert(const Witness& witness);
  //! Deletes p from S (a seed, Lemma 5.4) and dirties the simplices around its former neighbours.
  void remove(VertexId p);
  //! Marks every simplex dirty (all of Vor S is checked again).
  void dirty_all();

  //! Topology(S) with the local queues.  Returns complete when no check has a witness.
  [[nodiscard]] TopologyStatus run();

  Delaunay& delaunay() { return del_; }
  const Delaunay& delaunay() const { return del_; }
  RestrictedDelaunay& restricted() { return restricted_; }
  SurfaceOracle& oracle() { return oracle_; }
  std::uint64_t seed() const { return seed_; }

  const std::vector<InsertionRecord>& insertion_log() const { return log_; }
  std::size_t insertions(CheckKind kind) const { return insertions_[static_cast<int>(kind)]; }
  std::size_t seeds_deleted() const { return seeds_deleted_; }
  std::size_t rejected_witnesses() const { return rejected_; }
  //! Seconds spent in each check (vor_edge … silhouette), and the triangles dirtied since
  //! the last take_changed_triangles() (for Quality / Smooth / size control).
  double seconds(CheckKind kind) const { return seconds_[static_cast<int>(kind)]; }
  void add_seconds(CheckKind kind, double s) { seconds_[static_cast<int>(kind)] += s; }
  std::set<TriangleKey> take_changed_triangles();
  //! Whether a limit is reached (points or time); reports progress when due.
  std::optional<TopologyStatus> limit_reached(const std::string& phase);

  nlohmann::json insertions_json() const;

 private:
  void dirty(const std::vector<VertexId>& sorted_vertices);

  SurfaceOracle& oracle_;
  std::uint64_t seed_;
  TopologyLimits limits_;
  Delaunay del_;
  RestrictedDelaunay restricted_;
  std::set<TriangleKey> queue_a_;
  std::set<EdgeKey> queue_b_, queue_d_;
  std::set<VertexId> queue_c_, queue_e_;
  std::set<TriangleKey> changed_;
  std::vector<InsertionRecord> log_;
  std::array<std::size_t, check_kind_count> insertions_{};
  std::array<double, check_kind_count> seconds_{};
  std::size_t seeds_deleted_ = 0, rejected_ = 0;
  std::chrono::steady_clock::time_point last_progress_;
};

}  // namespace delmesh
