#include "meshing/voronoi/restricted_delaunay.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "common/errors.h"
#include "common/tolerances.h"
#include "meshing/core/detail/key_order.h"
#include "meshing/core/detail/vec3.h"
#include "solvers/query_geometry.h"
#include "symbolic/scalar_traits.h"
#include "symbolic/scalar_types.h"

namespace delmesh {

static_assert(sizeof(VoronoiEdgeRecord) <= 32, "a record per Delaunay triangle: keep it small");

namespace {

// The number of entries of a lists block with these counts (unresolved, crossings, candidates).
std::size_t block_entries(std::size_t unresolved, std::size_t crossings, std::size_t candidates) {
  return 1 + unresolved + 2 * (crossings + candidates);
}

}  // namespace

RecordPoints VoronoiEdgeRecord::list(int which) const {
  if (!lists_) return {};
  const Vec3& counts = lists_[0];
  const auto n_unresolved = static_cast<std::size_t>(counts[0]), n_crossings = static_cast<std::size_t>(counts[1]),
             n_candidates = static_cast<std::size_t>(counts[2]);
  const std::size_t sizes[5] = {n_unresolved, n_crossings, n_candidates, n_crossings, n_candidates};
  std::size_t start = 1;
  for (int k = 0; k < which; ++k) start += sizes[k];
  return {lists_.get() + start, sizes[which]};
}

std::unique_ptr<Vec3[]> VoronoiEdgeRecord::copy(const VoronoiEdgeRecord& other) {
  if (!other.lists_) return nullptr;
  const Vec3& counts = other.lists_[0];
  const std::size_t n = block_entries(static_cast<std::size_t>(counts[0]), static_cast<std::size_t>(counts[1]),
                                      static_cast<std::size_t>(counts[2]));
  std::unique_ptr<Vec3[]> block(new Vec3[n]);
  std::copy(other.lists_.get(), other.lists_.get() + n, block.get());
  return block;
}

VoronoiEdgeRecord& VoronoiEdgeRecord::operator=(const VoronoiEdgeRecord& other) {
  if (this != &other) *this = VoronoiEdgeRecord(other);  // the copy constructor, then the move
  return *this;
}

VoronoiEdge VoronoiEdgeRecord::edge(const Delaunay& del, const TriangleKey& t) const {
  VoronoiEdge e = voronoi_edge_line(del, t);
  e.t0 = t0_;
  e.t1 = t1_;
  e.at_vertex0 = at_vertex0_;
  e.at_vertex1 = at_vertex1_;
  e.valid = valid_;
  e.degenerate = degenerate_;
  return e;
}

void VoronoiEdgeRecord::set_edge(const VoronoiEdge& e) {
  t0_ = e.t0;
  t1_ = e.t1;
  at_vertex0_ = e.at_vertex0;
  at_vertex1_ = e.at_vertex1;
  valid_ = e.valid;
  degenerate_ = e.degenerate;
}

void VoronoiEdgeLists::clear() {
  for (auto* points : {&unresolved, &crossings, &candidates}) points->clear();
  crossing_range.clear();
  candidate_range.clear();
}

void VoronoiEdgeRecord::set_lists(const VoronoiEdgeLists& lists) {
  if (lists.crossing_range.size() != lists.crossings.size() || lists.candidate_range.size() != lists.candidates.size())
    throw PreconditionViolation("VoronoiEdgeRecord::set_lists: a range list is not as long as its points");
  const std::size_t nu = lists.unresolved.size(), nc = lists.crossings.size(), nk = lists.candidates.size();
  if (nu + nc + nk == 0) {
    lists_.reset();
    return;
  }
  std::unique_ptr<Vec3[]> block(new Vec3[block_entries(nu, nc, nk)]);
  block[0] = {static_cast<double>(nu), static_cast<double>(nc), static_cast<double>(nk)};
  Vec3* out = block.get() + 1;
  for (const auto* points : {&lists.unresolved, &lists.crossings, &lists.candidates})
    out = std::copy(points->begin(), points->end(), out);
  for (const auto* ranges : {&lists.crossing_range, &lists.candidate_range})
    for (const auto& r : *ranges) *out++ = {r[0], r[1], 0.0};
  lists_ = std::move(block);
}

using namespace detail;

namespace {

//! Whether E ≠ 0 is proved on the box [lo, hi]: on a cover of it by boxes on each of which
//! SurfaceOracle::value_sign proves a sign, found by halving the widest side of a box that is not
//! proved, while at most `budget` boxes have been evaluated.  (The box is connected, so E then
//! keeps one sign on it.)
bool excludes_zero_on(const SurfaceOracle& oracle, const Vec3& lo, const Vec3& hi, std::size_t budget) {
  std::vector<std::array<Vec3, 2>> stack{{lo, hi}};
  for (std::size_t evaluated = 0; !stack.empty(); ++evaluated) {
    if (evaluated == budget) return false;
    const auto [a, b] = stack.back();
    stack.pop_back();
    if (oracle.value_sign(a, b) != 0) continue;
    int k = 0;
    for (int i = 1; i < 3; ++i)
      if (b[i] - a[i] > b[k] - a[k]) k = i;
    const double mid = 0.5 * (a[k] + b[k]);
    if (!(a[k] < mid && mid < b[k])) return false;
    Vec3 left_hi = b, right_lo = a;
    left_hi[k] = mid;
    right_lo[k] = mid;
    stack.push_back({right_lo, b});
    stack.push_back({a, left_hi});
  }
  return true;
}

//! The record's (valid) edge meets Σ nowhere, and nothing on it is unsettled.
bool misses_surface(const VoronoiEdgeRecord& r) {
  return r.edge_valid() && r.crossings().empty() && r.candidates().empty() && r.unresolved().empty();
}

//! The proved sign of E on the connector [v, a] of an edge's end a = at(t) at the shared Voronoi
//! vertex v (restricted_delaunay.h), from its bounding box; 0 if none is proved.
int connector_sign(const SurfaceOracle& oracle, const Vec3& a, const Vec3& v) {
  if (a == v) return oracle.value_sign(a);
  BoundingBox b;
  b.add(a);
  b.add(v);
  return oracle.value_sign(b.lo, b.hi);
}

//! Whether x lies in the box {lo, hi} = box[0], box[1].
bool in_box(const Vec3& x, const std::array<Vec3, 2>& box) {
  for (int k = 0; k < 3; ++k)
    if (!(x[k] >= box[0][k] && x[k] <= box[1][k])) return false;
  return true;
}

// Step 1 of facet_misses_surface(): F's Voronoi edges (edges[i] of boundary[i]) and the ends of
// the valid ones in `ends`; `inside_box` says whether every edge is valid with both ends at
// Voronoi vertices.  False when an edge proves nothing: it meets Σ (which puts a point of Σ in
// F), it is degenerate, or it has no line.
bool facet_edge_ends(const Delaunay& del, const EdgeKey& e, const std::vector<Delaunay::RingTriangle>& ring,
                     const std::vector<const VoronoiEdgeRecord*>& boundary, std::vector<VoronoiEdge>& edges,
                     BoundingBox& ends, bool& inside_box) {
  for (std::size_t i = 0; i < boundary.size(); ++i) {
    const VoronoiEdgeRecord* r = boundary[i];
    if (!r->crossings().empty() || !r->candidates().empty() || !r->unresolved().empty() || r->edge_degenerate())
      return false;
    const VoronoiEdge& edge = edges.emplace_back(r->edge(del, make_triangle_key(e[0], e[1], ring[i].third)));
    if (!edge.valid) {
      // An edge that is neither valid nor degenerate lies outside B, unless it has no line at all
      // (a triangle with no normal), which proves nothing.
      if (!(norm(edge.direction) > 0)) return false;
      inside_box = false;
      continue;
    }
    inside_box = inside_box && edge.at_vertex0 && edge.at_vertex1;
    ends.add(edge.at(edge.t0));
    ends.add(edge.at(edge.t1));
  }
  return true;
}

// Step 2 of facet_misses_surface(): adds to `ends` the points y of Π ∩ (edges of B) in F, i.e. on
// p's side of the bisector of p and each r (up to the margin, so that rounding can only add
// points).
void add_box_edge_points(const Delaunay& del, const Box3& clip, const EdgeKey& e,
                         const std::vector<Delaunay::RingTriangle>& ring, double margin, BoundingBox& ends) {
  const Vec3& p = del.point(e[0]);
  const Vec3& q = del.point(e[1]);
  for (const Vec3& y : plane_box_edge_points(0.5 * (p + q), q - p, clip)) {
    const bool in_facet = std::all_of(ring.begin(), ring.end(), [&](const Delaunay::RingTriangle& t) {
      const Vec3& r = del.point(t.third);
      const Vec3 w = r - p;
      return dot(w, y) - dot(w, 0.5 * (r + p)) <= margin * norm(w);
    });
    if (in_facet) ends.add(y);
  }
}

// The distance from x to the box [lo, hi].
double distance_outside(const Vec3& x, const Vec3& lo, const Vec3& hi) {
  double out = 0;
  for (int k = 0; k < 3; ++k) out += std::pow(std::max({0.0, lo[k] - x[k], x[k] - hi[k]}), 2);
  return std::sqrt(out);
}

// Step 4 of facet_misses_surface(): the largest δ = dist(v, box of `ends`) + ρ(v) over the
// Voronoi vertices v of F's valid edges (apexes from the ring) that may lie in B (those farther
// than ρ(v) from B are not vertices of F ∩ B).  The static radii are asked first, up to a
// quarter of the margin; the interval ones if δ is then too large.
double voronoi_vertex_reach(const Delaunay& del, const Box3& clip, const std::vector<Delaunay::RingTriangle>& ring,
                            const std::vector<VoronoiEdge>& edges, const BoundingBox& ends, double margin) {
  thread_local std::vector<std::array<VertexId, 4>> cells;
  cells.clear();
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const VoronoiEdge& edge = edges[i];
    if (!edge.valid || (!edge.at_vertex0 && !edge.at_vertex1)) continue;
    const TriangleKey& t = edge.triangle;
    for (VertexId apex : ring[i].apexes)
      if (apex >= 0) cells.push_back({t[0], t[1], t[2], apex});
  }
  double reach = 0;
  for (const double enough : {0.25 * margin, 0.0}) {
    reach = 0;
    for (const auto& c : cells) {
      const VoronoiVertex v = certified_voronoi_vertex(del, c, enough);
      if (!(distance_outside(v.centre, clip.lo, clip.hi) > v.radius))
        reach = std::max(reach, distance_outside(v.centre, ends.lo, ends.hi) + v.radius);
    }
    if (2 * reach <= margin) break;
  }
  return reach;
}

}  // namespace

