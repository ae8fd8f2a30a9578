#pragma once
//! \file mesh_readers.h
//! The OFF, PLY and STL readers behind read_polygon_soup (meshing/inputs/mesh_io.h).  They parse the whole
//! file themselves, so that no declared count, list size, colour or index reaches an allocation or
//! a conversion before it has been checked against the file: memory stays proportional to the
//! file's size and every corrupt file ends as one InvalidInput that says what is wrong and where.
//!
//! OFF: the optional keyword [ST][C][N][4][n]OFF, optionally followed by BINARY (Geomview's binary
//! layout: big-endian int32 counts and indices, float32 coordinates); "NV NF [NE]"; NV vertices of
//! 3 coordinates (4 with the prefix 4, divided by the last; other dimensions are refused), whose
//! normal, colour and texture fields are skipped; NF faces, one per line, "n i_1 ... i_n [colour]".
//! '#' starts a comment in the ASCII form.
//!
//! PLY: "ply", "format ascii|binary_little_endian|binary_big_endian 1.0", comment and obj_info
//! lines, elements with scalar and list properties of the eleven PLY types (both naming schemes),
//! "end_header".  The element "vertex" must have the scalar properties x, y, z; the element "face"
//! a list property vertex_indices (or vertex_index).  Other elements and properties are read and
//! skipped.
//!
//! STL, binary: an 80-byte header (any bytes, "solid" included), a little-endian uint32 triangle
//! count N, then N records of 50 bytes (normal and three corners as little-endian float32, a
//! uint16 attribute); the file is exactly 84 + 50·N bytes.  ASCII: "solid [name]", facets
//! "facet normal nx ny nz / outer loop / vertex x y z (three times) / endloop / endfacet",
//! "endsolid [name]", keywords in any case; several solids may follow each other.  The normals
//! are skipped (the corners' order gives the orientation).

#include <cstdint>
#include <string>

#include "meshing/core/mesh_soup.h"

namespace delmesh::detail {

//! Throws InvalidInput "mesh file 'PATH': WHY".
[[noreturn]] void mesh_file_error(const std::string& path, const std::string& why);

//! Throws InvalidInput "mesh file 'PATH': face FACE has SIZE vertices; only triangle meshes are
//! supported".
[[noreturn]] void not_a_triangle(const std::string& path, std::size_t face, const std::string& size);

//! Throws InvalidInput "mesh file 'PATH': face FACE has SIZE vertices (a face needs at least three)".
[[noreturn]] void too_few_corners(const std::string& path, std::size_t face, const std::string& size);

//! A word of a file as it may appear in a message: at most 32 characters, bytes that are not
//! printable ASCII shown as '?'.
std::string printable(const std::string& word);

//! "the file has N vertices (numbered FIRST to FIRST+N-1)", or "the file has no vertices".
std::string vertex_range(std::uintmax_t n, std::uintmax_t first);

//! Reads an OFF file (ASCII or binary) of the given contents.  Every face has at least three
//! vertices (a smaller one is refused); the soup's indices are as in the file, a negative one
//! stored as its two's complement (the caller reports it as negative).  Index range, repeated
//! vertices, finiteness and the presence of faces are left to the caller.  Throws InvalidInput
//! naming path.
PolygonSoup read_off(const std::string& path, const std::string& contents);

//! Both readers test the command's limits (common/run_limits.h: RunLimits::current()) at every
//! vertex and face (ASCII OFF) or element (PLY) and throw RunStopped once they have passed.
//!
//! Reads a PLY file (ASCII or binary) of the given contents, with the same guarantees as read_off.
//! Throws InvalidInput naming path.
PolygonSoup read_ply(const std::string& path, const std::string& contents);

//! Reads an STL file (binary or ASCII) of the given contents into an indexed soup: corners with
//! exactly equal coordinates (-0 and +0 equal) become one point, the points numbered in the order
//! of their first appearance, the triangles in the file's order with their corners' order.  The
//! file is binary when it has at least 84 bytes and its size is 84 + 50·N for the count N at byte
//! 80, whatever its first bytes; otherwise it must be ASCII (begin with "solid", after blanks).
//! A binary count is checked against the size before anything is allocated.  Throws InvalidInput
//! naming path for a truncated or corrupt file (a size that fits neither layout, a malformed
//! facet) and for a NaN or infinite coordinate; tests the command's limits at every triangle as
//! the other readers do.  A triangle with two equal corners is left to the caller (who refuses it
//! as a face that repeats a vertex), and so is an empty file of no triangles.
PolygonSoup read_stl(const std::string& path, const std::string& contents);

}  // namespace delmesh::detail
