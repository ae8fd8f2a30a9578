#pragma once
//! \file mesh_checker.h
//! An independent checker: everything is computed from the mesh alone (components, Euler
//! characteristic and genus per component, closed / manifold / orientable, minimum angle,
//! maximum radius-edge ratio, maximum roughness), never from the mesher's state.  It is what the
//! tests and experiments use to verify Theorem 6.1 (topology, radius-edge ratio, roughness).
//!
//! Conventions (all combinatorics are by vertex index; coincident points are not merged):
//! - V counts the vertices referenced by some triangle (unreferenced points are reported apart),
//!   E the distinct undirected edges {i, j}, F the triangles; χ = V − E + F.
//! - Components are those of the graph whose nodes are the triangles and in which two triangles
//!   are adjacent iff they share a VERTEX (so a bow-tie pinched at one vertex is one component).
//! - closed: every edge lies in exactly two triangles.
//! - manifold: closed, and the link of every vertex (the opposite edges of its triangles, as a
//!   multigraph) is a single cycle.
//! - orientable: no edge lies in more than two triangles, and the triangles can be re-oriented so
//!   that every edge shared by two triangles is traversed in opposite directions (BFS over the
//!   edge adjacency).  oriented: the GIVEN orientation already has that property (every directed
//!   edge is used at most once).
//! - genus g = (2 − χ)/2 of a component that is a closed orientable 2-manifold; elsewhere the
//!   genus is not defined: −1 in the structs, null in the JSON.
//! - boundary loops: the connected pieces of the graph formed by the boundary edges (edges in
//!   exactly one triangle).  On a 2-manifold with boundary these are its boundary circles; two
//!   circles that touch at a (non-manifold) vertex count as one piece.
//! - non-manifold edges: in three or more triangles; non-manifold vertices: the link is neither
//!   one cycle nor one path (e.g. a vertex pinching two fans together).
//! - Angles and ratios of a triangle with zero area: min angle 0, radius-edge ratio +∞.
//! - roughness of an edge shared by exactly two triangles (§6.1): π − internal dihedral angle,
//!   i.e. the angle between the two triangle normals after orienting the pair consistently.
//! - Angles, radius-edge ratios, roughness and edge lengths are computed on vectors first scaled
//!   by a power of two (exact) to a largest component in [1, 2) (per triangle for its area and
//!   ratio), so they do not depend on the mesh's scale: a mesh scaled by 1e200 or 1e-300 gets the
//!   measures of the unscaled one up to rounding.  signed_volume is the plain sum (it overflows
//!   or underflows where the cube of the scale does).

#include <array>
#include <cstddef>
#include <optional>
#include <ostream>
#include <vector>

#include <nlohmann/json.hpp>

#include "meshing/core/surface_mesh.h"

namespace delmesh {

//! One connected component (see the file comment for the adjacency used).
struct ComponentReport {
  std::size_t vertices = 0, edges = 0, triangles = 0;
  int euler_characteristic = 0;
  bool closed = false, manifold = false, orientable = false;
  int genus = -1;  //!< (2 − χ)/2 if closed, manifold and orientable, else −1 (undefined)
  std::size_t boundary_edges = 0, boundary_loops = 0;
  std::size_t nonmanifold_edges = 0, nonmanifold_vertices = 0;
};

struct MeshReport {
  std::size_t vertices = 0, edges = 0, triangles = 0;
  std::size_t unreferenced_vertices = 0;  //!< points used by no triangle (not counted in V)
  int components = 0;
  int euler_characteristic = 0;          //!< V − E + F of the whole mesh
  std::vector<int> genus_per_component;  //!< sorted ascending; −1 where undefined (not a closed orientable 2-manifold)
  //! Per component, sorted by (genus, −triangles): the same order as genus_per_component.
  std::vector<ComponentReport> component_reports;
  bool closed = false;                   //!< every edge has exactly two incident triangles
  bool manifold = false;                 //!< closed, and every vertex link is one cycle
  bool orientable = false;               //!< consistently oriented triangles exist
  bool oriented = false;                 //!< the given triangles are consistently oriented
  std::size_t boundary_edges = 0;        //!< edges in exactly one triangle
  std::size_t boundary_loops = 0;        //!< connected pieces of the boundary edges (file comment)
  std::size_t nonmanifold_edges = 0;     //!< edges in three or more triangles
  std::size_t nonmanifold_vertices = 0;  //!< vertices whose link is not one cycle or one path
  double signed_volume = 0;              //!< Σ over triangles of det(a, b, c)/6 (> 0: outward, if closed)
  double min_angle_deg = 0;
  double max_radius_edge_ratio = 0;      //!< circumradius / shortest edge
  double max_roughness_rad = 0;          //!< π − dihedral angle, over interior edges
  double min_edge_length = 0, max_edge_length = 0;
  //! Edges that both of their triangles traverse in the same direction (so oriented is false).
  std::size_t misoriented_edges = 0;
  //! Where the first defect of each kind lies, for messages that say where: edges as vertex
  //! indices {lo, hi} with lo < hi, the lexicographically smallest of their kind; the vertex of
  //! smallest index.  Empty when the mesh has no such defect.  (Not written by to_json.)
  std::optional<std::array<std::size_t, 2>> first_boundary_edge, first_nonmanifold_edge,
      first_misoriented_edge;
  std::optional<std::size_t> first_nonmanifold_vertex;

  //! True iff closed, manifold and orientable with exactly these genera (sorted ascending).
  bool has_topology(const std::vector<int>& genus_per_component) const;
};

//! Checks a triangle soup given as points and index triples (duplicates are not merged).
//! Throws InvalidInput if an index is out of range, a triangle repeats a vertex index, or a
//! referenced point has a non-finite coordinate.
MeshReport check_mesh(const std::vector<Point3>& points,
                      const std::vector<std::array<std::size_t, 3>>& triangles);
//! Checks a Surface_mesh (its faces as a soup).  Throws InvalidInput if a face is not a triangle.
MeshReport check_mesh(const SurfaceMesh& mesh);

//! The faces of a Surface_mesh as a soup: points in vertex order, triangles as index triples.
//! Throws InvalidInput if a face is not a triangle.
void mesh_to_soup(const SurfaceMesh& mesh, std::vector<Point3>& points,
                  std::vector<std::array<std::size_t, 3>>& triangles);

//! Every field but misoriented_edges and the first-defect locations, with the key names of the
//! statistics JSON (docs/cli.md): vertices, edges, triangles, components, euler_characteristic,
//! genus_per_component, closed, manifold, closed_manifold, orientable, oriented, min_angle_deg, max_radius_edge_ratio, max_roughness_rad…
//! plus boundary_edges, boundary_loops, nonmanifold_edges, nonmanifold_vertices (also per
//! component).  A radius-edge ratio of +∞ and an undefined genus are written as null.
nlohmann::json to_json(const MeshReport& report);
std::ostream& operator<<(std::ostream& out, const MeshReport& report);

}  // namespace delmesh