RestrictedDelaunay::RestrictedDelaunay(const Delaunay& del, SurfaceOracle& oracle, std::uint64_t seed)
    : del_(del), oracle_(oracle), seed_(seed) {}

double RestrictedDelaunay::facet_rotation(const EdgeKey& e, int attempt) const {
  return 2 * M_PI * seeded_uniform(attempt_seed(seed_, attempt), e[0], e[1], generic_stream::facet_rotation);
}

VoronoiFacet RestrictedDelaunay::rotated_facet(const EdgeKey& e, int attempt) const {
  return voronoi_facet(del_, e, oracle_.clip_box(), facet_rotation(e, attempt));
}

void RestrictedDelaunay::track(const TriangleKey& t, bool was_restricted, bool is_restricted) {
  if (was_restricted == is_restricted) return;
  for (VertexId v : t) {
    if (static_cast<std::size_t>(v) >= stars_.size()) stars_.resize(v + 1);
    auto& star = stars_[v];
    if (is_restricted) {
      star.push_back(t);
    } else {
      star.erase(std::find_if(star.begin(), star.end(), [&](const TriangleKey& s) { return detail::KeyEqual{}(s, t); }));
    }
  }
}

void RestrictedDelaunay::erase_record(const TriangleKey& t) {
  if (const VoronoiEdgeRecord* r = edges_.take(t)) track(t, r->restricted, false);
}

const VoronoiEdgeRecord& RestrictedDelaunay::assign(const TriangleKey& t, VoronoiEdgeRecord& slot, bool was_restricted,
                                                    VoronoiEdgeRecord&& record, bool solved) {
  ++(solved ? records_solved_ : records_restricted_);
  slot = std::move(record);
  track(t, was_restricted, slot.restricted);
  return slot;
}

const VoronoiEdgeRecord& RestrictedDelaunay::install(const TriangleKey& t, VoronoiEdgeRecord&& record, bool solved) {
  const auto [slot, inserted] = edges_.try_emplace(t);
  return assign(t, *slot, !inserted && slot->restricted, std::move(record), solved);
}

std::optional<VoronoiEdgeRecord> RestrictedDelaunay::update_without_solving(const TriangleKey& t,
                                                                            const std::array<VertexId, 2>* apexes,
                                                                    const VoronoiEdgeRecord*& current) {
  VoronoiEdgeRecord* cached = edges_.find(t);
  current = nullptr;
  if (!cached) return std::nullopt;
  if (!cached->shrunk || misses_surface(*cached)) {
    // Up to date, or an edge that misses Σ and so still does after shrinking (prepare_star).
    if (cached->shrunk) ++records_restricted_;
    cached->shrunk = false;
    current = cached;
    return std::nullopt;
  }
  return restrict_record(t, *cached, voronoi_edge(del_, t, oracle_.clip_box(), apexes));
}

