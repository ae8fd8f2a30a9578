#pragma once
//! \file simplex_keys.h
//! The names of samples and simplices: every vertex of Del S carries a stable integer id (its
//! insertion order, never reused; −1 is CGAL's infinite vertex), and a triangle or an edge is named
//! by its vertex ids sorted ascending.  Every cache of the mesher is keyed so
//! (meshing/voronoi/delaunay.h: make_triangle_key, make_edge_key).

#include <array>

namespace delmesh {

using VertexId = int;
using TriangleKey = std::array<VertexId, 3>;  //!< sorted ascending
using EdgeKey = std::array<VertexId, 2>;      //!< sorted ascending

}  // namespace delmesh
