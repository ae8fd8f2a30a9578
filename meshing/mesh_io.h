#pragma once
//! \file mesh_io.h
//! Reading and writing triangle meshes as OFF, PLY or OBJ, chosen by the file extension.
//! Output is readable by MeshLab and ParaView.

#include <string>

#include "meshing/surface_mesh.h"

namespace delmesh {

//! Writes mesh to path (.off, .ply or .obj).  Throws InvalidInput for another extension and
//! std::runtime_error if the file cannot be written.  Writes to a temporary file and renames it,
//! so an existing file is never left half-written.
void write_mesh(const SurfaceMesh& mesh, const std::string& path);

//! Reads a triangle mesh from path.  Throws InvalidInput if the file is missing, unreadable,
//! corrupt, not a triangle mesh, or has an unknown extension.
SurfaceMesh read_mesh(const std::string& path);

}  // namespace delmesh