const VoronoiEdgeRecord& RestrictedDelaunay::voronoi_edge_record(const TriangleKey& t,
                                                                 const std::array<VertexId, 2>* apexes) {
  const VoronoiEdgeRecord* current = nullptr;
  if (auto restricted = update_without_solving(t, apexes, current)) return install(t, std::move(*restricted), false);
  if (current) return *current;
  return install(t, compute(t, apexes), true);
}

std::vector<TriangleKey> RestrictedDelaunay::forget_destroyed(const InsertionChange& change) {
  std::vector<TriangleKey> left;
  left.reserve(change.destroyed_triangles.size());
  for (const auto& t : change.destroyed_triangles) edges_.prefetch(t);
  for (const auto& t : change.destroyed_triangles) {
    const VoronoiEdgeRecord* r = edges_.take(t);
    if (!r || r->restricted || r->shrunk) left.push_back(t);
    if (r) track(t, r->restricted, false);
  }
  forget({}, change.destroyed_edges);
  shrink_facets(change.shrunk_edges);
  return left;
}

std::vector<RestrictedDelaunay::StarRecord> RestrictedDelaunay::prepare_star(
    const std::vector<Delaunay::StarTriangle>& star, const detail::ParallelFor& parallel) {
  // One lookup per triangle: link triangles are restricted in place where possible; the rest are
  // solved in parallel, one slot each, and installed in the star's order.  (References into the
  // table survive later insertions into it.)
  std::vector<StarRecord> out(star.size());
  // The new vertex: the one vertex of every star triangle that contains it (its Voronoi vertices
  // are the new ones, whose connectors a kept record has not seen).
  VertexId x = -1;
  for (const auto& first : star) {
    if (!first.contains_vertex) continue;
    for (VertexId v : first.key)
      if (std::all_of(star.begin(), star.end(), [&](const Delaunay::StarTriangle& st) {
            return !st.contains_vertex || st.key[0] == v || st.key[1] == v || st.key[2] == v;
          }))
        x = v;
    break;
  }
  std::vector<std::size_t> to_solve;
  to_solve.reserve(star.size());
  for (const auto& s : star) edges_.prefetch(s.key);
  for (std::size_t i = 0; i < star.size(); ++i) {
    const auto& s = star[i];
    // A triangle containing the new vertex is new: it has no record.
    VoronoiEdgeRecord* cached = s.contains_vertex ? nullptr : edges_.find(s.key);
    if (!cached) {
      to_solve.push_back(i);
      continue;
    }
    if (!cached->shrunk) {
      out[i].had_record = true;
      out[i].was_restricted = cached->restricted;
      out[i].old_dual_point = cached->dual_point();
    }
    if (misses_surface(*cached)) {
      // e ∩ Σ = ∅ on a valid edge e, so e′ ∩ Σ = ∅ for e′ ⊆ e: the record stays as it is
      // (its edge is not needed once it holds no point of Σ) if E keeps its sign on the
      // connectors of e′ to its shared vertices too (the new vertex's is new); else it is solved.
      if (!kept_connectors_clean(*cached, s.key, s.apexes, x)) {
        to_solve.push_back(i);
        continue;
      }
      ++records_restricted_;
      cached->shrunk = false;
      out[i].record = cached;
      continue;
    }
    auto restricted = restrict_record(s.key, *cached, voronoi_edge(del_, s.key, oracle_.clip_box(), &s.apexes));
    if (!restricted) {
      to_solve.push_back(i);
      continue;
    }
    out[i].record = &assign(s.key, *cached, cached->restricted, std::move(*restricted), false);
  }
  std::vector<VoronoiEdgeRecord> solved(to_solve.size());
  parallel.run(to_solve.size(), [&](std::size_t k) {
    const auto& s = star[to_solve[k]];
    solved[k] = compute(s.key, &s.apexes);
  }, tolerances::parallel_least_records);
  for (std::size_t k = 0; k < to_solve.size(); ++k) {
    out[to_solve[k]].record = &install(star[to_solve[k]].key, std::move(solved[k]), true);
    out[to_solve[k]].solved = true;
  }
  return out;
}

void RestrictedDelaunay::add_facets(const std::vector<EdgeKey>& edges) {
  for (const EdgeKey& e : edges) facet_entry(e);
}

bool RestrictedDelaunay::facet_misses_surface(const EdgeKey& e, const std::vector<Delaunay::RingTriangle>& ring,
                                              const std::vector<const VoronoiEdgeRecord*>& boundary) {
  if (boundary.size() != ring.size())
    throw PreconditionViolation("RestrictedDelaunay::facet_misses_surface: the ring and its records differ in length");
  if (boundary.empty()) return false;
  // Step 1: the vertices of F ∩ B of the first two kinds: the ends of the valid Voronoi edges of
  // F.  An edge that meets Σ puts a point of Σ in F; a degenerate one proves nothing.
  BoundingBox ends;
  bool inside_box = true;  // every Voronoi edge of F valid, with both ends at Voronoi vertices
  thread_local std::vector<VoronoiEdge> edges;  // the edges of F (edges[i] of boundary[i])
  edges.clear();
  if (!facet_edge_ends(del_, e, ring, boundary, edges, ends, inside_box)) return false;
  const double margin = tolerances::face_membership_relative_tolerance * oracle_.diagonal();
  // Step 2: the third kind, points of Π ∩ (edges of B) in F.
  if (!inside_box) add_box_edge_points(del_, oracle_.clip_box(), e, ring, margin, ends);
  if (ends.empty()) return false;
  // Step 3: E of one sign on the box enlarged by the margin (needed in any case).
  BoundingBox box = ends;
  box.enlarge(margin);
  if (!excludes_zero_on(oracle_, box.lo, box.hi, tolerances::facet_miss_box_budget)) return false;
  // Step 4: every exact Voronoi vertex of F ∩ B lies within δ = voronoi_vertex_reach() of the
  // box of the points.  If 2δ exceeds the margin, the proof is redone on the box enlarged by 2δ
  // when every edge of F ends at Voronoi vertices, and not attempted otherwise.
  const double reach = voronoi_vertex_reach(del_, oracle_.clip_box(), ring, edges, ends, margin);
  if (!std::isfinite(reach)) return false;
  if (2 * reach > margin) {
    if (!inside_box) return false;
    ends.enlarge(2 * reach);
    if (!excludes_zero_on(oracle_, ends.lo, ends.hi, tolerances::facet_miss_box_budget)) return false;
  }
  ++facets_missing_surface_;
  return true;
}

const VoronoiEdgeRecord* RestrictedDelaunay::cached_record(const TriangleKey& t) const {
  return edges_.find(t);
}

