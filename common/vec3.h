#pragma once
//! \file vec3.h
//! A point or a vector of R³ as three doubles, in world coordinates: the type of the solvers'
//! query geometry (solvers/query_geometry.h), the surface oracle (meshing/core/surface_oracle.h) and
//! the Voronoi constructions (meshing/voronoi/voronoi_geometry.h).

#include <array>

namespace delmesh {

using Vec3 = std::array<double, 3>;

}  // namespace delmesh
