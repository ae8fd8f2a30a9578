#pragma once
//! \file surface_normals.h
//! The point data of a .vtp file of a mesh of an implicit surface (meshing/inputs/mesh_io.h): the unit
//! normals ∇E/|∇E| at its vertices, and the distance bounds of its gradient-flow certificate
//! carried from its triangles to its vertices.

#include <vector>

#include "meshing/core/surface_mesh.h"
#include "meshing/inputs/implicit_oracle.h"
#include "meshing/inputs/mesh_io.h"

namespace delmesh::app {

//! ∇E(v)/|∇E(v)| at each live vertex v of mesh, in index order (the order write_mesh writes the
//! vertices in): ∇E evaluated in double by the oracle's compiled gradient (ImplicitOracle::gradient),
//! then divided by its Euclidean length (std::hypot, so that neither overflow nor underflow of its
//! square changes it).  The zero vector where ∇E(v) is zero or not finite (E is not smooth there,
//! or overflows).
PointNormals surface_normals(const ImplicitOracle& oracle, const SurfaceMesh& mesh);

//! Per live vertex of mesh, in index order: the least of triangle_bounds over the faces around it.
//! triangle_bounds holds one number per face in index order, each bounding the distance to Σ of
//! every point of its closed triangle (DelMeshResult::triangle_distance_bounds: the gradient-flow
//! certificate's per-triangle bounds, gradient_flow_certificate.h, which bound d(x, Σ) for every
//! x of the triangle, its corners included, rounded up); so each result bounds the distance from
//! its vertex to Σ.  Empty (no bound is made up) if triangle_bounds is empty, if it does not have
//! one finite number >= 0 per face, or if a vertex has no face around it.
PointDistances vertex_distance_bounds(const SurfaceMesh& mesh, const std::vector<double>& triangle_bounds);

}  // namespace delmesh::app