std::optional<VoronoiEdgeRecord> RestrictedDelaunay::restrict_record(const TriangleKey& t, const VoronoiEdgeRecord& old,
                                                                     const VoronoiEdge& edge) const {
  if (!old.unresolved().empty() || !old.edge_valid() || !edge.valid) return std::nullopt;
  const VoronoiEdge e = old.edge(del_, t);
  if (edge.point != e.point || edge.direction != e.direction) return std::nullopt;
  // e′ ⊆ e as computed; the new ends are those of e′ clamped into e (exact as sets).
  const double t0 = std::max(edge.t0, e.t0), t1 = std::min(edge.t1, e.t1);
  if (!(t0 < t1)) return std::nullopt;
  const double margin = tolerances::duplicate_sample_relative_distance * oracle_.diagonal();
  // 1: inside e′ away from its ends, 0: outside e′, −1: undecided.
  auto side = [&](const Vec3& range) {
    if (range[1] < t0 - margin || range[0] > t1 + margin) return 0;
    if (range[0] > t0 + margin && range[1] < t1 - margin) return 1;
    return -1;
  };
  VoronoiEdgeRecord r;
  VoronoiEdge kept = edge;
  kept.t0 = t0;
  kept.t1 = t1;
  r.set_edge(kept);
  // Keeps the points whose enclosures lie inside e′; false if one cannot be placed.
  thread_local VoronoiEdgeLists lists;
  lists.clear();
  auto keep = [&](RecordPoints points, RecordPoints ranges, std::vector<Vec3>& kept_points,
                  std::vector<std::array<double, 2>>& kept_ranges) {
    for (std::size_t i = 0; i < points.size(); ++i) {
      const int s = side(ranges[i]);
      if (s < 0) return false;
      if (s == 0) continue;
      kept_points.push_back(points[i]);
      kept_ranges.push_back({ranges[i][0], ranges[i][1]});
    }
    return true;
  };
  if (!keep(old.crossings(), old.crossing_range(), lists.crossings, lists.crossing_range) ||
      !keep(old.candidates(), old.candidate_range(), lists.candidates, lists.candidate_range))
    return std::nullopt;
  r.set_lists(lists);
  // No crossing is at a Voronoi vertex of e′, so the §5.1 rule keeps every crossing.
  r.restricted = !lists.crossings.empty();
  return r;
}

RestrictedDelaunay::FacetEntry& RestrictedDelaunay::facet_entry(const EdgeKey& e) {
  const auto [entry, added] = facets_.try_emplace(e);
  if (added) *entry = FacetEntry{};
  return *entry;
}

const VoronoiFacet& RestrictedDelaunay::facet(const EdgeKey& e, const std::vector<Delaunay::RingTriangle>* ring) {
  FacetEntry& entry = facet_entry(e);
  if (!entry.built) {
    ++facets_built_;
    entry.facet = voronoi_facet(del_, e, oracle_.clip_box(), facet_rotation(e), ring);
    entry.built = true;
  }
  return entry.facet;
}

bool RestrictedDelaunay::facet_section_certified(const EdgeKey& e) {
  // The entry stays where it is while facet() fills in its geometry (FlatTable's contract).
  FacetEntry& entry = facet_entry(e);
  if (entry.section_certified < 0) {
    SectionProof proof = certify_by_cell(e);
    if (proof == SectionProof::none) proof = certify_by_cover(e, facet(e));
    record_section(entry.section_certified, proof);
  }
  return entry.section_certified == 1;
}

void RestrictedDelaunay::record_section(int& slot, SectionProof proof) {
  slot = proof == SectionProof::none ? 0 : 1;
  if (proof == SectionProof::by_cell) ++facets_certified_by_cell_;
}

bool RestrictedDelaunay::cell_certified(VertexId p, const std::vector<VertexId>& facet_sites) {
  return certify_cell(p, facet_sites, [&] { return voronoi_cell(del_, p, oracle_.clip_box()); });
}

bool RestrictedDelaunay::certify_new_cell(VertexId x, const std::vector<std::array<VertexId, 4>>& cells,
                                          const std::vector<VertexId>& neighbours) {
  return certify_cell(x, neighbours, [&] { return voronoi_cell(del_, x, oracle_.clip_box(), cells, neighbours); });
}

namespace {

// Two of the tests below first evaluate their expression in doubles, rounded to nearest: each
// such operation's result lies between the lower and upper ends of the interval operation on
// intervals holding its operands, so the double value lies in the interval enclosure, and when it
// fails the test (with tolerances::slope_pretest_relative_margin for the one rounding outside the
// enclosure, in the comparison of plane_within_slope) the enclosure fails it too.  The answer is
// then false without switching the rounding mode, which costs more than the arithmetic; false
// proves nothing.

//! Whether the bisector plane {y : ⟨y − (p + q)/2, q − p⟩ = 0} of p and q misses the box
//! [lo, hi] (true for an empty box), by one interval evaluation over the box.
bool plane_misses_box(const Vec3& p, const Vec3& q, const std::array<Vec3, 2>& box) {
  for (int k = 0; k < 3; ++k)
    if (box[0][k] > box[1][k]) return true;
  RoundingGuard guard;
  Interval side(0);
  for (int k = 0; k < 3; ++k) {
    const Interval normal = Interval(q[k]) - Interval(p[k]);
    const Interval middle = (Interval(q[k]) + Interval(p[k])) / 2;
    side += normal * (Interval(box[0][k], box[1][k]) - middle);
  }
  return certainly_nonzero(side);
}

//! Whether ⟨q − p, u⟩ and ⟨q − p, v⟩ are proved (by interval arithmetic) to be non-zero and of
//! opposite signs.
bool normal_between_cones(const Vec3& p, const Vec3& q, const Vec3& u, const Vec3& v) {
  const Vec3 d{q[0] - p[0], q[1] - p[1], q[2] - p[2]};
  const double a_near = d[0] * u[0] + d[1] * u[1] + d[2] * u[2], b_near = d[0] * v[0] + d[1] * v[1] + d[2] * v[2];
  if (!((a_near > 0 && b_near < 0) || (a_near < 0 && b_near > 0))) return false;
  RoundingGuard guard;
  Interval m[3];
  for (int k = 0; k < 3; ++k) m[k] = Interval(q[k]) - Interval(p[k]);
  const Interval a = m[0] * u[0] + m[1] * u[1] + m[2] * u[2];
  const Interval b = m[0] * v[0] + m[1] * v[1] + m[2] * v[2];
  return (a.inf() > 0 && b.sup() < 0) || (a.sup() < 0 && b.inf() > 0);
}

//! Whether |⟨w, q − p⟩| / |q − p| < slope, with q − p and the quotient enclosed by intervals.
bool plane_within_slope(const Vec3& w, const Vec3& p, const Vec3& q, double slope) {
  const Vec3 d{q[0] - p[0], q[1] - p[1], q[2] - p[2]};
  const double along_near = std::abs(d[0] * w[0] + d[1] * w[1] + d[2] * w[2]);
  const double length_near = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (!(along_near < slope * length_near * (1 + tolerances::slope_pretest_relative_margin))) return false;
  RoundingGuard guard;
  Interval m[3];
  for (int k = 0; k < 3; ++k) m[k] = Interval(q[k]) - Interval(p[k]);
  const Interval along = m[0] * w[0] + m[1] * w[1] + m[2] * w[2];
  const Interval length = CGAL::sqrt(CGAL::square(m[0]) + CGAL::square(m[1]) + CGAL::square(m[2]));
  if (!(length.inf() > 0)) return false;
  return (CGAL::abs(along) / length).sup() < slope;
}

}  // namespace

