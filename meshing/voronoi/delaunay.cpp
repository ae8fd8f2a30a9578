#include "meshing/voronoi/delaunay.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <iterator>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Delaunay_triangulation_cell_base_3.h>
#include <CGAL/Triangulation_data_structure_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include "common/errors.h"
#include "meshing/core/detail/id_marks.h"
#include "meshing/core/detail/key_order.h"
#include "meshing/core/detail/vec3.h"

namespace delmesh {

TriangleKey make_triangle_key(VertexId a, VertexId b, VertexId c) {
  // Three compare-exchanges sort three entries.
  if (b < a) std::swap(a, b);
  if (c < b) std::swap(b, c);
  if (b < a) std::swap(a, b);
  return {a, b, c};
}

EdgeKey make_edge_key(VertexId a, VertexId b) { return a < b ? EdgeKey{a, b} : EdgeKey{b, a}; }

namespace detail {

struct VertexInfo {
  VertexId id = -1;
  bool is_seed = false;
};

using Vb = CGAL::Triangulation_vertex_base_with_info_3<VertexInfo, Kernel>;
using Cb = CGAL::Delaunay_triangulation_cell_base_3<Kernel>;
using Tds = CGAL::Triangulation_data_structure_3<Vb, Cb>;
using Dt = CGAL::Delaunay_triangulation_3<Kernel, Tds>;

//! The distinct edges of one insertion's cavity facets: an open-addressing set of edge keys that
//! keeps its table between insertions, so that it allocates only while it grows.
class CavityEdges {
 public:
  //! Empties the set for a cavity whose facets have at most `occurrences` edges in all.
  void start(std::size_t occurrences) {
    std::size_t capacity = 64;
    while (capacity < 2 * occurrences) capacity *= 2;
    if (capacity > slots_.size()) {
      slots_.assign(capacity, empty);
    } else {
      for (std::size_t i : used_) slots_[i] = empty;
    }
    used_.clear();
    mask_ = slots_.size() - 1;
  }
  //! Adds e; returns whether it was not in the set yet.
  bool add(const EdgeKey& e) {
    std::uint64_t h = (static_cast<std::uint64_t>(static_cast<std::uint32_t>(e[0])) << 32) ^
                      static_cast<std::uint32_t>(e[1]);
    h *= 0x9E3779B97F4A7C15ULL;
    for (std::size_t i = static_cast<std::size_t>(h >> 32) & mask_;; i = (i + 1) & mask_) {
      if (KeyEqual{}(slots_[i], e)) return false;
      if (slots_[i][0] < 0) {
        slots_[i] = e;
        used_.push_back(i);
        return true;
      }
    }
  }

 private:
  static constexpr EdgeKey empty{-1, -1};
  std::vector<EdgeKey> slots_;
  std::vector<std::size_t> used_;
  std::size_t mask_ = 0;
};

struct DelaunayImpl {
  Dt dt;
  CavityEdges cavity_edges;  //!< scratch of insert_point(), as are the three lists below
  std::vector<Dt::Facet> cavity_boundary, cavity_internal;
  std::vector<Dt::Cell_handle> cavity_cells;
  std::vector<Dt::Vertex_handle> handles;  // by id; null when removed
  std::vector<std::array<double, 3>> points;
  std::vector<char> seeds;
  std::size_t alive = 0;

