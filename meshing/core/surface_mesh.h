#pragma once
//! \file surface_mesh.h
//! The output mesh type: a CGAL Surface_mesh over exact-predicates / inexact-constructions points.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

namespace delmesh {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point3 = Kernel::Point_3;
using Vector3 = Kernel::Vector_3;
using SurfaceMesh = CGAL::Surface_mesh<Point3>;

}  // namespace delmesh