bool RestrictedDelaunay::signs_certify(const Vec3& p, const Vec3& q, const Vec3& u, const CellCertificate& cq) {
  return covers_cell(cq) && cq.orientation != 0 && normal_between_cones(p, q, u, cq.orientation * cq.w);
}

bool RestrictedDelaunay::certify_cell(VertexId p, const std::vector<VertexId>& facet_sites,
                                      const std::function<VoronoiCell()>& build_cell) {
  using State = CellCertificate::State;
  if (static_cast<std::size_t>(p) >= cells_.size()) cells_.resize(static_cast<std::size_t>(p) + 1);
  CellCertificate& c = cells_[p];
  if (covers_cell(c)) return true;
  // V_p, built once whichever attempt asks for it first.
  std::optional<VoronoiCell> built;
  auto cell_of_p = [&]() -> const VoronoiCell& {
    if (!built) built = build_cell();
    return *built;
  };
  if (c.state == State::proved && cell_of_p().valid && complete_grown_cell(c, cell_of_p())) return true;
  if (failure_kept(c)) return false;
  c = CellCertificate{};
  const Vec3 n = oracle_.normal(del_.point(p));
  if (!(norm(n) > 0)) return false;
  // With facets to certify: the slope that certifies every facet pq a slope up to the cap can,
  // leaving out the facets that q's kept certificate already certifies, alone or with a proof
  // over V_p of ⟨∇E, n_p⟩ > 0 (the usual sign on a small cell, around p where it is |∇E(p)|).
  double target = 0;
  for (VertexId q : facet_sites) {
    if (certify_by_cell(make_edge_key(p, q)) == SectionProof::by_cell) continue;
    if (static_cast<std::size_t>(q) < cells_.size() && signs_certify(del_.point(p), del_.point(q), n, cells_[q]))
      continue;
    const Vec3 m = del_.point(q) - del_.point(p);
    const double along = std::abs(dot(m, n)) / norm(m);
    if (along <= tolerances::cell_slope_cap) target = std::max(target, along);
  }
  target *= tolerances::cell_slope_margin;
  // The oracle bounds no slopes (nor signs): Silhouette's turn.  Otherwise a proof without a
  // slope when no facet wants one: its sign may still certify facets with q's (certify_by_cell).
  if (!facet_sites.empty() && !oracle_.bounds_cone_slopes()) return false;
  const VoronoiCell& cell = cell_of_p();
  if (!cell.valid) return false;
  c.w = n;
  if (target > 0) {
    // For the facets, within the smaller budget; a failure is not kept.
    const SurfaceOracle::ConeAnswer answer = oracle_.gradient_cone_slope(AffineChart::identity(), cell.domain, n, target);
    if (!(answer.slope > 0)) return false;
    c.state = State::proved;
    c.slope = answer.slope;
    c.surface_box = answer.surface_box;
    c.orientation = answer.orientation;
    return true;
  }
  SurfaceOracle::ConeAnswer answer = oracle_.prove_gradient_cone(AffineChart::identity(), cell.domain, n);
  if (answer.proved) {
    c.state = State::proved;  // without a slope
    c.surface_box = answer.surface_box;
    c.orientation = answer.orientation;
    return true;
  }
  c.state = State::failed;
  c.vertices = del_.size();
  c.silhouette_point = answer.vanishing_point;
  return false;
}

namespace {

//! The domain a ∩ b (same dimension): the boxes met, the half-spaces of both.
Domain intersection(const Domain& a, const Domain& b) {
  Domain d = a;
  for (std::size_t j = 0; j < d.dimension(); ++j) {
    d.box.bounds[j][0] = std::max(a.box.bounds[j][0], b.box.bounds[j][0]);
    d.box.bounds[j][1] = std::min(a.box.bounds[j][1], b.box.bounds[j][1]);
  }
  d.half_spaces.insert(d.half_spaces.end(), b.half_spaces.begin(), b.half_spaces.end());
  return d;
}

}  // namespace

bool RestrictedDelaunay::complete_grown_cell(CellCertificate& c, const VoronoiCell& cell) {
  const Vec3 n = c.w;
  double slope = c.slope;
  std::optional<std::array<Vec3, 2>> surface_box = c.surface_box;
  int orientation = c.orientation;
  for (const Domain& grown : c.grown) {
    const Domain part = intersection(cell.domain, grown);
    bool empty = false;
    for (const auto& side : part.box.bounds) empty = empty || !(side[0] < side[1]);
    // No interior: then V_p gained nothing here.  A point y of V_p outside the old V_p is
    // strictly closer to the removed site s than to p, and so are the points of V_p near y,
    // which include interior points of the convex V_p: what V_p gained has interior.
    if (empty) continue;
    SurfaceOracle::ConeAnswer answer;
    if (c.slope > 0) {
      answer = oracle_.gradient_cone_slope(AffineChart::identity(), part, n, c.slope);
      if (!(answer.slope > 0)) return false;
      slope = std::min(slope, answer.slope);
    } else {
      answer = oracle_.prove_gradient_cone(AffineChart::identity(), part, n);
      if (!answer.proved) {
        // A failure on a part of V_p is one on V_p, kept as certify_cell() keeps its own: the
        // point that refuted it, if any, is a point of J_{n_p} in V_p.
        c = CellCertificate{};
        c.state = CellCertificate::State::failed;
        c.vertices = del_.size();
        c.silhouette_point = answer.vanishing_point;
        return false;
      }
    }
    // One sign on every part that meets Σ is the sign on their union.
    const bool meets_surface = !answer.surface_box || (*answer.surface_box)[0][0] <= (*answer.surface_box)[1][0];
    if (meets_surface && answer.orientation != orientation) orientation = 0;
    if (surface_box && answer.surface_box) {
      for (int k = 0; k < 3; ++k) {
        (*surface_box)[0][k] = std::min((*surface_box)[0][k], (*answer.surface_box)[0][k]);
        (*surface_box)[1][k] = std::max((*surface_box)[1][k], (*answer.surface_box)[1][k]);
      }
    } else {
      surface_box.reset();
    }
  }
  c.slope = slope;
  c.surface_box = surface_box;
  c.orientation = orientation;
  c.grown.clear();
  return true;
}

std::optional<Vec3> RestrictedDelaunay::cell_silhouette_point(VertexId p) const {
  if (static_cast<std::size_t>(p) >= cells_.size()) return std::nullopt;
  const CellCertificate& c = cells_[p];
  return failure_kept(c) ? c.silhouette_point : std::nullopt;
}

