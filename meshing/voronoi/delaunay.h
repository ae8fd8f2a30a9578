#pragma once
//! \file delaunay.h
//! The Delaunay triangulation Del S of the sample set S (CGAL Delaunay_triangulation_3 with exact
//! predicates), with dynamic insertion and removal.  Every vertex carries a stable integer id
//! (its insertion order, never reused) and whether it is a seed of SampleTopology (§5.4).
//!
//! Simplices are named by their sorted vertex ids (TriangleKey, EdgeKey); this is how every cache
//! of the mesher is keyed.  The triangulation may have dimension < 3 (e.g. the four critical
//! points of a torus in a generic height direction are coplanar); the queries below work in every
//! dimension: a Delaunay triangle is a 2-face of Del S (a finite facet in dimension 3, a finite
//! cell in dimension 2, none below), a Delaunay edge a finite 1-face.

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "meshing/core/simplex_keys.h"
#include "meshing/core/surface_mesh.h"

namespace delmesh {

TriangleKey make_triangle_key(VertexId a, VertexId b, VertexId c);
EdgeKey make_edge_key(VertexId a, VertexId b);

//! What one insertion changed in Del S (Bowyer–Watson: the cells in conflict with x form a
//! star-shaped cavity, replaced by the cone from x over its boundary).
//! - destroyed: the triangles and edges strictly inside the cavity; they are no longer in Del S.
//! - shrunk: the triangles and edges on the cavity boundary; they stay in Del S, and their dual
//!   Voronoi edges and facets are now subsets of what they were (V_x took a part of them).
//! - every triangle and edge containing x is new.
//! Every other simplex keeps its dual Voronoi face unchanged.  Each list holds distinct keys in no
//! particular order (that of CGAL's search of the cavity).  `local` is false when this could not
//! be described locally (Del S had dimension < 3 before or after the insertion): then every dual
//! face may have changed.
struct InsertionChange {
  bool local = false;
  std::vector<TriangleKey> destroyed_triangles, shrunk_triangles;
  std::vector<EdgeKey> destroyed_edges, shrunk_edges;
};

//! A sample nearest to a point and its distance |point − sample| (id −1 when there is no sample).
struct Nearest {
  VertexId id = -1;
  double distance = 0;
};

//! Decides from the sample nearest to a point whether the point is inserted.
using NearestTest = std::function<bool(const Nearest&)>;

//! What Delaunay::insert_tracking() returns: the new vertex's id (nothing if the point coincides
//! with a vertex or was refused; `change` is then empty), what the insertion changed, and the
//! sample nearest to the point before the insertion.
struct Insertion {
  std::optional<VertexId> id;
  InsertionChange change;
  Nearest nearest;
};

namespace detail {
struct DelaunayImpl;
}

class Delaunay {
 public:
  Delaunay();
  ~Delaunay();
  Delaunay(Delaunay&&) noexcept;
  Delaunay& operator=(Delaunay&&) noexcept;

  //! Inserts p.  Returns the new vertex id, or nothing if p coincides with an existing vertex.
  std::optional<VertexId> insert(const std::array<double, 3>& p, bool is_seed);
  //! The same, and what the insertion changed (see InsertionChange) and p's nearest sample before
  //! it.  `hint`, if a current vertex near p, starts the point location there (the result does
  //! not depend on it; the cost of the walk does).  If `accept` is given and S is not empty, p is
  //! inserted only if accept(nearest) holds; otherwise Del S is left as it was.
  //! In dimension 3 the nearest sample q costs no search of its own: it is a vertex of a cell in
  //! conflict with p, read off the cavity that the insertion computes anyway.  Proof: a point r of
  //! the closed ball with diameter pq other than p and q sees pq at an angle of at least π/2, so
  //! |pr|² ≤ |pq|² − |rq|² < |pq|²; as no sample is closer to p than q, that ball holds no other
  //! sample, pq is an edge of every Delaunay triangulation of S ∪ {p}, and every edge at p joins
  //! it to a vertex of the cavity's boundary.  Among samples at the same distance (in floating
  //! point) the least id is taken.
  Insertion insert_tracking(const std::array<double, 3>& p, bool is_seed, VertexId hint = -1,
                            const NearestTest& accept = {});
  //! Removes the vertex; its id is never reused.  Precondition: contains(id).
  void remove(VertexId id);

