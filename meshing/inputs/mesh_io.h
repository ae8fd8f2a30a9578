#pragma once
//! \file mesh_io.h
//! Reading and writing triangle meshes, the format chosen by the file extension (case-insensitive).
//! OFF, PLY, OBJ and STL are read (STL binary or ASCII) and written (STL as binary); VTK XML
//! PolyData (.vtp) is written only.
//! OFF, PLY, OBJ and VTP output is ASCII with 17 significant digits (every double round-trips, and
//! the same mesh always gives the same bytes); STL output is binary, with float32 coordinates as
//! the format has them.  All are readable by MeshLab or ParaView (.vtp by ParaView and meshio).

#include <array>
#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

#include "common/enum_names.h"
#include "meshing/core/mesh_soup.h"
#include "meshing/core/surface_mesh.h"

namespace delmesh {

//! The mesh file formats written, chosen by the file extension (case-insensitive): .off, .ply,
//! .obj, .stl (binary STL, CGAL::IO::write_STL: an 80-byte header, then per triangle its unit
//! normal and corners as float32), .vtp (VTK XML PolyData, ASCII: the points, the triangles as
//! Polys and, when given, the point data "Normals" and "certified_distance").
enum class MeshFormat { off, ply, obj, stl, vtp };
constexpr auto enum_names(MeshFormat) {
  return name_table<MeshFormat>("MeshFormat", {{MeshFormat::off, "off"},
                                               {MeshFormat::ply, "ply"},
                                               {MeshFormat::obj, "obj"},
                                               {MeshFormat::stl, "stl"},
                                               {MeshFormat::vtp, "vtp"}});
}
inline std::ostream& operator<<(std::ostream& out, MeshFormat format) { return write_enum(out, format); }

//! The format of a mesh file named `path`, by its extension.  Throws InvalidInput for another
//! extension (or none), with a message that lists .off, .ply, .obj, .stl and .vtp.
MeshFormat mesh_format(const std::string& path);

//! One vector per point of a soup (per live vertex of a mesh, in index order): the unit normals
//! a .vtp file carries as its point data "Normals".  Empty: none.
using PointNormals = std::vector<std::array<double, 3>>;

//! One number per point (per live vertex of a mesh, in index order): a proved upper bound on the
//! distance from the point to the surface it approximates, which a .vtp file carries as its point
//! data "certified_distance" (Float64, one component).  Empty: none.  The writer states no bound
//! of its own: the caller passes only numbers a certificate proved.
using PointDistances = std::vector<double>;

//! Writes the soup to `out` in `format` (the points in index order, then the triangles), and
//! nothing else: opening, renaming and checking `out` for a failed write are the caller's.
//! `normals` and `distances` are written by MeshFormat::vtp only; the other formats ignore them
//! (their bytes are the same with or without them), and so is a .vtp's without them.
//! \pre every index is below soup.points.size(), normals is empty or has one vector per point,
//! and distances is empty or has one finite number >= 0 per point (else PreconditionViolation).
void write_triangle_soup(const TriangleSoup& soup, std::ostream& out, MeshFormat format,
                         const PointNormals& normals = {}, const PointDistances& distances = {});
//! The same for the live vertices and the faces of mesh (InvalidInput for a non-triangle face).
void write_mesh(const SurfaceMesh& mesh, std::ostream& out, MeshFormat format, const PointNormals& normals = {},
                const PointDistances& distances = {});

//! Writes mesh to path (.off, .ply, .obj, .stl or .vtp; the live vertices in index order, then
//! the faces).
//! Throws InvalidInput for another extension or a non-triangle face, and std::runtime_error if the
//! file cannot be written.  Writes to a temporary file in the same directory and renames it, so an
//! existing file is never left half-written (the program's outputs go through
//! apps/output_files.h instead, which also handles devices, links and groups of files).
void write_mesh(const SurfaceMesh& mesh, const std::string& path);
//! The same for a soup (the writer used by write_mesh).  \pre every index is below
//! soup.points.size() (else PreconditionViolation).
void write_triangle_soup(const TriangleSoup& soup, const std::string& path);

//! Reads a polygon soup from path (OFF, ASCII or binary PLY, OBJ, binary or ASCII STL).  STL's
//! triangles, which repeat their corners' coordinates, are indexed: exactly equal coordinates are
//! one point, numbered in the order of first appearance (detail/mesh_readers.h: read_stl), so
//! that the soup's connectivity can be checked like the other formats'.  Throws InvalidInput,
//! with the path and the reason, if the file is missing, unreadable, truncated or corrupt, has no
//! faces, has a face with fewer than three vertices or one that repeats a vertex, has an index
//! out of range or a non-finite coordinate, or has another extension (.vtp, which is written,
//! included).  Works for any soup (non-manifold too).
PolygonSoup read_polygon_soup(const std::string& path);

//! Reads a triangle soup from path: read_polygon_soup, and throws InvalidInput also for a face
//! that is not a triangle.  Works for any soup (non-manifold too), so that the checker can report
//! on bad meshes.
TriangleSoup read_triangle_soup(const std::string& path);

//! The soup with every face of more than three vertices triangulated as read_input_mesh does it
//! (meshing/inputs/input_mesh.h: PMP::triangulate_faces, a constrained Delaunay triangulation of the
//! face in its best-fitting plane, no convexity needed), each face on its own, so that any soup
//! (open, non-manifold, inconsistently oriented) can be triangulated: the triangles of a face
//! keep its orientation and replace it in the face order; triangles are kept as they are, and so
//! are the points.  Throws InvalidInput naming `source` (a path) for a face that cannot be
//! triangulated (a degenerate polygon).  \pre every index is below soup.points.size().
TriangleSoup triangulate_polygons(const PolygonSoup& soup, const std::string& source);

//! Reads a triangle mesh from path: read_triangle_soup, then builds the Surface_mesh.  Throws
//! InvalidInput additionally if the soup is not a polygon mesh (an edge in more than two
//! triangles, a pinched vertex, inconsistent orientation), which Surface_mesh cannot represent.
SurfaceMesh read_mesh(const std::string& path);

}  // namespace delmesh