  Dt::Vertex_handle handle(VertexId id) const {
    if (id < 0 || id >= static_cast<VertexId>(handles.size()) || handles[id] == Dt::Vertex_handle())
      throw PreconditionViolation("Delaunay: no vertex with id " + std::to_string(id));
    return handles[id];
  }
};

}  // namespace detail

namespace {
std::atomic<std::uint64_t> last_serial{0};
}  // namespace

Delaunay::Delaunay()
    : impl_(std::make_unique<detail::DelaunayImpl>()), points_(&impl_->points), serial_(++last_serial) {}
Delaunay::~Delaunay() = default;
Delaunay::Delaunay(Delaunay&&) noexcept = default;
Delaunay& Delaunay::operator=(Delaunay&&) noexcept = default;

namespace {

// The sorted key of facet (c, i), or nothing if it has the infinite vertex.
template <class Dt>
std::optional<TriangleKey> facet_key(const Dt& dt, const typename Dt::Facet& f) {
  std::array<VertexId, 3> ids{};
  for (int k = 1; k <= 3; ++k) {
    const auto v = f.first->vertex((f.second + k) & 3);
    if (dt.is_infinite(v)) return std::nullopt;
    ids[k - 1] = v->info().id;
  }
  return make_triangle_key(ids[0], ids[1], ids[2]);
}

// The id of a vertex, −1 for the infinite one.
template <class Dt>
VertexId vertex_id(const Dt& dt, typename Dt::Vertex_handle v) {
  return dt.is_infinite(v) ? VertexId(-1) : v->info().id;
}

// The cell c of x (x its vertex ix) as x and its other three vertices (−1 for the infinite one).
template <class Dt>
std::array<VertexId, 4> cell_vertices(const Dt& dt, typename Dt::Cell_handle c, int ix, VertexId x) {
  return {x, vertex_id(dt, c->vertex((ix + 1) & 3)), vertex_id(dt, c->vertex((ix + 2) & 3)),
          vertex_id(dt, c->vertex((ix + 3) & 3))};
}

// Scratch of the star walks, one per thread: its vectors keep their capacity between calls.
struct StarScratch {
  std::vector<detail::Dt::Cell_handle> reached, stack;
};

StarScratch& star_scratch() {
  thread_local StarScratch scratch;
  return scratch;
}

// Visits the cells of vertex v (dimension 3) in the order of CGAL's incident_cells(): depth first
// from v->cell(), each cell when it is first reached, until visit(c) returns true.  Returns that
// cell, or a null handle if there is none.  Like incident_cells(), it marks the cells it reaches
// (the TDS's conflict flag) and clears the marks before it returns.
template <class Visit>
detail::Dt::Cell_handle visit_star(detail::Dt::Vertex_handle v, Visit visit) {
  StarScratch& s = star_scratch();
  s.reached.clear();
  s.stack.clear();
  detail::Dt::Cell_handle found;
  auto reach = [&](detail::Dt::Cell_handle c) {
    c->tds_data().mark_in_conflict();
    s.reached.push_back(c);
    if (visit(c)) {
      found = c;
      return true;
    }
    s.stack.push_back(c);
    return false;
  };
  if (!reach(v->cell())) {
    while (!s.stack.empty() && found == detail::Dt::Cell_handle()) {
      const auto c = s.stack.back();
      s.stack.pop_back();
      for (int i = 0; i < 4; ++i) {
        if (c->vertex(i) == v) continue;
        const auto next = c->neighbor(i);
        if (!next->tds_data().is_clear()) continue;
        if (reach(next)) break;
      }
    }
  }
  for (const auto& c : s.reached) c->tds_data().clear();
  return found;
}

// The first cell of u's star (dimension 3) with the vertex v and, unless w is null, the vertex w,
// or a null handle: CGAL's is_edge(u, v) and is_facet(u, v, w) return the first cell of
// incident_cells(u) with them, which is this one.
detail::Dt::Cell_handle first_star_cell_with(detail::Dt::Vertex_handle u, detail::Dt::Vertex_handle v,
                                             detail::Dt::Vertex_handle w = {}) {
  return visit_star(u, [&](detail::Dt::Cell_handle c) {
    return c->has_vertex(v) && (w == detail::Dt::Vertex_handle() || c->has_vertex(w));
  });
}

// The cells of vertex v (dimension 3) in the order of CGAL's incident_cells(): the thread's
// scratch list, valid until the next walk on this thread.
const std::vector<detail::Dt::Cell_handle>& star_cells(detail::Dt::Vertex_handle v) {
  visit_star(v, [](detail::Dt::Cell_handle) { return false; });
  return star_scratch().reached;
}

// The apexes of facet (c, i): the vertex of c opposite it and that of the neighbour across it (−1
// for the infinite vertex).
template <class Dt>
std::array<VertexId, 2> facet_apexes(const Dt& dt, typename Dt::Cell_handle c, int i) {
  const auto other = c->neighbor(i);
  return {vertex_id(dt, c->vertex(i)), vertex_id(dt, other->vertex(other->index(c)))};
}

}  // namespace

std::optional<VertexId> Delaunay::insert(const std::array<double, 3>& p, bool is_seed) {
  return insert_point(p, is_seed, nullptr, nullptr, -1, nullptr);
}

Insertion Delaunay::insert_tracking(const std::array<double, 3>& p, bool is_seed, VertexId hint,
                                    const NearestTest& accept) {
  Insertion insertion;
  insertion.id = insert_point(p, is_seed, &insertion.change, &insertion.nearest, hint, accept ? &accept : nullptr);
  return insertion;
}

namespace {

// |q − p|² for the point q of vertex u.
double squared_distance(const detail::DelaunayImpl& impl, const detail::Dt::Vertex_handle& u,
                        const std::array<double, 3>& p) {
  using detail::operator-;
  const auto d = impl.points[u->info().id] - p;
  return detail::dot(d, d);
}

// Reports u (at squared distance d2) as p's nearest sample into `nearest` (if asked); false if
// `accept` refuses p.
bool report_nearest(Nearest* nearest, const NearestTest* accept, const detail::Dt::Vertex_handle& u, double d2) {
  const Nearest n{u->info().id, std::sqrt(d2)};
  if (nearest) *nearest = n;
  return !accept || (*accept)(n);
}

// The cavity of `point` (the cells in conflict with it, from `cell` that contains it), its
// boundary facets and its internal facets, into the implementation's scratch lists.
void find_cavity(detail::DelaunayImpl& impl, const Point3& point, detail::Dt::Cell_handle cell) {
  impl.cavity_boundary.clear();
  impl.cavity_internal.clear();
  impl.cavity_cells.clear();
  impl.dt.find_conflicts(point, cell, std::back_inserter(impl.cavity_boundary), std::back_inserter(impl.cavity_cells),
                         std::back_inserter(impl.cavity_internal));
}

// p's nearest sample among the vertices of the cavity, which holds it (insert_tracking() in the
// header), with its squared distance; ties go to the smaller id.
std::pair<detail::Dt::Vertex_handle, double> nearest_cavity_vertex(const detail::DelaunayImpl& impl,
                                                                   const std::array<double, 3>& p) {
  detail::Dt::Vertex_handle best;
  double best_d2 = 0;
  for (const auto& c : impl.cavity_cells)
    for (int k = 0; k < 4; ++k) {
      const auto u = c->vertex(k);
      if (impl.dt.is_infinite(u)) continue;
      const double d2 = squared_distance(impl, u, p);
      if (best == detail::Dt::Vertex_handle() || d2 < best_d2 || (d2 == best_d2 && u->info().id < best->info().id)) {
        best = u;
        best_d2 = d2;
      }
    }
  return {best, best_d2};
}

// The faces the cavity changes, into `change`: an edge of the cavity shrinks if it lies on a
// boundary facet and is destroyed otherwise (the boundary facets' edges are taken first, each edge
// once); the boundary facets shrink and the internal ones are destroyed.
void record_cavity_change(detail::DelaunayImpl& impl, InsertionChange& change) {
  auto& boundary = impl.cavity_boundary;
  auto& internal = impl.cavity_internal;
  detail::CavityEdges& seen = impl.cavity_edges;
  seen.start(3 * (boundary.size() + internal.size()));
  change.shrunk_triangles.reserve(boundary.size());
  change.destroyed_triangles.reserve(internal.size());
  change.shrunk_edges.reserve(3 * boundary.size());
  change.destroyed_edges.reserve(3 * internal.size());
  for (const auto& [facets, triangles, edges] :
       {std::tie(boundary, change.shrunk_triangles, change.shrunk_edges),
        std::tie(internal, change.destroyed_triangles, change.destroyed_edges)})
    for (const auto& f : facets)
      if (const auto t = facet_key(impl.dt, f)) {
        triangles.push_back(*t);
        for (const EdgeKey& e : {EdgeKey{(*t)[0], (*t)[1]}, EdgeKey{(*t)[0], (*t)[2]}, EdgeKey{(*t)[1], (*t)[2]}})
          if (seen.add(e)) edges.push_back(e);
      }
  change.local = true;
}

// Gives the new vertex v (at p) the next id and records it; returns the id.
VertexId register_vertex(detail::DelaunayImpl& impl, const detail::Dt::Vertex_handle& v,
                         const std::array<double, 3>& p, bool is_seed) {
  const VertexId id = static_cast<VertexId>(impl.handles.size());
  v->info().id = id;
  v->info().is_seed = is_seed;
  impl.handles.push_back(v);
  impl.points.push_back(p);
  impl.seeds.push_back(is_seed ? 1 : 0);
  ++impl.alive;
  return id;
}

}  // namespace

std::optional<VertexId> Delaunay::insert_point(const std::array<double, 3>& p, bool is_seed,
                                               InsertionChange* change, Nearest* nearest, VertexId hint,
                                               const NearestTest* accept) {
  for (double c : p)
    if (!std::isfinite(c)) throw PreconditionViolation("Delaunay::insert: non-finite point");
  auto& dt = impl_->dt;
  const Point3 point(p[0], p[1], p[2]);
  if (change) *change = InsertionChange{};
  if (nearest) *nearest = Nearest{};
  detail::Dt::Vertex_handle v;
  if (dt.dimension() == 3) {
    detail::Dt::Locate_type lt;
    int li = 0, lj = 0;
    const auto cell = contains(hint) ? dt.locate(point, lt, li, lj, impl_->handles[hint]->cell())
                                     : dt.locate(point, lt, li, lj);
    if (lt == detail::Dt::VERTEX) {
      if (nearest || accept) report_nearest(nearest, accept, cell->vertex(li), 0);
      return std::nullopt;
    }
    if (change) {
      // The cavity (the cells in conflict with p): its internal facets are destroyed, its boundary
      // facets shrink, and p is starred from its boundary (Bowyer–Watson) without a second search.
      find_cavity(*impl_, point, cell);
      if (nearest || accept) {
        const auto [best, best_d2] = nearest_cavity_vertex(*impl_, p);
        if (!report_nearest(nearest, accept, best, best_d2)) return std::nullopt;
      }
      record_cavity_change(*impl_, *change);
      const auto& boundary = impl_->cavity_boundary;
      v = dt.insert_in_hole(point, impl_->cavity_cells.begin(), impl_->cavity_cells.end(), boundary.front().first,
                            boundary.front().second);
    } else {
      v = dt.insert(point, lt, cell, li, lj);  // insert(): no nearest sample asked for
    }
  } else {
    if ((nearest || accept) && impl_->alive > 0) {
      const auto u = dt.nearest_vertex(point);
      if (!report_nearest(nearest, accept, u, squared_distance(*impl_, u, p))) return std::nullopt;
    }
    const std::size_t before = dt.number_of_vertices();
    v = dt.insert(point);
    if (dt.number_of_vertices() == before) return std::nullopt;  // coincides with a vertex
  }
  return register_vertex(*impl_, v, p, is_seed);
}

void Delaunay::remove(VertexId id) {
  auto v = impl_->handle(id);
  impl_->dt.remove(v);
  impl_->handles[id] = detail::Dt::Vertex_handle();
  --impl_->alive;
}

bool Delaunay::contains(VertexId id) const {
  return id >= 0 && id < static_cast<VertexId>(impl_->handles.size()) &&
         impl_->handles[id] != detail::Dt::Vertex_handle();
}

void Delaunay::bad_point_id() { throw PreconditionViolation("Delaunay::point: bad id"); }

bool Delaunay::is_seed(VertexId id) const { return impl_->seeds.at(id) != 0; }
std::size_t Delaunay::size() const { return impl_->alive; }
int Delaunay::dimension() const { return impl_->dt.dimension(); }

std::vector<VertexId> Delaunay::vertices() const {
  std::vector<VertexId> out;
  out.reserve(impl_->alive);
  for (VertexId id = 0; id < static_cast<VertexId>(impl_->handles.size()); ++id)
    if (impl_->handles[id] != detail::Dt::Vertex_handle()) out.push_back(id);
  return out;
}

std::vector<VertexId> Delaunay::neighbours(VertexId id) const {
  auto v = impl_->handle(id);
  std::vector<VertexId> out;
  const auto& dt = impl_->dt;
  if (dt.dimension() == 3) {
    const auto& cells = star_cells(v);
    out.reserve(3 * cells.size());
    for (const auto& c : cells)
      for (int k = 0; k < 4; ++k) {
        const auto w = c->vertex(k);
        if (w != v && !dt.is_infinite(w)) out.push_back(w->info().id);
      }
    detail::sort_distinct_ids(out);
    return out;
  }
  if (dt.dimension() < 1) return out;
  std::vector<detail::Dt::Vertex_handle> adjacent;
  impl_->dt.finite_adjacent_vertices(v, std::back_inserter(adjacent));
  for (auto w : adjacent) out.push_back(w->info().id);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::vector<TriangleKey> Delaunay::incident_triangles(VertexId id) const {
  auto v = impl_->handle(id);
  std::vector<TriangleKey> out;
  const auto& dt = impl_->dt;
  if (dt.dimension() == 3) {
    // Each facet at v lies in two of v's cells: it is taken from the one at the lower address,
    // as closed_star() does.
    for (const auto& c : star_cells(v)) {
      const int iv = c->index(v);
      for (int j = 0; j < 4; ++j)
        if (j != iv && &*c < &*c->neighbor(j))
          if (const auto t = facet_key(dt, detail::Dt::Facet(c, j))) out.push_back(*t);
    }
  } else if (dt.dimension() == 2) {
    std::vector<detail::Dt::Cell_handle> cells;
    dt.incident_cells(v, std::back_inserter(cells));
    for (auto c : cells) {
      // Triangulation_3::is_infinite(Cell_handle) requires dimension 3: test the vertex directly.
      if (c->has_vertex(dt.infinite_vertex())) continue;
      out.push_back(make_triangle_key(c->vertex(0)->info().id, c->vertex(1)->info().id,
                                      c->vertex(2)->info().id));
    }
  }
  detail::sort_unique(out);
  return out;
}

std::optional<std::array<VertexId, 2>> Delaunay::triangle_apexes(const TriangleKey& t) const {
  const auto& dt = impl_->dt;
  if (dt.dimension() != 3) return std::nullopt;
  for (VertexId id : t)
    if (!contains(id)) return std::nullopt;
  if (t[0] == t[1] || t[0] == t[2] || t[1] == t[2]) return std::nullopt;  // as CGAL's is_facet()
  const auto u = impl_->handles[t[0]], v = impl_->handles[t[1]], w = impl_->handles[t[2]];
  const auto c = first_star_cell_with(u, v, w);
  if (c == detail::Dt::Cell_handle()) return std::nullopt;
  return facet_apexes(dt, c, 6 - c->index(u) - c->index(v) - c->index(w));
}

std::vector<Delaunay::StarTriangle> Delaunay::closed_star(VertexId x,
                                                          std::vector<std::array<VertexId, 4>>* cell_ids) const {
  std::vector<StarTriangle> out;
  if (cell_ids) cell_ids->clear();
  const auto& dt = impl_->dt;
  if (dt.dimension() != 3) return out;
  const auto v = impl_->handle(x);
  const auto& cells = star_cells(v);
  // Each cell has one facet opposite x and shares its three facets at x with other cells.
  thread_local std::vector<StarTriangle> found;
  found.clear();
  found.reserve(cells.size() * 5 / 2 + 1);
  if (cell_ids) cell_ids->reserve(cells.size());
  for (const auto& c : cells) {
    const int ix = c->index(v);
    if (cell_ids) cell_ids->push_back(cell_vertices(dt, c, ix, x));
    for (int j = 0; j < 4; ++j) {
      // A facet containing x lies in two cells of x's star: it is kept from the one at the lower
      // address (the facet opposite x lies in one cell of the star only).
      if (j != ix && &*c->neighbor(j) < &*c) continue;
      const auto t = facet_key(dt, detail::Dt::Facet(c, j));
      if (!t) continue;
      found.push_back({*t, facet_apexes(dt, c, j), j != ix});
    }
  }
  // The keys are distinct, so every sort leaves them in the same sequence: they are sorted as
  // 128-bit words, the key's order (key_order.h) above the triangle's index in `found`.
  thread_local std::vector<unsigned __int128> order;
  order.clear();
  for (std::size_t i = 0; i < found.size(); ++i) {
    const TriangleKey& k = found[i].key;
    order.push_back(static_cast<unsigned __int128>(detail::pair_word(k[0], k[1])) << 64 |
                    detail::order_word(k[2]) << 32 | i);
  }
  std::sort(order.begin(), order.end());
  out.reserve(found.size());
  for (const unsigned __int128 w : order) out.push_back(found[static_cast<std::uint32_t>(w)]);
  return out;
}

std::vector<std::array<VertexId, 4>> Delaunay::incident_cells(VertexId x) const {
  std::vector<std::array<VertexId, 4>> out;
  const auto& dt = impl_->dt;
  if (dt.dimension() != 3) return out;
  const auto v = impl_->handle(x);
  const auto& cells = star_cells(v);
  out.reserve(cells.size());
  for (const auto& c : cells) out.push_back(cell_vertices(dt, c, c->index(v), x));
  return out;
}

std::vector<TriangleKey> Delaunay::edge_triangles(const EdgeKey& e) const {
  std::vector<TriangleKey> out;
  const auto& dt = impl_->dt;
  if (!contains(e[0]) || !contains(e[1])) return out;
  if (dt.dimension() == 3) {
    for (const auto& t : edge_ring(e)) out.push_back(make_triangle_key(e[0], e[1], t.third));
  } else {
    for (const auto& t : incident_triangles(e[0]))
      if (std::find(t.begin(), t.end(), e[1]) != t.end()) out.push_back(t);
  }
  detail::sort_unique(out);
  return out;
}

std::vector<Delaunay::RingTriangle> Delaunay::edge_ring(const EdgeKey& e) const {
  std::vector<RingTriangle> out;
  const auto& dt = impl_->dt;
  if (dt.dimension() != 3 || !contains(e[0]) || !contains(e[1])) return out;
  if (e[0] == e[1]) return out;  // as CGAL's is_edge()
  const auto u = impl_->handles[e[0]], v = impl_->handles[e[1]];
  const auto c = first_star_cell_with(u, v);
  if (c == detail::Dt::Cell_handle()) return out;
  const int i = c->index(u), j = c->index(v);
  auto start = dt.incident_facets(detail::Dt::Edge(c, i, j));
  auto f = start;
  do {
    if (const auto t = facet_key(dt, *f)) {
      VertexId third = -1;
      for (VertexId v : *t)
        if (v != e[0] && v != e[1]) third = v;
      out.push_back({third, facet_apexes(dt, f->first, f->second)});
    }
  } while (++f != start);
  return out;
}

std::vector<EdgeKey> Delaunay::incident_edges(VertexId id) const {
  std::vector<EdgeKey> out;
  for (VertexId w : neighbours(id)) out.push_back(make_edge_key(id, w));
  std::sort(out.begin(), out.end(), detail::KeyLess{});
  return out;
}

std::size_t Delaunay::triangle_count() const {
  const auto& dt = impl_->dt;
  if (dt.dimension() == 3) return dt.number_of_finite_facets();
  return dt.dimension() == 2 ? triangles().size() : 0;
}

std::vector<TriangleKey> Delaunay::triangles() const {
  std::vector<TriangleKey> out;
  const auto& dt = impl_->dt;
  if (dt.dimension() == 3) {
    for (auto f = dt.finite_facets_begin(); f != dt.finite_facets_end(); ++f) {
      const auto c = f->first;
      const int i = f->second;
      out.push_back(make_triangle_key(c->vertex((i + 1) & 3)->info().id,
                                      c->vertex((i + 2) & 3)->info().id,
                                      c->vertex((i + 3) & 3)->info().id));
    }
  } else if (dt.dimension() == 2) {
    // CGAL's cell iterators are empty below dimension 3: collect the stars instead.
    for (VertexId id : vertices()) {
      const auto star = incident_triangles(id);
      out.insert(out.end(), star.begin(), star.end());
    }
  }
  detail::sort_unique(out);
  return out;
}

bool Delaunay::is_triangle(const TriangleKey& t) const {
  const auto& dt = impl_->dt;
  if (dt.dimension() < 2) return false;
  for (VertexId id : t)
    if (!contains(id)) return false;
  if (t[0] == t[1] || t[0] == t[2] || t[1] == t[2]) return false;  // as CGAL's is_facet()
  const auto u = impl_->handles[t[0]], v = impl_->handles[t[1]], w = impl_->handles[t[2]];
  if (dt.dimension() == 3)
    return first_star_cell_with(u, v, w) != detail::Dt::Cell_handle();
  detail::Dt::Cell_handle c;
  int i, j, k;
  return dt.is_facet(u, v, w, c, i, j, k);
}

bool Delaunay::is_edge(const EdgeKey& e) const {
  const auto& dt = impl_->dt;
  if (dt.dimension() < 1) return false;
  if (!contains(e[0]) || !contains(e[1])) return false;
  if (dt.dimension() < 2) {
    const auto n = neighbours(e[0]);
    return std::binary_search(n.begin(), n.end(), e[1]);
  }
  if (e[0] == e[1]) return false;  // as CGAL's is_edge()
  const auto u = impl_->handles[e[0]], v = impl_->handles[e[1]];
  if (dt.dimension() == 3)
    return first_star_cell_with(u, v) != detail::Dt::Cell_handle();
  detail::Dt::Cell_handle c;
  int i, j;
  return dt.is_edge(u, v, c, i, j);
}

std::pair<VertexId, double> Delaunay::nearest(const std::array<double, 3>& x, VertexId hint) const {
  if (impl_->alive == 0) throw PreconditionViolation("Delaunay::nearest: empty triangulation");
  const Point3 point(x[0], x[1], x[2]);
  auto v = contains(hint) ? impl_->dt.nearest_vertex(point, impl_->handles[hint]->cell())
                          : impl_->dt.nearest_vertex(point);
  return {v->info().id, detail::distance(impl_->points[v->info().id], x)};
}

}  // namespace delmesh
