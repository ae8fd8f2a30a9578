#pragma once
//! \file mesh_io.h
//! Reading and writing triangle meshes as OFF, PLY or OBJ, chosen by the file extension
//! (case-insensitive).  Output is ASCII with 17 significant digits (every double round-trips, and
//! the same mesh always gives the same bytes) and is readable by MeshLab and ParaView.

#include <array>
#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

#include "common/enum_names.h"
#include "meshing/mesh_soup.h"
#include "meshing/surface_mesh.h"

namespace delmesh {

//! The mesh file formats, chosen by the file extension (case-insensitive): .off, .ply, .obj.
enum class MeshFormat { off, ply, obj };
constexpr auto enum_names(MeshFormat) {
  return name_table<MeshFormat>("MeshFormat", {{MeshFormat::off, "off"}, {MeshFormat::ply, "ply"}, {MeshFormat::obj, "obj"}});
}
inline std::ostream& operator<<(std::ostream& out, MeshFormat format) { return write_enum(out, format); }

//! The format of a mesh file named `path`, by its extension.  Throws InvalidInput for another
//! extension (or none).
MeshFormat mesh_format(const std::string& path);

//! Writes the soup to `out` in `format` (the points in index order, then the triangles), and
//! nothing else: opening, renaming and checking `out` for a failed write are the caller's.
//! \pre every index is below soup.points.size() (else PreconditionViolation).
void write_triangle_soup(const TriangleSoup& soup, std::ostream& out, MeshFormat format);
//! The same for the live vertices and the faces of mesh (InvalidInput for a non-triangle face).
void write_mesh(const SurfaceMesh& mesh, std::ostream& out, MeshFormat format);

//! Writes mesh to path (.off, .ply or .obj; the live vertices in index order, then the faces).
//! Throws InvalidInput for another extension or a non-triangle face, and std::runtime_error if the
//! file cannot be written.  Writes to a temporary file in the same directory and renames it, so an
//! existing file is never left half-written (the program's outputs go through
//! apps/output_files.h instead, which also handles devices, links and groups of files).
void write_mesh(const SurfaceMesh& mesh, const std::string& path);
//! The same for a soup (the writer used by write_mesh).  \pre every index is below
//! soup.points.size() (else PreconditionViolation).
void write_triangle_soup(const TriangleSoup& soup, const std::string& path);

//! Reads a polygon soup from path (OFF, ASCII or binary PLY, OBJ).  Throws InvalidInput, with
//! the path and the reason, if the file is missing, unreadable, truncated or corrupt, has no
//! faces, has a face with fewer than three vertices or one that repeats a vertex, has an index
//! out of range or a non-finite coordinate, or has an unknown extension.  Works for any soup
//! (non-manifold too).
PolygonSoup read_polygon_soup(const std::string& path);

//! Reads a triangle soup from path: read_polygon_soup, and throws InvalidInput also for a face
//! that is not a triangle.  Works for any soup (non-manifold too), so that the checker can report
//! on bad meshes.
TriangleSoup read_triangle_soup(const std::string& path);

//! Reads a triangle mesh from path: read_triangle_soup, then builds the Surface_mesh.  Throws
//! InvalidInput additionally if the soup is not a polygon mesh (an edge in more than two
//! triangles, a pinched vertex, inconsistent orientation), which Surface_mesh cannot represent.
SurfaceMesh read_mesh(const std::string& path);

}  // namespace delmesh
