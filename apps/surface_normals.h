#pragma once
//! \file surface_normals.h
//! The unit normals ∇E/|∇E| of an implicit surface at the vertices of a mesh of it, for the
//! point data of a .vtp file (meshing/mesh_io.h).

#include "meshing/mesh_io.h"
#include "meshing/surface_mesh.h"
#include "symbolic/surface.h"

namespace delmesh::app {

//! ∇E(v)/|∇E(v)| at each live vertex v of mesh, in index order (the order write_mesh writes the
//! vertices in): ∇E compiled once from the exact gradient of `surface` (symbolic/compiled_system.h)
//! and evaluated in double at the vertex, then divided by its Euclidean length.  The zero vector
//! where ∇E(v) is zero or not finite (E is not smooth there, or overflows).
PointNormals surface_normals(const Surface& surface, const SurfaceMesh& mesh);

}  // namespace delmesh::app
