#include "meshing/driver/refinement.h"

#include <algorithm>
#include <sstream>
#include <tuple>

#include "common/errors.h"
#include "common/tolerances.h"
#include "meshing/core/detail/id_marks.h"
#include "meshing/core/detail/key_order.h"
#include "meshing/core/detail/vec3.h"
#include "meshing/core/theorem_bounds.h"

namespace delmesh {

namespace {

EdgeKey as_edge(const std::array<VertexId, 3>& s) { return {s[0], s[1]}; }

// The log's record of an insertion of witness w (the ids and the nearest sample come later).
InsertionRecord insertion_record(const Witness& w, VertexId partner_of) {
  InsertionRecord record;
  record.point = w.point;
  record.kind = w.kind;
  record.from_undecided = w.from_undecided;
  record.partner_of = partner_of;
  return record;
}

// Whether a witness at `point` may be inserted, from its nearest sample: refused within the
// duplicate distance (counted as rejected) and below the termination floor (recorded, not
// inserted).  `refused` says whether it refused.
struct InsertionFilter {
  double duplicate_distance, floor;
  const Vec3& point;
  std::size_t& rejected;
  std::size_t& floor_hits;
  std::vector<Vec3>& floor_locations;
  bool refused = false;

  bool accepts(const Nearest& nearest) {
    if (nearest.distance <= duplicate_distance) {
      ++rejected;
      refused = true;
    } else if (nearest.distance < floor) {
      // The termination floor: recorded, not inserted.
      ++floor_hits;
      if (floor_locations.size() < tolerances::floor_locations_listed &&
          std::find(floor_locations.begin(), floor_locations.end(), point) == floor_locations.end())
        floor_locations.push_back(point);
      refused = true;
    }
    return !refused;
  }
};

// x's neighbours q in its closed star, ascending: the edges xq of the star.
std::vector<VertexId> star_neighbours(VertexId x, const std::vector<Delaunay::StarTriangle>& star) {
  std::vector<VertexId> neighbours;
  neighbours.reserve(2 * star.size());
  for (const auto& s : star)
    if (s.contains_vertex)
      for (VertexId v : s.key)
        if (v != x) neighbours.push_back(v);
  detail::sort_distinct_ids(neighbours);
  return neighbours;
}

// The records of x's star brought up to date (RestrictedDelaunay::prepare_star()), and with the
// geometry checks V_x's certificate, towards the slope that certifies the facets of all the new
// edges xq (they lie in V_x; facet_section_certified() takes those it certifies from it),
// alongside the records: neither reads what the other writes (restricted_delaunay.h), and V_x is
// built from its Delaunay cells `cells`, read with the star, without a walk of Del S on the other
// thread.  Not while only the topology checks run: their cells are large and their certificates
// often fail, and a failure here would be paid again by Silhouette.
std::vector<RestrictedDelaunay::StarRecord> prepare_star_records(
    RestrictedDelaunay& restricted, const detail::ParallelFor& parallel, bool geometry_enabled, VertexId x,
    const std::vector<Delaunay::StarTriangle>& star, const std::vector<std::array<VertexId, 4>>& cells,
    const std::vector<VertexId>& neighbours) {
  std::vector<RestrictedDelaunay::StarRecord> records;
  auto prepare_records = [&] { records = restricted.prepare_star(star, parallel); };
  if (geometry_enabled)
    parallel.invoke([&] { restricted.certify_new_cell(x, cells, neighbours); }, prepare_records);
  else
    prepare_records();
  return records;
}

}  // namespace

std::vector<Refinement::Step> Refinement::make_table() {
  // The geometry rows start disabled (enable_geometry()).
  std::vector<Step> table;
  for (const CheckInfo& row : check_registry()) table.push_back({&row, {}, row.phase == CheckPhase::topology});
  return table;
}

// Every current triangle has a record whenever the loop asks (the constructor's promise to
// RestrictedDelaunay: insert() and remove() record each new or changed triangle before they
// return), and only current triangles have one (cached_record()'s invariant), so the record
// decides without looking for the triangle in Del S.
bool Refinement::current(const TriangleKey& t) const { return restricted_.cached_record(t) != nullptr; }

bool Refinement::current(const EdgeKey& e) const { return restricted_.has_facet(e) || del_.is_edge(e); }

bool Refinement::face_current(const Simplex& s) const {
  if (s[1] < 0) return del_.contains(s[0]);
  if (s[2] < 0) return current(as_edge(s));
  return current(TriangleKey(s));
}

Refinement::Refinement(SurfaceOracle& oracle, std::uint64_t seed, RefinementLimits limits, RecheckPolicy policy,
                       int threads, bool parallel_every_batch)
    : oracle_(oracle), seed_(seed), limits_(std::move(limits)), run_limits_(limits_.deadline, limits_.interrupt),
      policy_(policy), restricted_(del_, oracle, seed),
      steps_(make_table()), parallel_(threads, parallel_every_batch), insertions_(check_kind_count()),
      checks_(check_kind_count()), seconds_(check_kind_count()),
      start_(limits_.start.value_or(std::chrono::steady_clock::now())), last_progress_(std::chrono::steady_clock::now()) {
  // insert() and remove() compute the record of every new or changed triangle at once.
  restricted_.assume_every_triangle_recorded();
  set_last_edge_step();
}

void Refinement::set_last_edge_step() {
  last_edge_step_ = -1;
  for (std::size_t k = 0; k < steps_.size(); ++k)
    if (steps_[k].enabled && steps_[k].row->face == FaceKind::edge) last_edge_step_ = static_cast<int>(k);
}

void Refinement::enable_geometry(double lambda, std::optional<double> size_bound, std::optional<double> max_distance) {
  if (!(lambda > 0 && lambda < alpha_lambda_bound)) throw PreconditionViolation("enable_geometry: lambda out of (0, 1/3)");
  if (size_bound && !(*size_bound > 0)) throw PreconditionViolation("enable_geometry: size bound not positive");
  if (max_distance && !(*max_distance > 0 && std::isfinite(*max_distance)))
    throw PreconditionViolation("enable_geometry: distance bound not positive");
  if (max_distance && !oracle_.flow_distance())
    throw PreconditionViolation("enable_geometry: the oracle bounds no distance to its surface");
  lambda_ = lambda;
  size_bound_ = size_bound;
  max_distance_ = max_distance;
  flow_distance_ = max_distance ? oracle_.flow_distance() : nullptr;
  geometry_enabled_ = true;
  for (auto& step : steps_)
    if (step.row->phase == CheckPhase::geometry) step.enabled = !step.row->runs_at || step.row->runs_at(lambda);
  set_last_edge_step();
  // Every current face a geometry row examines: for restricted_triangles rows the restricted
  // triangles, for the others every face of their kind.
  std::optional<std::vector<TriangleKey>> restricted_triangles, all_triangles;
  for (auto& step : steps_) {
    const CheckInfo& row = *step.row;
    if (row.phase != CheckPhase::geometry || !step.enabled) continue;
    if (row.face == FaceKind::triangle) {
      auto& list = row.dirtied == Dirtied::restricted_triangles ? restricted_triangles : all_triangles;
      if (!list) list = row.dirtied == Dirtied::restricted_triangles ? restricted_.triangles() : del_.triangles();
      for (const auto& t : *list) step.queue.push(t);
    } else {
      for (VertexId v : del_.vertices()) {
        if (row.face == FaceKind::vertex) step.queue.push({v, -1, -1});
        else
          for (VertexId w : del_.neighbours(v))
            if (v < w) step.queue.push({v, w, -1});
      }
    }
  }
}

void Refinement::queue(const Simplex& f, FaceKind kind, Dirtied dirtied, const VoronoiEdgeRecord* record,
                       bool facet_misses_surface) {
  for (auto& step : steps_) {
    const CheckInfo& row = *step.row;
    if (!step.enabled || row.face != kind || row.dirtied != dirtied) continue;
    if (record && row.may_fire && policy_ == RecheckPolicy::new_faces && !row.may_fire(*record)) continue;
    if (facet_misses_surface && row.silent_off_surface) continue;
    step.queue.push(f);
  }
}

void Refinement::queue_triangle(const TriangleKey& t, bool new_face) {
  queue_triangle(t, new_face, restricted_.voronoi_edge_record(t));
}

void Refinement::queue_triangle(const TriangleKey& t, bool new_face, const VoronoiEdgeRecord& r) {
  // The record is computed eagerly (the checks would compute it anyway).  A row that is a
  // function of the record alone (VorEdge) is skipped when its may_fire says it cannot fire;
  // restricted_triangles rows (Quality, size, Smooth) only look at restricted triangles.
  if (new_face) queue(t, FaceKind::triangle, Dirtied::new_faces, &r);
  if (r.restricted) queue(t, FaceKind::triangle, Dirtied::restricted_triangles);
}

void Refinement::queue_edge(const EdgeKey& e, bool facet_misses_surface) {
  queue({e[0], e[1], -1}, FaceKind::edge, Dirtied::new_faces, nullptr, facet_misses_surface);
}

void Refinement::queue_vertex(VertexId v, bool new_cell) {
  queue({v, -1, -1}, FaceKind::vertex, Dirtied::restricted_star);
  if (new_cell) queue({v, -1, -1}, FaceKind::vertex, Dirtied::new_faces);
}

void Refinement::queue_everything_within(const std::vector<VertexId>& vs) {
  auto in = [&](VertexId v) { return std::binary_search(vs.begin(), vs.end(), v); };
  for (VertexId v : vs) {
    if (!del_.contains(v)) continue;
    for (const auto& t : del_.incident_triangles(v))
      if (t[0] == v && in(t[1]) && in(t[2])) {
        // A record is a solve: the clock reading costs nothing beside it.
        if (limit_passed()) return;
        queue_triangle(t, true);
      }
    for (VertexId w : del_.neighbours(v))
      if (v < w && in(w)) queue_edge({v, w});
    queue_vertex(v, true);
  }
}

std::optional<VertexId> Refinement::insert(const Witness& w) { return timed_insert(w, -1); }

std::optional<VertexId> Refinement::timed_insert(const Witness& w, VertexId partner_of) {
  const auto start = std::chrono::steady_clock::now();
  const auto id = insert_and_queue(w, partner_of);
  seconds_insertion_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return id;
}

std::optional<VertexId> Refinement::insert_and_queue(const Witness& w, VertexId partner_of) {
  InsertionRecord record = insertion_record(w, partner_of);
  // The nearest sample comes with the insertion's own search (Delaunay::insert_tracking()); a
  // point too close to it is refused before Del S changes.
  InsertionFilter filter{limits_.duplicate_relative_distance * oracle_.diagonal(), floor_for(w.kind), w.point,
                         rejected_, floor_hits_, floor_locations_};
  const NearestTest accept = [&filter](const Nearest& nearest) { return filter.accepts(nearest); };
  auto [id, change, nearest] = del_.insert_tracking(w.point, w.kind == CheckKind::seed, w.measured_from, accept);
  record.nearest = nearest.id;
  record.nearest_distance = nearest.distance;
  if (!id) {
    if (!filter.refused) ++rejected_;
    return std::nullopt;
  }
  const VertexId x = *id;
  record.id = x;
  log_.push_back(record);
  ++(partner_of < 0 ? insertions_[static_cast<int>(w.kind)] : partners_);
  if (!change.local) {
    // Del S of dimension < 3 before or after: every face may have changed (a few points only).
    restricted_.shrink(change);
    queue_everything_within(del_.vertices());
    return id;
  }
  // TopoDisk(p) depends only on the restricted star of p: it is queued for x and for the
  // vertices of every triangle that entered or left Tri S|Σ (a triangle never solved counts).
  std::vector<VertexId> star_changed{x};
  star_changed.reserve(1 + 3 * change.destroyed_triangles.size());
  auto star_change = [&](const TriangleKey& t) { star_changed.insert(star_changed.end(), t.begin(), t.end()); };
  for (const auto& t : restricted_.forget_destroyed(change)) star_change(t);
  // Shrunk faces keep their clean results (the lemma in refinement.h); their records are brought
  // up to date now, and a triangle whose dual point changed goes to Quality and Smooth again.
  std::vector<std::array<VertexId, 4>> cells;  // x's Delaunay cells, read in the same walk
  const auto star = del_.closed_star(x, geometry_enabled_ ? &cells : nullptr);
  star_changed.reserve(star_changed.size() + 3 * star.size());  // at most three per star triangle
  const std::vector<VertexId> neighbours = star_neighbours(x, star);
  const std::vector<RestrictedDelaunay::StarRecord> records =
      prepare_star_records(restricted_, parallel_, geometry_enabled_, x, star, cells, neighbours);
  for (std::size_t i = 0; i < star.size(); ++i) {
    const auto& t = star[i].key;
    const VoronoiEdgeRecord& r = *records[i].record;
    const bool contains_x = star[i].contains_vertex;
    if (contains_x) {
      // The faces dual to simplices containing x are new: all their checks run.
      if (r.restricted) star_change(t);
      queue_triangle(t, true, r);
      continue;
    }
    const auto& before = records[i];
    const bool status_changed = !before.had_record || before.was_restricted != r.restricted;
    if (status_changed) star_change(t);
    // A record solved again is a new answer, not a subset of the old one: VorEdge runs on it as
    // on a new face (its may_fire decides whether it is queued).
    if (before.solved)
      queue_triangle(t, true, r);
    else if (status_changed || before.old_dual_point != r.dual_point())
      queue_triangle(t, policy_ == RecheckPolicy::changed_faces, r);
    else if (policy_ == RecheckPolicy::changed_faces)
      queue(t, FaceKind::triangle, Dirtied::new_faces);
  }
  prepare_new_edges(x, star, records, neighbours);
  // The queues' order does not depend on the order of the pushes (WorkQueue): repeats go, the
  // order stays.
  detail::drop_repeated_ids(star_changed);
  for (VertexId v : star_changed) queue_vertex(v, v == x);
  if (policy_ == RecheckPolicy::changed_faces) {
    for (const auto& e : change.shrunk_edges) queue_edge(e);
    for (VertexId v : neighbours) queue_vertex(v, true);
  }
  return id;
}

void Refinement::prepare_new_edges(VertexId x, const std::vector<Delaunay::StarTriangle>& star,
                                   const std::vector<RestrictedDelaunay::StarRecord>& records,
                                   const std::vector<VertexId>& neighbours) {
  // The facet of a new edge xq is cut by the third vertices r of the triangles xqr, all of which
  // are in the star with their apexes, and bounded by their Voronoi edges, whose records are up
  // to date.  The pairs (q, r) for each triangle xqr, both ways, are counted into one bucket per
  // neighbour q (facet_misses_surface() reads a ring in any order).
  // The bucket of each neighbour, by id (the entries of other ids are stale, and never read).
  thread_local std::vector<std::uint32_t> bucket_of;
  if (!neighbours.empty() && static_cast<std::size_t>(neighbours.back()) >= bucket_of.size())
    bucket_of.resize(2 * static_cast<std::size_t>(neighbours.back()) + 1);
  for (std::size_t k = 0; k < neighbours.size(); ++k) bucket_of[neighbours[k]] = static_cast<std::uint32_t>(k);
  auto slot = [&](VertexId q) -> std::size_t { return bucket_of[q]; };
  struct RingEntry {
    VertexId r;
    std::size_t index;  // of xqr in the star
  };
  // The buckets' bounds and contents, kept per thread between insertions.
  thread_local std::vector<std::size_t> first, fill;
  thread_local std::vector<RingEntry> ring;
  first.assign(neighbours.size() + 1, 0);
  for (const auto& s : star)
    if (s.contains_vertex)
      for (VertexId v : s.key)
        if (v != x) ++first[slot(v) + 1];
  for (std::size_t k = 0; k < neighbours.size(); ++k) first[k + 1] += first[k];
  ring.resize(first.back());
  {
    fill.assign(first.begin(), first.end() - 1);
    for (std::size_t i = 0; i < star.size(); ++i) {
      const auto& s = star[i];
      if (!s.contains_vertex) continue;
      VertexId q = -1, r = -1;
      for (VertexId v : s.key)
        if (v != x) (q < 0 ? q : r) = v;
      ring[fill[slot(q)]++] = {r, i};
      ring[fill[slot(r)]++] = {q, i};
    }
  }
  std::vector<EdgeKey> new_edges;
  new_edges.reserve(neighbours.size());
  thread_local std::vector<Delaunay::RingTriangle> thirds;
  thread_local std::vector<const VoronoiEdgeRecord*> boundary;
  for (std::size_t k = 0; k < neighbours.size(); ++k) {
    const VertexId q = neighbours[k];
    thirds.clear();
    boundary.clear();
    for (std::size_t i = first[k]; i < first[k + 1]; ++i) {
      thirds.push_back({ring[i].r, star[ring[i].index].apexes});
      boundary.push_back(records[ring[i].index].record);
    }
    // A facet proved to miss Σ is not built, and the rows silent off Σ (FacetContact,
    // FacetCycle) do not examine it; its geometry is built on demand if another check asks.
    const EdgeKey xq = make_edge_key(x, q);
    if (policy_ == RecheckPolicy::new_faces && restricted_.facet_misses_surface(xq, thirds, boundary)) {
      queue_edge(xq, true);
      continue;
    }
    new_edges.push_back(xq);
  }
  restricted_.add_facets(new_edges);
  for (const EdgeKey& e : new_edges) queue_edge(e);
}

void Refinement::remove(VertexId p) {
  // The star of p goes; the hole is re-triangulated among N(p), whose faces grow.
  const auto star = del_.incident_triangles(p);
  const auto edges = del_.incident_edges(p);
  const std::vector<VertexId> around = del_.neighbours(p);
  // The cells around p grow into V_p only: their kept proofs are completed there (invalidate()).
  const VoronoiCell cell = voronoi_cell(del_, p, oracle_.clip_box());
  del_.remove(p);
  ++seeds_deleted_;
  restricted_.forget(star, edges);
  restricted_.forget_cell(p);
  restricted_.invalidate(around, cell.valid ? &cell.domain : nullptr);
  queue_everything_within(around);
}

std::optional<MeshStatus> Refinement::limit_reached(std::chrono::steady_clock::time_point now) {
  if (limits_.progress &&
      std::chrono::duration<double>(now - last_progress_).count() >= tolerances::progress_interval_seconds) {
    last_progress_ = now;
    ProgressReport report;
    report.phase = geometry_enabled_ ? ProgressPhase::geometry : ProgressPhase::topology;
    report.points = del_.size();
    for (const auto& step : steps_)
      if (step.enabled) report.queued.push_back({step.row->name, step.queue.size()});
    report.elapsed_seconds = std::chrono::duration<double>(now - start_).count();
    limits_.progress(report);
  }
  if (limits_.interrupt && limits_.interrupt->load(std::memory_order_relaxed)) return MeshStatus::interrupted;
  if (del_.size() >= limits_.max_points) return MeshStatus::point_limit;
  if (limits_.deadline && now >= *limits_.deadline) return MeshStatus::time_limit;
  return std::nullopt;
}

MeshStatus Refinement::run() {
  // The clock is read when a run of checks of one row ends (another row's check comes, or a
  // check found a witness), and after every tolerances::checks_per_clock_reading checks of a
  // run: the time since the previous reading goes to that row, whose checks (with the loop's
  // bookkeeping between them, and the recording of their clean results) filled it, as a
  // reading after every check would give.  The time limit is tested against the latest reading.
  auto now = std::chrono::steady_clock::now();
  int timed_kind = -1;       // the row of the checks since `now`
  std::size_t untimed = 0;   // how many
  auto read_clock = [&] {
    const auto t = std::chrono::steady_clock::now();
    if (untimed > 0) seconds_[timed_kind] += std::chrono::duration<double>(t - now).count();
    now = t;
    untimed = 0;
  };
  while (true) {
    if (auto status = limit_reached(now)) {
      read_clock();
      return *status;
    }
    auto step = std::find_if(steps_.begin(), steps_.end(),
                             [](const Step& s) { return s.enabled && !s.queue.empty(); });
    if (step == steps_.end()) {
      if (requeue_unsettled()) continue;
      read_clock();
      return MeshStatus::complete;
    }
    const Simplex item = step->queue.pop();
    const int index = static_cast<int>(step - steps_.begin());
    const CheckInfo& row = *step->row;
    const auto k = static_cast<int>(row.kind);
    if (untimed > 0 && (k != timed_kind || untimed >= tolerances::checks_per_clock_reading)) read_clock();
    // A face no longer in Del S has nothing to check.  A row with a generic choice whose witnesses
    // were all rejected runs again with the next choice (S is unchanged: the face is still current).
    const bool current_face = face_current(item);
    // Silhouette's facet shortcut rests on FacetContact and FacetCycle being clean on every facet
    // of V_p.  Their queues come first and are empty when Silhouette's turn comes, so only a facet
    // left unsettled can break the premise.
    CheckContext context{restricted_, row.kind, lambda_, size_bound_, max_distance_, flow_distance_,
                         /*cell_faces_clean=*/row.kind != CheckKind::silhouette || silhouette_premise(item[0])};
    bool inserted = false, retry = false;
    do {
      CheckResult result;
      if (current_face) {
        result = row.check(context, item);
        // The last edge check of the edge: its facet's geometry is not kept.
        if (index == last_edge_step_ && result.clean()) restricted_.release_facet(as_edge(item));
      }
      ++checks_[k];
      timed_kind = k;
      ++untimed;
      const bool had_witness = !result.witnesses.empty();
      if (had_witness) read_clock();  // the insertion's time is its own
      inserted = settle(index, item, std::move(result));
      retry = !inserted && had_witness && row.generic_choice &&
              ++context.attempt < tolerances::generic_choice_attempts;
      if (retry) ++retries_;
    } while (retry);
    if (inserted) {
      // A face that gave a witness is not clean: it is examined again once the witness is in S
      // (e.g. V_p keeps other points of J_{n_p} after the furthest one is inserted).
      step->queue.push(item);
      now = std::chrono::steady_clock::now();
    }
  }
}

bool Refinement::settle(int step, const Simplex& item, CheckResult result) {
  // The paper's witness first; a witness that duplicates a sample gives way to the next one.
  bool inserted = false;
  for (const auto& w : result.witnesses)
    if (insert(w)) {
      inserted = true;
      insert_partner(w);
      break;
    }
  if (!inserted && !result.witnesses.empty()) {
    const Witness& w = result.witnesses.front();
    result.unsettled.push_back({w.kind, UnsettledReason::rejected_witness, w.point});
  }
  const auto key = std::make_pair(step, item);
  if (result.unsettled.empty())
    unsettled_.erase(key);
  else
    unsettled_[key] = {std::move(result.unsettled), changes()};
  return inserted;
}

void Refinement::insert_partner(const Witness& w) {
  using detail::operator+;
  using detail::operator*;
  if (w.kind == CheckKind::seed) return;
  const InsertionRecord& witness = log_.back();
  const double reach = tolerances::opposite_sheet_reach * witness.nearest_distance;
  const Vec3 n = oracle_.normal(w.point);
  if (!(reach > 0) || !(detail::norm(n) > 0)) return;
  // A root this close is w's own (and a partner there would be rejected as a duplicate).
  const double own = tolerances::duplicate_sample_relative_distance * oracle_.diagonal() / tolerances::opposite_sheet_spacing;
  // No partner when E(w + t n) is strictly monotone in t on [−reach, reach] (⟨∇E, n⟩ of one sign
  // along the segment) and changes sign on [−own, own]: its only zero there is w's own.
  if (const int along = oracle_.gradient_sign(w.point + (-reach) * n, w.point + reach * n, n); along != 0)
    if (oracle_.value_sign(w.point + (-own) * n) == -along && oracle_.value_sign(w.point + own * n) == along) return;
  // The nearest point of Σ on the normal line other than w itself, if the search settled it.
  const SolveResult line = oracle_.surface_line(w.point, n, -reach, reach);
  if (!line.undecided.empty()) return;
  std::optional<double> nearest_t;
  for (const auto& root : line.roots) {
    const auto& b = root.box.bounds[0];
    const double t = root.midpoint[0];
    if ((b[0] <= 0 && 0 <= b[1]) || std::abs(t) <= own) continue;
    if (!nearest_t || std::abs(t) < std::abs(*nearest_t)) nearest_t = t;
  }
  if (!nearest_t) return;
  const Vec3 y = w.point + *nearest_t * n;
  // The two conditions of the termination argument in refinement.h.  A partner below the
  // termination floor is not tried: it is optional, so it is no witness the floor held back.
  if (!(std::abs(detail::dot(oracle_.normal(y), n)) >= tolerances::opposite_sheet_min_cosine)) return;
  const double spacing = del_.nearest(y, witness.id).second;
  if (!(spacing >= tolerances::opposite_sheet_spacing * std::abs(*nearest_t)) || spacing < floor_for(w.kind)) return;
  Witness partner = w;
  partner.point = y;
  partner.measured_from = witness.id;
  partner.from_undecided = false;
  timed_insert(partner, witness.id);
}

bool Refinement::silhouette_premise(VertexId p) const {
  for (const auto& [key, entry] : unsettled_) {
    const auto& [step, item] = key;
    const CheckKind kind = steps_[step].row->kind;
    if ((kind == CheckKind::facet_contact || kind == CheckKind::facet_cycle) && (item[0] == p || item[1] == p))
      return false;
  }
  return true;
}

bool Refinement::requeue_unsettled() {
  // A face left unsettled is examined again if S changed since (it may have shrunk away from
  // what could not be settled, or a rejected witness may now be inserted).  Faces no longer in
  // Del S are forgotten: a face that comes back is new and is queued anyway.
  bool queued = false;
  for (auto it = unsettled_.begin(); it != unsettled_.end();) {
    const auto& [step, item] = it->first;
    if (!face_current(item)) {
      it = unsettled_.erase(it);
      continue;
    }
    if (it->second.changes != changes()) {
      steps_[step].queue.push(item);
      queued = true;
    }
    ++it;
  }
  return queued;
}

std::vector<Unsettled> Refinement::unsettled() const {
  std::vector<Unsettled> out = standing_unsettled_;
  for (const auto& [key, entry] : unsettled_)
    if (face_current(key.second)) out.insert(out.end(), entry.what.begin(), entry.what.end());
  return out;
}

Certification Refinement::certify(MeshStatus run_status, bool output_defective) const {
  Certification c;
  c.unsettled = unsettled();
  const auto unresolved = restricted_.unresolved_regions();
  c.unresolved_edge_regions = unresolved.size();
  for (const auto& [t, x] : unresolved) c.unsettled.push_back({CheckKind::vor_edge, UnsettledReason::unresolved_crossing, x});
  // current(t) skips the queued checks of a triangle without a record, on the promise that every
  // current triangle has one and only current ones do; if the promise was broken and not mended
  // by the end, the counts differ.
  if (restricted_.record_count() != del_.triangle_count())
    c.unsettled.push_back({CheckKind::vor_edge, UnsettledReason::record_count_mismatch, {}});
  // VorEdge's condition on every final record, whether or not its check ran since the record was
  // last solved: a record with a tangency candidate or two crossings fails Lemma 4.7.  A face the
  // driver already lists as unsettled is not listed twice.
  for (int s = 0; s < static_cast<int>(steps_.size()); ++s) {
    const CheckInfo& row = *steps_[s].row;
    if (row.kind != CheckKind::vor_edge || !row.may_fire) continue;
    std::vector<std::pair<TriangleKey, Vec3>> firing;
    restricted_.for_each_record([&](const TriangleKey& t, const VoronoiEdgeRecord& r) {
      if (row.may_fire(r) && unsettled_.count({s, t}) == 0)
        firing.push_back({t, r.candidates().empty() ? r.crossings().front() : r.candidates().front()});
    });
    std::sort(firing.begin(), firing.end());
    for (const auto& [t, x] : firing) c.unsettled.push_back({CheckKind::vor_edge, UnsettledReason::vor_edge_fires, x});
  }
  c.status = run_status;
  if (run_status == MeshStatus::complete && (!c.unsettled.empty() || output_defective)) c.status = MeshStatus::uncertified;
  return c;
}

nlohmann::json Refinement::insertions_json() const {
  nlohmann::json j = nlohmann::json::object();
  for (int k = 0; k < check_kind_count(); ++k) {
    const std::string name = check_kind_name(static_cast<CheckKind>(k));
    j[name == "seed" ? "seeds" : name] = insertions_[k];
  }
  j["seeds_deleted"] = seeds_deleted_;
  j["rejected_witnesses"] = rejected_;
  j["generic_choice_retries"] = retries_;
  j["opposite_sheet"] = partners_;
  return j;
}

double Refinement::floor_for(CheckKind kind) const {
  // The phase of the row whose witness it is: size- and distance-bound witnesses are the Quality
  // row's, and a seed (no row) belongs to the topology phase.
  const CheckKind row_kind = kind == CheckKind::size || kind == CheckKind::distance ? CheckKind::quality : kind;
  const auto step = std::find_if(steps_.begin(), steps_.end(), [&](const Step& s) { return s.row->kind == row_kind; });
  const bool geometry = step != steps_.end() && step->row->phase == CheckPhase::geometry;
  return geometry ? limits_.min_spacing : tolerances::topology_floor_fraction * limits_.min_spacing;
}

nlohmann::json Refinement::floor_json() const {
  return {{"value", limits_.min_spacing},
          {"topology_value", floor_for(CheckKind::vor_edge)},
          {"reached", floor_hits_ > 0},
          {"witnesses_below", floor_hits_},
          {"locations", floor_locations_}};
}

nlohmann::json Refinement::checks_json() const { return per_step(checks_); }

nlohmann::json Refinement::seconds_json() const { return per_step(seconds_); }

template <class T>
nlohmann::json Refinement::per_step(const std::vector<T>& counts) const {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& step : steps_) j[step.row->name] = counts[static_cast<int>(step.row->kind)];
  return j;
}

}  // namespace delmesh