  bool contains(VertexId id) const;
  //! The point of a vertex ever inserted (removed ones keep theirs); throws PreconditionViolation
  //! for another id.
  const std::array<double, 3>& point(VertexId id) const {
    if (id < 0 || static_cast<std::size_t>(id) >= points_->size()) bad_point_id();
    return (*points_)[static_cast<std::size_t>(id)];
  }
  bool is_seed(VertexId id) const;
  std::size_t size() const;
  //! A number that no other Delaunay made in this process has (a move passes it on).  With ids
  //! never reused and points never changed, (serial(), ids) always names the same points, so a
  //! value computed from them may be kept under that key.
  std::uint64_t serial() const { return serial_; }
  int dimension() const;
  //! Ids of the current vertices, ascending.
  std::vector<VertexId> vertices() const;
  //! Delaunay neighbours of id (ascending).
  std::vector<VertexId> neighbours(VertexId id) const;
  //! Delaunay triangles incident to id (sorted keys, ascending).
  std::vector<TriangleKey> incident_triangles(VertexId id) const;
  //! In dimension 3: the vertices opposite the Delaunay triangle t in its two cells (−1 for the
  //! infinite vertex), or nothing if t is not a triangle of Del S.  Below dimension 3: nothing.
  std::optional<std::array<VertexId, 2>> triangle_apexes(const TriangleKey& t) const;
  //! One triangle of the closed star of a vertex x: its key, its apexes (as triangle_apexes), and
  //! whether it contains x (otherwise it is opposite x in one of x's cells: a link triangle).
  struct StarTriangle {
    TriangleKey key;
    std::array<VertexId, 2> apexes;
    bool contains_vertex;
  };
  //! In dimension 3: every finite triangle of the cells incident to x, once each, ascending by
  //! key.  Below dimension 3: empty.  If `cells` is given it receives incident_cells(x), read in
  //! the same walk.
  std::vector<StarTriangle> closed_star(VertexId x, std::vector<std::array<VertexId, 4>>* cells = nullptr) const;
  //! In dimension 3: the vertices of the cells incident to x, x first (−1 for the infinite
  //! vertex), in CGAL's order of the cells.  Below dimension 3: empty.
  std::vector<std::array<VertexId, 4>> incident_cells(VertexId x) const;
  //! Delaunay triangles that contain the edge e (sorted keys, ascending; empty if e is not an edge).
  std::vector<TriangleKey> edge_triangles(const EdgeKey& e) const;
  //! A finite triangle pqr around a Delaunay edge pq: its third vertex r and its apexes (as
  //! triangle_apexes).
  struct RingTriangle {
    VertexId third;
    std::array<VertexId, 2> apexes;
  };
  //! In dimension 3: the finite triangles around the edge e, in the order of the cells around e
  //! (one circulation, no lookup per triangle); empty if e is not an edge.  Below dimension 3:
  //! empty.
  std::vector<RingTriangle> edge_ring(const EdgeKey& e) const;
  //! Delaunay edges incident to id (sorted keys, ascending).
  std::vector<EdgeKey> incident_edges(VertexId id) const;
  //! All Delaunay triangles (ascending).
  std::vector<TriangleKey> triangles() const;
  //! The number of Delaunay triangles, triangles().size(), counted without listing them in
  //! dimension 3.
  std::size_t triangle_count() const;
  bool is_triangle(const TriangleKey& t) const;
  bool is_edge(const EdgeKey& e) const;
  //! The vertex nearest to x and its distance (the search starts at `hint` if it is a current
  //! vertex).  Precondition: size() > 0.
  std::pair<VertexId, double> nearest(const std::array<double, 3>& x, VertexId hint = -1) const;

 private:
  //! insert() and insert_tracking(): `change` and `nearest` are filled when given, and `accept`
  //! (if given) is asked before anything changes.
  std::optional<VertexId> insert_point(const std::array<double, 3>& p, bool is_seed, InsertionChange* change,
                                       Nearest* nearest, VertexId hint, const NearestTest* accept);

  [[noreturn]] static void bad_point_id();

  std::unique_ptr<detail::DelaunayImpl> impl_;
  //! impl_->points, read inline by point() (the implementation, hence the vector, never moves).
  const std::vector<std::array<double, 3>>* points_;
  std::uint64_t serial_;
};

}  // namespace delmesh
