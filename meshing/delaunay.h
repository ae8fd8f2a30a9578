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
#include <memory>
#include <optional>
#include <vector>

#include "meshing/surface_mesh.h"

namespace delmesh {

using VertexId = int;
using TriangleKey = std::array<VertexId, 3>;  //!< sorted ascending
using EdgeKey = std::array<VertexId, 2>;      //!< sorted ascending

TriangleKey make_triangle_key(VertexId a, VertexId b, VertexId c);
EdgeKey make_edge_key(VertexId a, VertexId b);

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
  //! Removes the vertex; its id is never reused.  Precondition: contains(id).
  void remove(VertexId id);

  bool contains(VertexId id) const;
  const std::array<double, 3>& point(VertexId id) const;
  bool is_seed(VertexId id) const;
  std::size_t size() const;
  int dimension() const;
  //! Ids of the current vertices, ascending.
  std::vector<VertexId> vertices() const;
  //! Delaunay neighbours of id (ascending).
  std::vector<VertexId> neighbours(VertexId id) const;
  //! Delaunay triangles incident to id (sorted keys, ascending).
  std::vector<TriangleKey> incident_triangles(VertexId id) const;
  //! All Delaunay triangles (ascending).
  std::vector<TriangleKey> triangles() const;
  bool is_triangle(const TriangleKey& t) const;
  bool is_edge(const EdgeKey& e) const;
  //! The vertex nearest to x and its distance.  Precondition: size() > 0.
  std::pair<VertexId, double> nearest(const std::array<double, 3>& x) const;

 private:
  std::unique_ptr<detail::DelaunayImpl> impl_;
};

}  // namespace delmesh
