#pragma once
//! \file mesh_soup.h
//! The soups a mesh file is read into (meshing/inputs/mesh_io.h, meshing/inputs/detail/mesh_readers.h): points
//! and faces as the file gives them, nothing merged or reordered.

#include <array>
#include <cstddef>
#include <vector>

#include "meshing/core/surface_mesh.h"

namespace delmesh {

//! A triangle soup as read from a file: points and index triples, nothing merged or reordered.
struct TriangleSoup {
  std::vector<Point3> points;
  std::vector<std::array<std::size_t, 3>> triangles;
};

//! A polygon soup as read from a file, nothing merged or reordered: face f has the vertex indices
//! corners[offsets[f]], …, corners[offsets[f + 1] − 1], at least three of them (offsets holds
//! faces() + 1 entries, the first 0).  Flat, so that its memory is a small multiple of the file's.
struct PolygonSoup {
  std::vector<Point3> points;
  std::vector<std::size_t> corners;
  std::vector<std::size_t> offsets{0};
  std::size_t faces() const { return offsets.size() - 1; }
  std::size_t face_size(std::size_t f) const { return offsets[f + 1] - offsets[f]; }
  //! The first of face f's face_size(f) vertex indices.
  const std::size_t* face(std::size_t f) const { return corners.data() + offsets[f]; }
  //! The faces as index lists (what CGAL's polygon-soup functions take).
  std::vector<std::vector<std::size_t>> polygons() const {
    std::vector<std::vector<std::size_t>> out;
    out.reserve(faces());
    for (std::size_t f = 0; f < faces(); ++f) out.emplace_back(face(f), face(f) + face_size(f));
    return out;
  }
};

}  // namespace delmesh