void RestrictedDelaunay::forget_cell(VertexId p) {
  if (static_cast<std::size_t>(p) < cells_.size()) cells_[p] = CellCertificate{};
}

RestrictedDelaunay::SectionProof RestrictedDelaunay::certify_by_cell(const EdgeKey& e) const {
  const Vec3& p = del_.point(e[0]);
  const Vec3& q = del_.point(e[1]);
  for (VertexId v : e) {
    if (static_cast<std::size_t>(v) >= cells_.size()) continue;
    const CellCertificate& c = cells_[v];
    if (!covers_cell(c)) continue;
    if (plane_within_slope(c.w, p, q, c.slope) || (c.surface_box && plane_misses_box(p, q, *c.surface_box)))
      return SectionProof::by_cell;
  }
  // Both cells certified with a sign, q − p between their cones (facet_section_certified()).
  if (static_cast<std::size_t>(std::max(e[0], e[1])) >= cells_.size()) return SectionProof::none;
  const CellCertificate& cp = cells_[e[0]];
  if (covers_cell(cp) && cp.orientation != 0 && signs_certify(p, q, cp.orientation * cp.w, cells_[e[1]]))
    return SectionProof::by_cell;
  return SectionProof::none;
}

RestrictedDelaunay::SectionProof RestrictedDelaunay::certify_by_cover(const EdgeKey& e, const VoronoiFacet& f) const {
  if (!f.valid && !f.degenerate) return SectionProof::none;
  const Vec3& p = del_.point(e[0]);
  const Vec3& q = del_.point(e[1]);
  // The in-plane part of ∇E at the midpoint of pq (the plane's origin before clipping): it
  // depends on p and q only, so a facet that shrinks keeps its direction (refinement.h).
  const Vec3 midpoint = 0.5 * (p + q);
  const Vec3 g = oracle_.gradient(midpoint);
  const Vec3 m = normalized(f.normal);
  Vec3 w = g - dot(g, m) * m;
  if (!(norm(w) > 0)) w = f.a;
  auto proof = [](bool proved) { return proved ? SectionProof::by_cover : SectionProof::none; };
  if (f.valid) return proof(oracle_.prove_gradient_cone(f.chart(), f.domain, normalized(w)).proved);
  // A degenerate facet lies in the bounding box of its polygon's points (VoronoiFacet), widened
  // by the membership tolerance as its world box is (WitnessCollector::add_degenerate_facet).
  const double margin = tolerances::face_membership_relative_tolerance * oracle_.diagonal();
  if (f.polygon.empty() || !(margin > 0)) return SectionProof::none;
  return proof(oracle_.prove_gradient_cone(f.chart(), f.polygon_hull(margin), normalized(w)).proved);
}

namespace {

//! A box holding the exact segment {p + t·v : t ∈ [t0, t1]} of e (outward rounding).
std::array<Vec3, 2> segment_box(const VoronoiEdge& e) {
  RoundingGuard guard;
  const Interval t(e.t0, e.t1);
  std::array<Vec3, 2> box;
  for (int k = 0; k < 3; ++k) {
    const Interval x = Interval(e.point[k]) + t * Interval(e.direction[k]);
    box[0][k] = x.inf();
    box[1][k] = x.sup();
  }
  return box;
}

// The zero of E on the edge's parameter range between tv and tf, where E is proved monotone and
// E(at(tv)) has proved sign sv ≠ 0: nothing if E(at(tf)) has the same sign (no zero), else the
// bisection limit of the sign change (to the last bit of t, or a point where E = 0 up to
// rounding).
std::optional<double> monotone_zero(const SurfaceOracle& oracle, const VoronoiEdge& e, double tv, double tf, int sv) {
  const int sf = oracle.value_sign(e.at(tf));
  if (sf == sv) return std::nullopt;
  if (sf == 0) return tf;
  double a = tv, b = tf;
  while (true) {
    const double m = 0.5 * (a + b);
    if (m == a || m == b) return m;
    const int sm = oracle.value_sign(e.at(m));
    if (sm == 0) return m;
    (sm == sv ? a : b) = m;
  }
}

// Whether E keeps one sign on a box holding e's segment and on the connectors from the shared
// Voronoi vertices `shared` to e's ends: the polyline misses Σ, which is all SurfaceLine could
// answer.  Tried first on the box that also holds the shared vertices (one evaluation), then on
// the segment's box with the connectors proved apart.
bool segment_signed(const SurfaceOracle& oracle, const VoronoiEdge& e, const std::array<Vec3, 2>& shared) {
  const auto box = segment_box(e);
  std::array<Vec3, 2> wide = box;
  for (int i = 0; i < 2; ++i)
    if (i == 0 ? e.at_vertex0 : e.at_vertex1)
      for (int k = 0; k < 3; ++k) {
        wide[0][k] = std::min(wide[0][k], shared[i][k]);
        wide[1][k] = std::max(wide[1][k], shared[i][k]);
      }
  const bool widened = wide != box;
  if (oracle.value_sign(wide[0], wide[1]) != 0) return true;
  if (!widened) return false;
  const int sign = oracle.value_sign(box[0], box[1]);
  if (sign == 0) return false;
  bool connectors_agree = true;
  for (int i = 0; i < 2 && connectors_agree; ++i)
    if ((i == 0 ? e.at_vertex0 : e.at_vertex1) && !in_box(shared[i], box))
      connectors_agree = connector_sign(oracle, e.at(i == 0 ? e.t0 : e.t1), shared[i]) == sign;
  return connectors_agree;
}

// The crossings, candidates and unresolved regions of one Voronoi edge e with Σ, gathered into
// `lists` from SurfaceLine's answer on e's segment and from e's connectors.  e is seen as the
// other faces see it: the polyline v0, at(t0), at(t1), v1, whose ends v_i at Voronoi vertices are
// the shared points of voronoi_edge_ends() (at(t0) and at(t1) otherwise).  The connector from v_i
// to at(t_i) is as long as v_i's distance from e's line, which the circumcentre's error can make
// far longer than a rounding.
class EdgeCrossings {
 public:
  EdgeCrossings(SurfaceOracle& oracle, const VoronoiEdge& e, const std::array<Vec3, 2>& shared,
                VoronoiEdgeLists& lists)
      : oracle_(oracle), e_(e), shared_(shared), lists_(lists) {}

  // SurfaceLine's certified roots: crossings, or zeros near a Voronoi vertex (add_near_vertex).
  void add_roots(const std::vector<CertifiedRoot>& roots) {
    const double vertex_tol = tolerances::duplicate_sample_relative_distance * oracle_.diagonal();
    for (const auto& root : roots) {
      const double t = root.midpoint[0], lo = root.box.bounds[0][0], hi = root.box.bounds[0][1];
      if (e_.at_vertex0 && std::abs(t - e_.t0) <= vertex_tol) {
        add_near_vertex(e_.t0, true, lo, hi);
      } else if (e_.at_vertex1 && std::abs(t - e_.t1) <= vertex_tol) {
        add_near_vertex(e_.t1, false, lo, hi);
      } else {
        lists_.crossings.push_back(root.world);
        lists_.crossing_range.push_back({lo, hi});
      }
    }
  }

