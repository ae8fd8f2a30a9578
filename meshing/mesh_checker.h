#pragma once
//! \file mesh_checker.h
//! An independent checker: everything is computed from the mesh alone (components, Euler
//! characteristic and genus per component, closed / manifold / orientable, minimum angle,
//! maximum radius-edge ratio, maximum roughness), never from the mesher's state.

#include <nlohmann/json.hpp>
#include <vector>

#include "meshing/surface_mesh.h"

namespace delmesh {

struct MeshReport {
  std::size_t vertices = 0, edges = 0, triangles = 0;
  int components = 0;
  int euler_characteristic = 0;
  std::vector<int> genus_per_component;  //!< sorted ascending; −1 where not a closed surface
  bool closed = false;                   //!< every edge has exactly two incident triangles
  bool manifold = false;                 //!< closed, and every vertex link is one cycle
  bool orientable = false;               //!< consistently oriented triangles exist
  double min_angle_deg = 0;
  double max_radius_edge_ratio = 0;      //!< circumradius / shortest edge
  double max_roughness_rad = 0;          //!< π − dihedral angle, over interior edges
};

//! Checks a triangle soup given as points and index triples (duplicates are not merged).
MeshReport check_mesh(const std::vector<Point3>& points,
                      const std::vector<std::array<std::size_t, 3>>& triangles);
//! Checks a Surface_mesh (its faces as a soup).
MeshReport check_mesh(const SurfaceMesh& mesh);

nlohmann::json to_json(const MeshReport& report);

}  // namespace delmesh