  // SurfaceLine's undecided regions: a boundary root next to a Voronoi vertex is settled there;
  // another becomes a candidate where its projection onto Σ lies on e, and unresolved otherwise.
  void add_undecided(const std::vector<UndecidedBox>& undecided) {
    const double face_tol = tolerances::face_membership_relative_tolerance * oracle_.diagonal();
    for (const auto& u : undecided) {
      const double lo = u.box.bounds[0][0], hi = u.box.bounds[0][1];
      const double tm = 0.5 * (lo + hi);
      const bool near0 = std::abs(tm - e_.t0) <= std::abs(tm - e_.t1);
      if (u.reason == UndecidedReason::boundary_root && (near0 ? e_.at_vertex0 : e_.at_vertex1)) {
        add_near_vertex(near0 ? e_.t0 : e_.t1, near0, lo, hi);
        continue;
      }
      const auto x = oracle_.project(u.world);
      const double tol = std::max(face_tol, hi - lo);
      if (x) {
        const double tx = dot(*x - e_.point, e_.direction);
        const double off = distance(*x, e_.at(tx));
        if (off <= tol && tx >= e_.t0 - tol && tx <= e_.t1 + tol) {
          lists_.candidates.push_back(*x);
          lists_.candidate_range.push_back({std::min(lo, tx - tol), std::max(hi, tx + tol)});
          continue;
        }
      }
      lists_.unresolved.push_back(u.world);
    }
  }

  // The connectors not settled above whose sign is not proved: each may hold a zero that
  // SurfaceLine, on e's line, cannot see.  If E(v) = 0 up to rounding, the zero is at the vertex:
  // settled by add_near_vertex() with R = [v, a], a = at(tv).  If E is proved strictly monotone
  // along it (the sign of ⟨∇E, a − v⟩ on [v, a]) and non-zero at both ends, it holds one zero if
  // the signs differ (a crossing, reported at a) and none otherwise; else several zeros are
  // possible: a crossing at v, unresolved.
  void settle_connectors() {
    for (int i = 0; i < 2; ++i) {
      if (!(i == 0 ? e_.at_vertex0 : e_.at_vertex1) || settled_at_vertex_[i] || end_sign(i) != 0) continue;
      const double tv = i == 0 ? e_.t0 : e_.t1;
      const Vec3 a = e_.at(tv), v = shared_[i];
      const int sv = oracle_.value_sign(v), sa = oracle_.value_sign(a);
      if (sv == 0) {
        // E(v) = 0 up to rounding: a zero at the Voronoi vertex, settled as above (§5.1).
        add_near_vertex(tv, i == 0, tv, tv);
        continue;
      }
      if (sa != 0 && oracle_.gradient_sign(v, a, a - v) != 0) {
        if (sv == sa) continue;
        lists_.crossings.push_back(a);
      } else {
        lists_.crossings.push_back(v);
        lists_.unresolved.push_back(v);
      }
      lists_.crossing_range.push_back({tv, tv});
    }
  }

  // Whether e's dual triangle is in Tri S|Σ: e crosses Σ, other than at one Voronoi vertex that
  // §5.1 excludes.
  bool restricted() const {
    const bool lone_excluded_vertex =
        lists_.crossings.size() == 1 && vertex_root_excluded_.size() == 1 && vertex_root_excluded_[0];
    return !lists_.crossings.empty() && !lone_excluded_vertex;
  }

 private:
  // The proved sign of E on the connector of end i, or 0.
  int end_sign(int i) const { return connector_sign(oracle_, e_.at(i == 0 ? e_.t0 : e_.t1), shared_[i]); }

  // A zero of E in the parameter range [lo, hi] that may be at the Voronoi vertex v = e.at(tv)
  // (a certified root within the vertex tolerance, or a boundary_root region the isolator could
  // not separate from v), settled by interval proofs on the part R of [lo, hi] ∪ {tv} in e.
  // The vertex v is the point voronoi_edge_ends() shares with the other edges at it, so they all
  // see the same sign of E(v).  R runs from v through the connector to at(tv), then along e.
  void add_near_vertex(double tv, bool at_start, double lo, double hi) {
    const double tf = at_start ? std::max(hi, tv) : std::min(lo, tv);  // the far end of R
    const Vec3 into = at_start ? e_.direction : (-1.0) * e_.direction;  // direction of u − v
    settled_at_vertex_[at_start ? 0 : 1] = true;
    const Vec3 v = shared_[at_start ? 0 : 1];
    const int s = oracle_.gradient_sign(v, e_.at(tf), into);
    const int sv = oracle_.value_sign(v);
    if (s == 0) {
      // E is not proved monotone on R: it may hold several zeros.  Kept as a crossing, unresolved.
      lists_.crossings.push_back(v);
      lists_.crossing_range.push_back({lo, hi});
      lists_.unresolved.push_back(v);
    } else if (sv == 0) {
      // E(v) = 0 up to rounding and E monotone on R: v is R's only zero, the §5.1 case.
      lists_.crossings.push_back(v);
      lists_.crossing_range.push_back({std::min(lo, tv), std::max(hi, tv)});
      vertex_root_excluded_.push_back(s > 0);
    } else if (const auto t = monotone_zero(oracle_, e_, tv, tf, sv)) {
      // E(v) ≠ 0: R's one zero is a crossing inside e (none if E keeps its sign on R).
      lists_.crossings.push_back(e_.at(*t));
      lists_.crossing_range.push_back({lo, hi});
    }
  }

  SurfaceOracle& oracle_;
  const VoronoiEdge& e_;
  const std::array<Vec3, 2>& shared_;
  VoronoiEdgeLists& lists_;
  // Zeros at Voronoi vertices: whether each would be excluded by §5.1 if it were the only one.
  std::vector<bool> vertex_root_excluded_;
  // Whether a zero next to each end's Voronoi vertex was settled (add_near_vertex()).
  std::array<bool, 2> settled_at_vertex_{false, false};
};

}  // namespace

bool RestrictedDelaunay::kept_connectors_clean(const VoronoiEdgeRecord& r, const TriangleKey& t,
                                               const std::array<VertexId, 2>& apexes, VertexId x) const {
  const VoronoiEdge e = r.edge(del_, t);
  const bool x_is_apex = apexes[0] == x || apexes[1] == x;
  // The bounding box of e's computed ends lies in segment_box(e) (rounding to nearest is above
  // rounding down and below rounding up, and the operations are monotone).
  std::optional<std::array<Vec3, 2>> box;
  for (VertexId apex : apexes) {
    if (apex < 0 || (x_is_apex && apex != x)) continue;
    if (r.segment_signed && !box) {
      BoundingBox b;
      b.add(e.at(e.t0));
      b.add(e.at(e.t1));
      box = std::array<Vec3, 2>{b.lo, b.hi};
    }
    // The vertex v of the cell t·apex and its connector [v, a] to e's line (a ∈ e where e′ ends at v).
    const Vec3 v = voronoi_vertex(del_, {t[0], t[1], t[2], apex});
    const Vec3 a = e.at(dot(v - e.point, e.direction));
    if (box && in_box(v, *box) && in_box(a, *box)) continue;
    if (connector_sign(oracle_, a, v) == 0) return false;
  }
  return true;
}

VoronoiEdgeRecord RestrictedDelaunay::compute(const TriangleKey& t, const std::array<VertexId, 2>* apexes) const {
  VoronoiEdgeRecord r;
  // The lists are gathered here (one scratch per thread), then packed into the record.
  thread_local VoronoiEdgeLists lists;
  lists.clear();
  auto finish = [&] {
    r.set_lists(lists);
    return std::move(r);
  };
  std::array<Vec3, 2> shared{};
  const VoronoiEdge e = voronoi_edge(del_, t, oracle_.clip_box(), apexes, &shared);
  r.set_edge(e);
  if (e.degenerate) {
    // The edge is numerically the point v: Σ passes through it unless SurfaceLine excludes a
    // segment of length 2δ about v along the edge's line.
    const double delta = tolerances::duplicate_sample_relative_distance * oracle_.diagonal();
    const auto near = oracle_.surface_line(e.point, e.direction, e.t0 - delta, e.t0 + delta);
    if (!near.roots.empty() || !near.undecided.empty()) lists.unresolved.push_back(e.at(e.t0));
  }
  if (!e.valid) return finish();
  if (segment_signed(oracle_, e, shared)) {
    r.segment_signed = true;
    return finish();
  }
  const auto result = oracle_.surface_line(e.point, e.direction, e.t0, e.t1);
  EdgeCrossings crossings(oracle_, e, shared, lists);
  crossings.add_roots(result.roots);
  crossings.add_undecided(result.undecided);
  crossings.settle_connectors();
  r.restricted = crossings.restricted();
  return finish();
}

void RestrictedDelaunay::invalidate(const std::vector<VertexId>& vertices, const Domain* grown_into) {
  auto in = [&](VertexId v) { return std::binary_search(vertices.begin(), vertices.end(), v); };
  for (VertexId v : vertices) {
    const bool proved = static_cast<std::size_t>(v) < cells_.size() &&
                        cells_[v].state == CellCertificate::State::proved;
    if (grown_into && proved)
      cells_[v].grown.push_back(*grown_into);
    else
      forget_cell(v);
    if (!del_.contains(v)) continue;
    for (const auto& t : del_.incident_triangles(v))
      if (t[0] == v && in(t[1]) && in(t[2])) erase_record(t);
    for (VertexId w : del_.neighbours(v))
      if (v < w && in(w)) facets_.erase(EdgeKey{v, w});
  }
}

void RestrictedDelaunay::forget(const std::vector<TriangleKey>& triangles, const std::vector<EdgeKey>& edges) {
  for (const auto& t : triangles) erase_record(t);
  for (const auto& e : edges) facets_.erase(e);
}

void RestrictedDelaunay::shrink_facets(const std::vector<EdgeKey>& edges) {
  for (const auto& e : edges) {
    FacetEntry* entry = facets_.find(e);
    if (!entry) continue;
    if (entry->section_certified != 1) {
      facets_.erase(e);
      continue;
    }
    entry->facet = VoronoiFacet{};
    entry->built = false;
  }
}

void RestrictedDelaunay::shrink(const InsertionChange& change) {
  if (!change.local) {
    edges_.clear();
    stars_.clear();
    facets_.clear();
    cells_.clear();
    return;
  }
  forget_destroyed(change);
  for (const auto& t : change.shrunk_triangles)
    if (VoronoiEdgeRecord* r = edges_.find(t)) r->shrunk = true;
}

std::vector<TriangleKey> RestrictedDelaunay::star(VertexId p) {
  std::vector<TriangleKey> out;
  if (every_triangle_recorded_) {
    if (static_cast<std::size_t>(p) < stars_.size()) out = stars_[p];
    std::sort(out.begin(), out.end(), detail::KeyLess{});
    return out;
  }
  for (const auto& t : del_.incident_triangles(p))
    if (voronoi_edge_record(t).restricted) out.push_back(t);
  return out;
}

const std::vector<TriangleKey>& RestrictedDelaunay::star_unordered(VertexId p) {
  thread_local std::vector<TriangleKey> computed;
  if (!every_triangle_recorded_) {
    computed = star(p);
    return computed;
  }
  if (static_cast<std::size_t>(p) < stars_.size()) return stars_[p];
  computed.clear();
  return computed;
}

std::optional<std::array<TriangleKey, 2>> RestrictedDelaunay::restricted_pair(const EdgeKey& e) {
  std::array<TriangleKey, 2> pair;
  std::size_t count = 0;
  auto take = [&](const TriangleKey& t) {
    if (t[0] != e[1] && t[1] != e[1] && t[2] != e[1]) return;
    if (count < 2) pair[count] = t;
    ++count;
  };
  if (every_triangle_recorded_) {
    if (static_cast<std::size_t>(e[0]) < stars_.size())
      for (const auto& t : stars_[e[0]]) take(t);
  } else {
    for (const auto& t : star(e[0])) take(t);
  }
  if (count != 2) return std::nullopt;
  if (pair[1] < pair[0]) std::swap(pair[0], pair[1]);
  return pair;
}

std::vector<std::pair<TriangleKey, Vec3>> RestrictedDelaunay::unresolved_regions() const {
  std::vector<std::pair<TriangleKey, Vec3>> out;
  edges_.for_each([&](const TriangleKey& t, const VoronoiEdgeRecord& r) {
    for (const auto& x : r.unresolved()) out.push_back({t, x});
  });
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<TriangleKey> RestrictedDelaunay::triangles() {
  std::vector<TriangleKey> out;
  if (every_triangle_recorded_) {
    // Every current triangle has its record: Tri S|Σ is the union of the restricted stars, each
    // triangle taken from the star of its smallest vertex.
    for (std::size_t v = 0; v < stars_.size(); ++v)
      for (const auto& t : stars_[v])
        if (static_cast<std::size_t>(t[0]) == v) out.push_back(t);
    std::sort(out.begin(), out.end(), detail::KeyLess{});
    return out;
  }
  for (const auto& t : del_.triangles())
    if (voronoi_edge_record(t).restricted) out.push_back(t);
  return out;
}

}  // namespace delmesh
